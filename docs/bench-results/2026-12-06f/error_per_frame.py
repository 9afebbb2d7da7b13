#!/usr/bin/env python3
"""Per frame, how far a run's pose is from the ground truth's, both taken relative to their first
frame (no alignment: what the tracker believes against what happened), and the rough pose's
source (stats.csv: 'constant-velocity' marks the frames whose rough pose was the prediction).

usage: error_per_frame.py GROUNDTRUTH.txt FIRST LAST CELL_DIR...
"""
import csv
import sys

import numpy as np
from scipy.spatial.transform import Rotation


def poses(path):
    out = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            v = [float(x) for x in line.split()[:8]]
            T = np.eye(4)
            T[:3, :3] = Rotation.from_quat(v[4:8]).as_matrix()
            T[:3, 3] = v[1:4]
            out[v[0]] = T
    return out


def main(gt_path, first, last, cells):
    gt = poses(gt_path)
    stamps = np.array(sorted(gt))
    nearest = lambda t: gt[stamps[np.abs(stamps - t).argmin()]]
    for cell in cells:
        est = poses(cell + "/trajectory.txt")
        times = sorted(est)
        with open(cell + "/stats.csv") as f:
            source = [row["rough_pose"] for row in csv.DictReader(f)]
        g0, e0 = nearest(times[0]), est[times[0]]
        row = []
        for i in range(int(first), int(last) + 1):
            g = np.linalg.inv(g0) @ nearest(times[i])
            e = np.linalg.inv(e0) @ est[times[i]]
            cm = 100 * np.linalg.norm((np.linalg.inv(g) @ e)[:3, 3])
            row.append(f"{i}:{cm:.1f}{'P' if source[i] == 'constant-velocity' else ''}")
        print(f"{cell}: [cm] per frame, P = the prediction was the rough pose\n  " + " ".join(row))


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:])
