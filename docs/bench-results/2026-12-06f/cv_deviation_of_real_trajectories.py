#!/usr/bin/env python3
"""How far a real camera lands from the constant-velocity prediction, frame to frame at 30 Hz.

For each ground-truth trajectory (TUM format: stamp tx ty tz qx qy qz qw), poses are
interpolated at 30 frames/s (positions linearly, orientations by slerp); the prediction of frame
k is T[k-1] * (T[k-2]^-1 T[k-1]), the deviation T_pred^-1 T[k]. Prints percentiles and the
maximum of its translation [cm] and rotation angle [deg]. Mocap noise counts in too, so these
are upper bounds of what the camera itself did.

usage: cv_deviation_of_real_trajectories.py GROUNDTRUTH.txt...
"""
import sys

import numpy as np
from scipy.spatial.transform import Rotation, Slerp


def load(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            rows.append([float(v) for v in line.replace(",", " ").split()[:8]])
    a = np.array(rows)
    return a[np.concatenate([[True], np.diff(a[:, 0]) > 0])]  # strictly increasing stamps


def at_30hz(a):
    t = a[:, 0]
    ts = np.arange(t[0], t[-1], 1.0 / 30.0)
    T = np.tile(np.eye(4), (len(ts), 1, 1))
    T[:, :3, :3] = Slerp(t, Rotation.from_quat(a[:, 4:8]))(ts).as_matrix()
    T[:, :3, 3] = np.stack([np.interp(ts, t, a[:, i]) for i in (1, 2, 3)], 1)
    return T


def main(paths):
    print("trajectory | frames | translation cm: p99 / p99.9 / max | rotation deg: p99 / max")
    for path in paths:
        T = at_30hz(load(path))
        inv = np.linalg.inv
        cm, deg = [], []
        for k in range(2, len(T)):
            predicted = T[k - 1] @ (inv(T[k - 2]) @ T[k - 1])
            d = inv(predicted) @ T[k]
            cm.append(100 * np.linalg.norm(d[:3, 3]))
            deg.append(np.degrees(Rotation.from_matrix(d[:3, :3]).magnitude()))
        cm, deg = np.array(cm), np.array(deg)
        name = "/".join(path.split("/")[-2:])
        print(f"{name} | {len(cm)} | {np.percentile(cm, 99):.2f} / {np.percentile(cm, 99.9):.2f} / "
              f"{cm.max():.2f} | {np.percentile(deg, 99):.2f} / {deg.max():.2f}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
