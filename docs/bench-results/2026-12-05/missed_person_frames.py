#!/usr/bin/env python3
"""Stop 29: how a person the mask misses takes over the map tracker (walking_rpy seed 5,
person_missed, default screen), frame by frame.

Input: the per-match dump of map_dump.patch (HBOS_MAPDUMP=FILE hbos-slam --tracker map ...), one
line per screened match: frame, point id, frame the point was made at, on the person, kept
screenings, observed x y, predicted x y under the final pose, under the rough pose, point xyz
(world), sigma, kept, lost. For each frame: the matches on the room and on the person, split into
points made in the last 3 frames ("new") and older ones, with the median residual [px/sigma]
under the ground truth, the rough pose and the final pose, and the share the screen kept.
Run: python3 missed_person_frames.py DUMP.csv SEQUENCE_DIR [first last step]
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-12-04f"))
from tum_poses import GroundTruth  # noqa: E402

K = np.array([[535.4, 0, 320.1], [0, 539.2, 247.6], [0, 0, 1]])  # the rendered tum3 camera


def main():
    dump, sequence = sys.argv[1], sys.argv[2]
    first, last, step = (int(x) for x in sys.argv[3:6]) if len(sys.argv) > 5 else (150, 200, 2)
    gt = GroundTruth(sequence)
    a = np.loadtxt(dump, delimiter=",")
    g0 = gt.at(gt.frame_stamps[0])  # the map's world is the first camera
    print("frame | group: matches, median residual [px/sigma] under ground truth / rough / final "
          "pose, share kept")
    for f in range(first, last, step):
        r = a[a[:, 0] == f]
        T = np.linalg.inv(gt.at(gt.frame_stamps[f])) @ g0
        pc = (T[:3, :3] @ r[:, 11:14].T).T + T[:3, 3]
        uv = (K @ pc.T).T
        uv = uv[:, :2] / uv[:, 2:]
        obs, sigma = r[:, 5:7], r[:, 14]
        res = {"gt": np.linalg.norm(obs - uv, axis=1) / sigma,
               "rough": np.linalg.norm(obs - r[:, 9:11], axis=1) / sigma,
               "final": np.linalg.norm(obs - r[:, 7:9], axis=1) / sigma}
        new = f - r[:, 2] <= 3
        person = r[:, 3] == 1
        out = []
        for name, sel in (("room old", ~person & ~new), ("room new", ~person & new),
                          ("person old", person & ~new), ("person new", person & new)):
            if not sel.any():
                out.append(f"{name} 0")
                continue
            med = " / ".join(f"{np.median(res[k][sel]):.1f}" for k in ("gt", "rough", "final"))
            out.append(f"{name} {sel.sum()}: {med}, {r[sel, 15].mean():.2f}")
        print(f"{f} | " + " | ".join(out))


if __name__ == "__main__":
    main()
