"""Keeps the cells of one seed block of a dynbench JSON, for standing.py per block.
usage: python3 seed_block.py IN.json OUT.json FIRST LAST   (seeds FIRST..LAST, inclusive)"""
import json
import re
import sys

data = json.load(open(sys.argv[1]))
first, last = int(sys.argv[3]), int(sys.argv[4])
data["cells"] = [c for c in data["cells"] if first <= int(re.search(r"_s(\d+)_", c["id"]).group(1)) <= last]
json.dump(data, open(sys.argv[2], "w"))
