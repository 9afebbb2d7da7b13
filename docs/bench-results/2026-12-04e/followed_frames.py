"""Where the default still follows a person without a mask (docs/results.md, stop 27).

For each unmasked default cell of an hbos-dynbench output folder, the frames whose estimated
frame-to-frame translation is more than 10 mm off the ground truth's ("followed"), and for those
frames and the others: the person's share of the matches, the share of the person's matches the
screen kept, and the rough pose's source. Needs the rendered sequences (their groundtruth.txt).
Run: python3 followed_frames.py DYNBENCH_OUT RENDER_CACHE
"""
import csv
import os
import sys

import numpy as np
from scipy.spatial.transform import Rotation


def poses(path):
    out = {}
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        v = [float(x) for x in line.split()]
        T = np.eye(4)
        T[:3, :3] = Rotation.from_quat(v[4:8]).as_matrix()
        T[:3, 3] = v[1:4]
        out[round(v[0], 4)] = T
    return out


def main():
    out_dir, cache = sys.argv[1], sys.argv[2]
    print("| cell | followed frames | person share of matches, followed / other [%] | "
          "person matches kept, followed / other [%] | remembered-statics frames |")
    print("|---|---:|---:|---:|---:|")
    for scenario in ["walking_xyz", "walking_rpy"]:
        for seed in range(1, 6):
            cell = os.path.join(out_dir, "cells", f"{scenario}_s{seed}_none_default")
            est = poses(os.path.join(cell, "trajectory.txt"))
            gt = poses(os.path.join(cache, f"{scenario}_seed{seed}_300f", "groundtruth.txt"))
            gk = np.array(sorted(gt))
            near = lambda t: gt[gk[np.argmin(abs(gk - t))]]
            stamps = sorted(est)
            followed = set()
            for i in range(1, len(stamps)):
                de = np.linalg.inv(est[stamps[i - 1]]) @ est[stamps[i]]
                dg = np.linalg.inv(near(stamps[i - 1])) @ near(stamps[i])
                if np.linalg.norm((np.linalg.inv(dg) @ de)[:3, 3]) > 0.010:
                    followed.add(i)
            rows = list(csv.DictReader(open(os.path.join(cell, "stats.csv"))))
            acc = {True: [0, 0, 0], False: [0, 0, 0]}  # matches, person, person kept
            remembered = 0
            for r in rows:
                f = int(r["frame"])
                if f == 0:
                    continue
                a = acc[f in followed]
                a[0] += int(r["matches"])
                a[1] += int(r["person_matches"])
                a[2] += int(r["person_survivors"])
                remembered += r["rough_pose"] == "ransac-remembered-statics"
            pct = lambda x, y: f"{100 * x / y:.0f}" if y else "-"
            print(f"| {scenario} s{seed} | {len(followed)} | "
                  f"{pct(acc[True][1], acc[True][0])} / {pct(acc[False][1], acc[False][0])} | "
                  f"{pct(acc[True][2], acc[True][1])} / {pct(acc[False][2], acc[False][1])} | "
                  f"{remembered} |")


if __name__ == "__main__":
    main()
