"""How far real hand-held cameras depart from constant velocity in one frame at 30 fps
(docs/results.md, "A missed person the rough pose follows: walking_rpy seed 9, traced").

For each ground-truth file given (TUM format: stamp tx ty tz qx qy qz qw), the poses nearest
to a 30 Hz clock, the relative motions T_k = P_{k-1}^-1 P_k, and per frame T_{k-1}^-1 T_k: what
a constant-velocity model misses. Prints the frame-to-frame step and that departure (translation
in mm, rotation in degrees). A file with gaps in its ground truth gives meaningless maxima.
Run: python3 constant_velocity_departure_real.py GROUNDTRUTH.txt [more ...]
"""
import sys

import numpy as np
from scipy.spatial.transform import Rotation


def poses_at_30hz(path):
    g = np.array([[float(x) for x in line.split()] for line in open(path)
                  if line.strip() and not line.startswith("#")])
    clock = np.arange(g[0, 0], g[-1, 0], 1.0 / 30.0)
    index = np.searchsorted(g[:, 0], clock).clip(0, len(g) - 1)
    poses = []
    for i in index:
        P = np.eye(4)
        P[:3, :3] = Rotation.from_quat(g[i, 4:8]).as_matrix()
        P[:3, 3] = g[i, 1:4]
        poses.append(P)
    return poses


def main():
    for path in sys.argv[1:]:
        poses = poses_at_30hz(path)
        motion = [np.linalg.inv(a) @ b for a, b in zip(poses, poses[1:])]
        departure = [np.linalg.inv(a) @ b for a, b in zip(motion, motion[1:])]
        step = np.array([1000 * np.linalg.norm(m[:3, 3]) for m in motion])
        t = np.array([1000 * np.linalg.norm(d[:3, 3]) for d in departure])
        r = np.array([np.degrees(np.linalg.norm(Rotation.from_matrix(d[:3, :3]).as_rotvec()))
                      for d in departure])
        print(f"{path}: {len(t)} frames; step [mm] median {np.median(step):.1f} max {step.max():.1f}; "
              f"departure [mm] 99th {np.percentile(t, 99):.1f} 99.9th {np.percentile(t, 99.9):.1f} "
              f"max {t.max():.1f}; [deg] 99th {np.percentile(r, 99):.2f} max {r.max():.2f}")


if __name__ == "__main__":
    main()
