#!/usr/bin/env python3
"""Stop 28: the cells of hbos-dynbench JSON files that lost frames (a lost frame has no pose, so
the cell's ATE is over the frames it tracked).
Run: python3 lost_frames.py dynbench_map_tracker.json [more.json ...]
"""
import json
import sys

for path in sys.argv[1:]:
    for cell in json.load(open(path))["cells"]:
        m = cell["metrics"]
        if m["frames_tracked"] < m["frames"]:
            print(f"{cell['id']}: {m['frames_tracked']} of {m['frames']} frames tracked, "
                  f"ATE {100 * m['ate_rmse_m']:.2f} cm over them")
