#!/usr/bin/env python3
"""Stop 29: the map tracker's rendered benchmark before and after the new-point changes.

Before: stop 28's run (../2026-12-04f/dynbench_map_tracker.json, code at 0da93e7). After: this
stop's run of the same cells (dynbench_map_tracker.json here). Per scenario, mask and screen:
ATE and RPE, mean over the 5 seeds, before and after, and the per-seed change (after minus
before) as mean, smallest and largest; then the cells that moved most and the lost frames.
Run: python3 before_after.py [BEFORE.json AFTER.json]
"""
import json
import os
import re
import statistics as st
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCREENS = ["fixed", "chi2", "quantile", "mad", "magnitude", "default"]


def cells(path):
    """{(scenario, mask, screen, seed): metrics}"""
    out = {}
    for cell in json.load(open(path))["cells"]:
        scenario, seed, mask, screen = re.fullmatch(r"(.+?)_s(\d+)_(.+)_([^_]+)",
                                                    cell["id"]).groups()
        out[(scenario, mask, screen, int(seed))] = cell["metrics"]
    return out


def tracked(metrics):
    return metrics["frames_tracked"] / metrics["frames"]


def main():
    before_path = sys.argv[1] if len(sys.argv) > 2 else os.path.join(
        HERE, "..", "2026-12-04f", "dynbench_map_tracker.json")
    after_path = sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "dynbench_map_tracker.json")
    before, after = cells(before_path), cells(after_path)
    common = sorted(set(before) & set(after))
    print(f"{len(common)} cells in both runs ({len(before)} before, {len(after)} after)\n")
    print("| scenario | mask | screen | ATE before [cm] | after | change per seed (min, max) "
          "| RPE before [mm/frame] | after | frames tracked before / after [%] |")
    print("|---|---|---|---:|---:|---|---:|---:|---|")
    rows = sorted({k[:3] for k in common},
                  key=lambda r: (r[0], r[1], SCREENS.index(r[2]) if r[2] in SCREENS else -1))
    for row in rows:
        seeds = sorted(k[3] for k in common if k[:3] == row)
        b = [100 * before[row + (s,)]["ate_rmse_m"] for s in seeds]
        a = [100 * after[row + (s,)]["ate_rmse_m"] for s in seeds]
        rb = [1000 * before[row + (s,)]["rpe_trans_m_per_frame"] for s in seeds]
        ra = [1000 * after[row + (s,)]["rpe_trans_m_per_frame"] for s in seeds]
        tb = [100 * tracked(before[row + (s,)]) for s in seeds]
        ta = [100 * tracked(after[row + (s,)]) for s in seeds]
        d = [y - x for x, y in zip(b, a)]
        print(f"| {row[0]} | {row[1]} | {row[2]} | {st.mean(b):.2f} | {st.mean(a):.2f} | "
              f"{st.mean(d):+.2f} ({min(d):+.2f}, {max(d):+.2f}) | {st.mean(rb):.2f} | "
              f"{st.mean(ra):.2f} | {st.mean(tb):.1f} / {st.mean(ta):.1f} |")
    moved = sorted(common, key=lambda k: abs(after[k]["ate_rmse_m"] - before[k]["ate_rmse_m"]),
                   reverse=True)
    print("\nThe 12 cells whose ATE moved most [cm]:\n")
    for k in moved[:12]:
        print(f"- {k[0]} seed {k[3]} {k[1]} {k[2]}: {100 * before[k]['ate_rmse_m']:.2f} -> "
              f"{100 * after[k]['ate_rmse_m']:.2f}")
    for name, run in (("before", before), ("after", after)):
        lost = [k for k in common if tracked(run[k]) < 1.0]
        print(f"\nCells with lost frames, {name}: {len(lost)} of {len(common)}")


if __name__ == "__main__":
    main()
