"""Tables for docs/results.md, "The detector's own noise scale (stop 25)".

Reads
  dynbench_min_scale.json                      the default screen with NoiseGate::min_scale
                                               (masks none, eroded, boxes, person_missed; 5 seeds)
  dynbench_person_missed_without_min_scale.json the same binary with min_scale = 0 (a throwaway
                                               switch), person_missed and none
  ../2026-12-04b/dynbench_shared_bias.json     stop 24: every screen, masks none, eroded, boxes
  ../2026-12-04/dynbench_guard.json            stop 23: every screen, person_missed
and prints, per scenario and mask, the default's ATE before and after (paired by seed), its
dynamic and static shares, and the other screens' ATE with the default's paired difference.
The before/after pairs come from one code path: the runs without min_scale reproduce stop 24's
cells bit for bit (checked here on the mask-free cells).
Run: python3 compare_min_scale.py
"""
import json
import os
import statistics as st

HERE = os.path.dirname(os.path.abspath(__file__))
SEEDS = [1, 2, 3, 4, 5]
OTHERS = ["chi2", "fixed", "quantile", "mad"]


def load(*parts):
    with open(os.path.join(HERE, *parts)) as f:
        return {c["id"]: c["metrics"] for c in json.load(f)["cells"]}


def column(cells, scenario, mask, screen, metric, scale=1.0):
    values = [cells[f"{scenario}_s{s}_{mask}_{screen}"][metric] for s in SEEDS]
    return [None if v is None else scale * v for v in values]  # None: no dynamic match


def mean_sd(values):
    return f"{st.mean(values):.2f} ± {st.stdev(values):.2f}"


def main():
    after = load("dynbench_min_scale.json")
    without = load("dynbench_person_missed_without_min_scale.json")
    stop24 = load("..", "2026-12-04b", "dynbench_shared_bias.json")
    stop23 = load("..", "2026-12-04", "dynbench_guard.json")
    for scenario in ["walking_xyz", "walking_rpy"]:
        same = column(without, scenario, "none", "default", "ate_rmse_m") == column(
            stop24, scenario, "none", "default", "ate_rmse_m")
        print(f"{scenario}: runs without min_scale reproduce stop 24's mask-free cells: {same}")
    print()
    print("| scenario | mask | default ATE [cm], before -> after (paired change; lower on) "
          "| dynamic kept [%] | statics dropped [%] | " + " | ".join(OTHERS) + " |")
    print("|---|---|---|---|---|" + "---|" * len(OTHERS))
    for scenario in ["walking_xyz", "walking_rpy"]:
        for mask in ["none", "eroded", "boxes", "person_missed"]:
            before_cells = without if mask == "person_missed" else stop24
            others_cells = stop23 if mask == "person_missed" else stop24
            b = column(before_cells, scenario, mask, "default", "ate_rmse_m", 100)
            a = column(after, scenario, mask, "default", "ate_rmse_m", 100)
            d = [x - y for x, y in zip(a, b)]
            lower = sum(1 for x in d if x < -0.005)
            shares = []
            for metric in ["dynamic_kept_share", "static_dropped_share"]:
                vb = column(before_cells, scenario, mask, "default", metric)
                va = column(after, scenario, mask, "default", metric)
                if any(v is None for v in vb + va):
                    shares.append("-")
                else:
                    shares.append(f"{100 * st.mean(vb):.1f} -> {100 * st.mean(va):.1f}")
            row = [f"{mean_sd(b)} -> {mean_sd(a)} ({st.mean(d):+.2f}; {lower} of 5)"] + shares
            for screen in OTHERS:
                if mask == "none":
                    row.append("-")
                    continue
                o = column(others_cells, scenario, mask, screen, "ate_rmse_m", 100)
                diff = [x - y for x, y in zip(a, o)]
                row.append(f"{mean_sd(o)} ({st.mean(diff):+.2f} ± {st.stdev(diff):.2f})")
            print(f"| {scenario} | {mask} | " + " | ".join(row) + " |")
    print("\nOther screens: stop 24's cells (stop 23's for person_missed); in brackets the "
          "default's paired difference to them, after the change, mean ± sd over the seeds.")


if __name__ == "__main__":
    main()
