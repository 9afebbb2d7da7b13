#!/usr/bin/env python3
"""The default screen's runs without and with the rough pose's prediction limit, paired by cell.

Each argument pair is a dynbench output folder without the limit and one with it (the same
cells). For every cell both run: ATE [cm], and the frames whose rough pose is the prediction
rather than RANSAC's (stats.csv's rough_pose column; it counts the frames where RANSAC was not
tried as well, so the difference between the two runs is what the limit added). Then per pair:
runs the same to the bit, lower, higher, the largest rise, runs lost (ATE > 5 cm) and the
Wilcoxon signed-rank p over the runs that differ.

usage: prediction_limit_paired.py LABEL OFF_DIR ON_DIR [LABEL OFF_DIR ON_DIR ...]
"""
import csv
import json
import os
import sys

from scipy.stats import wilcoxon

LOST_CM = 5.0


def cells(folder):
    with open(os.path.join(folder, "dynbench.json")) as f:
        return {c["id"]: 100 * c["metrics"]["ate_rmse_m"] for c in json.load(f)["cells"]}


def prediction_frames(folder, cell):
    with open(os.path.join(folder, "cells", cell, "stats.csv")) as f:
        return sum(row["rough_pose"] == "constant-velocity" for row in csv.DictReader(f))


def compare(label, off_dir, on_dir):
    off, on = cells(off_dir), cells(on_dir)
    ids = sorted(set(off) & set(on))
    print(f"## {label}: {len(ids)} runs ({off_dir} -> {on_dir})")
    print("cell | ATE without [cm] | ATE with [cm] | prediction frames without / with")
    same = lower = higher = 0
    worst_rise, worst_cell = 0.0, "-"
    diffs = []
    for k in ids:
        a, b = off[k], on[k]
        fa, fb = prediction_frames(off_dir, k), prediction_frames(on_dir, k)
        if a == b:
            same += 1
        else:
            diffs.append(b - a)
            lower += b < a
            higher += b > a
            if b - a > worst_rise:
                worst_rise, worst_cell = b - a, k
            print(f"{k} | {a:.3f} | {b:.3f} | {fa} / {fb}")
    lost_off = [k for k in ids if off[k] > LOST_CM]
    lost_on = [k for k in ids if on[k] > LOST_CM]
    p = wilcoxon(diffs).pvalue if len(diffs) >= 2 else float("nan")
    mean_off = sum(off[k] for k in ids) / len(ids)
    mean_on = sum(on[k] for k in ids) / len(ids)
    print(f"same to the bit {same}, lower {lower}, higher {higher} (Wilcoxon p over the changed "
          f"runs {p:.2g}); largest rise {worst_rise:.3f} cm ({worst_cell}); mean ATE "
          f"{mean_off:.3f} -> {mean_on:.3f} cm")
    print(f"lost (ATE > {LOST_CM} cm) without: {lost_off or 'none'}; with: {lost_on or 'none'}\n")


def main(args):
    if len(args) == 0 or len(args) % 3:
        sys.exit(__doc__)
    for i in range(0, len(args), 3):
        compare(*args[i:i + 3])


if __name__ == "__main__":
    main(sys.argv[1:])
