"""Concatenates the cells of hbos-dynbench outputs (different seeds, the same grid otherwise) into
one, for standing.py over every seed. usage: python3 merge_seed_blocks.py OUT.json IN.json..."""
import json
import sys

merged = json.load(open(sys.argv[2]))
for path in sys.argv[3:]:
    merged["cells"] += json.load(open(path))["cells"]
json.dump(merged, open(sys.argv[1], "w"))
