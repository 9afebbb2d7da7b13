#!/usr/bin/env python3
"""Stop 29: where the map tracker's frame-to-frame error (RPE) comes from, on one run.

Reads an hbos-slam output folder (trajectory.txt; with --tracker map also map_frames.csv) and its
rendered sequence's ground truth. Prints the RPE over all steps, over the steps into a keyframe
and the step after one, and the rest; then the ATE, the lag-1 correlation of the aligned
position errors (1: each frame inherits the last one's error, as a chain of frame-to-frame steps
does; 0: independent errors, as poses measured each against a fixed map would be) and sqrt(2) x
the ATE, the RPE that independent errors of the ATE's size would give.
Run: python3 rpe_vs_ate.py SEQUENCE_DIR RUN_DIR
"""
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-12-04f"))
from tum_poses import GroundTruth, load_poses  # noqa: E402


def rms(v):
    return float(np.sqrt(np.mean(np.square(v)))) if len(v) else float("nan")


def main():
    sequence, run = sys.argv[1], sys.argv[2]
    gt = GroundTruth(sequence)
    est = load_poses(os.path.join(run, "trajectory.txt"))
    keyframes_csv = os.path.join(run, "map_frames.csv")
    rows = list(csv.DictReader(open(keyframes_csv))) if os.path.exists(keyframes_csv) else []
    stamps = sorted(est)
    # The absolute errors after a rigid alignment (Umeyama, no scale), as the ATE takes them.
    p = np.array([est[t][:3, 3] for t in stamps])
    q = np.array([gt.at(t)[:3, 3] for t in stamps])
    pc, qc = p - p.mean(0), q - q.mean(0)
    u, _, vt = np.linalg.svd(qc.T @ pc)
    d = np.diag([1, 1, np.sign(np.linalg.det(u @ vt))])
    rotation = u @ d @ vt
    error = (rotation @ pc.T).T - qc  # per frame [m]
    ate = np.linalg.norm(error, axis=1)
    rho = np.sum(error[1:] * error[:-1]) / np.sum(error * error)
    step, keyframe = [], []
    for i, t in enumerate(stamps):
        if i == 0:
            continue
        a = stamps[i - 1]
        e = np.linalg.inv(est[a]) @ est[t]
        g = np.linalg.inv(gt.at(a)) @ gt.at(t)
        step.append(1000 * np.linalg.norm((np.linalg.inv(g) @ e)[:3, 3]))
        keyframe.append(int(rows[i]["keyframe"]) if i < len(rows) else 0)  # none: frame tracker
    step, keyframe = np.array(step), np.array(keyframe)
    after = np.zeros_like(keyframe)
    after[1:] = keyframe[:-1]
    print(f"{run}: {len(step)} steps, {keyframe.sum()} into a keyframe")
    print(f"RPE [mm/frame] RMSE: all {rms(step):.2f}, median {np.median(step):.2f}; into a keyframe "
          f"{rms(step[keyframe == 1]):.2f}, the step after {rms(step[after == 1]):.2f}, the rest "
          f"{rms(step[(keyframe == 0) & (after == 0)]):.2f}")
    print(f"ATE [mm] RMSE: {1000 * rms(ate):.2f}; lag-1 correlation of the position errors "
          f"{rho:.3f}; the RPE that independent errors of this size would give, sqrt(2) x ATE: "
          f"{1000 * np.sqrt(2) * rms(ate):.2f}")


if __name__ == "__main__":
    main()
