"""Stop 36: where a map-tracker run drifts, without the SE(3) alignment of the ATE.

Each trajectory is anchored at its first pose on the ground truth (the tracker starts at the
identity), then for every 15th frame prints the position error [cm] and the rotation error [deg]
from the truth, and lists the frames where the two runs' frame-to-frame errors differ most.

    /usr/bin/python3 anchored_drift.py GROUNDTRUTH CELL_A CELL_B

CELL_* are hbos-dynbench cell folders (trajectory.txt, stats.csv).
"""
import csv
import sys

import numpy as np
from scipy.spatial.transform import Rotation


def load(path):
    poses = {}
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        v = line.split()
        poses[float(v[0])] = np.array([float(x) for x in v[1:8]])
    return poses


def matrix(v):
    m = np.eye(4)
    m[:3, :3] = Rotation.from_quat(v[3:7]).as_matrix()
    m[:3, 3] = v[:3]
    return m


def main():
    gt = load(sys.argv[1])
    stamps = np.array(sorted(gt))

    def truth(t):
        return matrix(gt[stamps[np.argmin(abs(stamps - t))]])

    cells = sys.argv[2:4]
    drift, step = [], []
    for cell in cells:
        est = load(cell + "/trajectory.txt")
        keys = sorted(est)
        anchor = truth(keys[0]) @ np.linalg.inv(matrix(est[keys[0]]))
        rows = []
        for k in keys:
            p, g = anchor @ matrix(est[k]), truth(k)
            d = np.linalg.inv(g) @ p
            rows.append((np.linalg.norm(p[:3, 3] - g[:3, 3]) * 100,
                         np.degrees(np.linalg.norm(Rotation.from_matrix(d[:3, :3]).as_rotvec()))))
        drift.append(np.array(rows))
        errors = []
        for a, b in zip(keys[:-1], keys[1:]):
            e = np.linalg.inv(matrix(est[a])) @ matrix(est[b])
            g = np.linalg.inv(truth(a)) @ truth(b)
            d = np.linalg.inv(g) @ e
            errors.append((np.linalg.norm(d[:3, 3]) * 1000,
                           np.degrees(np.linalg.norm(Rotation.from_matrix(d[:3, :3]).as_rotvec()))))
        step.append(np.array(errors))
    print("anchored at frame 0: position error [cm] / rotation error [deg] every 15 frames")
    for name, rows in zip("AB", drift):
        print(name, " ".join(f"{i}:{rows[i, 0]:.2f}/{rows[i, 1]:.2f}" for i in range(0, len(rows), 15)))
    stats = [list(csv.DictReader(open(c + "/stats.csv"))) for c in cells]
    print("\nframes whose frame-to-frame rotation error differs most (A then B):")
    print("frame  trans[mm] rot[deg]  trans[mm] rot[deg]  person matches/kept A  B")
    diff = step[0][:, 1] - step[1][:, 1]
    for i in sorted(np.argsort(-abs(diff))[:16]):
        f = i + 1
        a, b = stats[0][f], stats[1][f]
        print(f"{f:5d} {step[0][i, 0]:9.2f} {step[0][i, 1]:8.3f} {step[1][i, 0]:9.2f} "
              f"{step[1][i, 1]:8.3f}  {a['person_matches']:>4}/{a['person_survivors']:<4} "
              f"{b['person_matches']:>4}/{b['person_survivors']}")


if __name__ == "__main__":
    main()
