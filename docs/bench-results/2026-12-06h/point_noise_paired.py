"""Pairs runs with the map tracker's --point-noise against the same runs without it (same
renders, same screen): per screen, how many runs have a lower / higher ATE and RPE, the means, a
two-sided Wilcoxon signed-rank p, the worst run and (ATE) the runs over 5 cm. Optionally writes a dynbench-like JSON whose
cells are the runs without the option, with those of the screens run with it replaced, for
standing.py.
usage: python3 point_noise_paired.py without.json with_dir_or_json [merged_out.json]"""
import json
import os
import statistics
import sys
from collections import defaultdict

from scipy.stats import wilcoxon


def load_cells(path):
    if os.path.isdir(path):
        cells = []
        for name in sorted(os.listdir(os.path.join(path, "cells"))):
            f = os.path.join(path, "cells", name, "cell.json")
            if os.path.exists(f):
                cell = json.load(open(f))
                cell["id"] = name  # a cell folder is named by its id
                cells.append(cell)
        return [c for c in cells if "metrics" in c]
    return [c for c in json.load(open(path))["cells"] if "metrics" in c]


def main():
    without = {c["id"]: c for c in load_cells(sys.argv[1])}
    with_ = {c["id"]: c for c in load_cells(sys.argv[2])}
    by_screen = defaultdict(list)
    for k in sorted(with_):
        if k in without:
            by_screen[k.rsplit("_", 1)[1]].append(k)
    for name, metric in (("ATE [cm]", lambda m: 100 * m["ate_rmse_m"]),
                         ("RPE [mm/frame]", lambda m: 1000 * m["rpe_trans_m_per_frame"])):
        print(f"\n## {name}: without -> with --point-noise")
        for screen, keys in sorted(by_screen.items()):
            for label, masked in (("masked", True), ("no mask", False), ("all", None)):
                ks = [k for k in keys if masked is None or (("_none_" not in k) == masked)]
                if not ks:
                    continue
                a = [metric(without[k]["metrics"]) for k in ks]
                b = [metric(with_[k]["metrics"]) for k in ks]
                lower = sum(y < x for x, y in zip(a, b))
                higher = sum(y > x for x, y in zip(a, b))
                p = wilcoxon(a, b).pvalue if any(x != y for x, y in zip(a, b)) else 1.0
                worst = max(range(len(ks)), key=lambda i: b[i])
                lost = f"; over 5 cm {sum(x > 5 for x in a)} -> {sum(y > 5 for y in b)}" if name.startswith("ATE") else ""
                print(f"  {screen:10s} {label:8s} {len(ks):3d} runs: lower on {lower:2d}, higher on "
                      f"{higher:2d}; mean {statistics.mean(a):.3f} -> {statistics.mean(b):.3f} "
                      f"(p = {p:.2g}); worst with: {ks[worst]} {b[worst]:.2f} "
                      f"(without {a[worst]:.2f}){lost}")
    if len(sys.argv) > 3:
        merged = dict(without)
        merged.update({k: v for k, v in with_.items() if k in without})
        json.dump({"cells": list(merged.values())}, open(sys.argv[3], "w"))


if __name__ == "__main__":
    main()
