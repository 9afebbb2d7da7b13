"""How far the ground truth's frame-to-frame motion departs from constant velocity
(docs/results.md, "Newborn tracks earn no trust", item 9).

For a rendered sequence (hbos-render output: rgb.txt and groundtruth.txt), the camera poses at
the colour images' stamps (nearest ground-truth pose), the relative motions T_k = P_{k-1}^-1 P_k,
and per frame the translation of T_{k-1}^-1 T_k: what a constant-velocity model misses. Prints
its median, 90th and 99th percentiles and maximum in mm.
Run: python3 constant_velocity_departure.py RENDER_CACHE/walking_rpy_seed4_300f
"""
import os
import sys

import numpy as np
from scipy.spatial.transform import Rotation


def rows(path):
    return [line.split() for line in open(path) if line.strip() and not line.startswith("#")]


def main():
    folder = sys.argv[1]
    gt = np.array([[float(x) for x in r] for r in rows(os.path.join(folder, "groundtruth.txt"))])
    stamps = [float(r[0]) for r in rows(os.path.join(folder, "rgb.txt"))]
    poses = []
    for stamp in stamps:
        g = gt[np.argmin(abs(gt[:, 0] - stamp))]
        P = np.eye(4)
        P[:3, :3] = Rotation.from_quat(g[4:8]).as_matrix()
        P[:3, 3] = g[1:4]
        poses.append(P)
    motion = [np.linalg.inv(a) @ b for a, b in zip(poses, poses[1:])]
    departure = [1000 * np.linalg.norm((np.linalg.inv(a) @ b)[:3, 3])
                 for a, b in zip(motion, motion[1:])]
    p50, p90, p99 = np.percentile(departure, [50, 90, 99])
    print(f"{folder}: departure from constant velocity [mm]: median {p50:.1f}, "
          f"90th {p90:.1f}, 99th {p99:.1f}, max {max(departure):.1f}")


if __name__ == "__main__":
    main()
