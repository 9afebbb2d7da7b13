"""Tables for docs/results.md, "A static group's shared offset (stop 24)".

Reads dynbench_shared_bias.json (this stop: the guard allowing for the offset static
neighbours share) and ../2026-12-04/dynbench_guard.json (stop 23: the guard without it), pairs
cells by id (scenario, seed, mask, screen) and prints:
  1. eroded rows: mean ATE per screen, before and after, and the paired change;
  2. boxes rows (the person fully inside its box: no dynamic match left): mean ATE per screen
     and the default minus each screen, paired by seed.
Run: python3 compare_shared_bias.py
"""
import json
import os
import statistics as st

HERE = os.path.dirname(os.path.abspath(__file__))
SCREENS = ["default", "chi2", "fixed", "quantile", "mad"]
SEEDS = [1, 2, 3, 4, 5]


def load(path):
    with open(path) as f:
        return {c["id"]: c["metrics"] for c in json.load(f)["cells"]}


def ate_cm(cells, scenario, mask, screen):
    return [100 * cells[f"{scenario}_s{s}_{mask}_{screen}"]["ate_rmse_m"] for s in SEEDS]


def mean_sd(values):
    return f"{st.mean(values):.2f} ± {st.stdev(values):.2f}"


def main():
    after = load(os.path.join(HERE, "dynbench_shared_bias.json"))
    before = load(os.path.join(HERE, "..", "2026-12-04", "dynbench_guard.json"))
    print("Eroded mask, ATE RMSE [cm]: stop 23 guard -> with the shared offset (paired change; seeds it changed)\n")
    print("| scenario | " + " | ".join(SCREENS) + " |")
    print("|---|" + "---|" * len(SCREENS))
    for scenario in ["walking_xyz", "walking_rpy"]:
        row = []
        for screen in SCREENS:
            b = ate_cm(before, scenario, "eroded", screen)
            a = ate_cm(after, scenario, "eroded", screen)
            d = [x - y for x, y in zip(a, b)]
            changed = sum(1 for x in d if abs(x) > 0.005)
            row.append(f"{st.mean(b):.2f} -> {st.mean(a):.2f} ({st.mean(d):+.2f}; {changed})")
        print(f"| {scenario} | " + " | ".join(row) + " |")
    print("\nBoxes mask (no dynamic match left), ATE RMSE [cm], mean ± sd over seeds\n")
    print("| scenario | " + " | ".join(SCREENS) + " |")
    print("|---|" + "---:|" * len(SCREENS))
    for scenario in ["walking_xyz", "walking_rpy"]:
        print(f"| {scenario} | " + " | ".join(mean_sd(ate_cm(after, scenario, "boxes", s)) for s in SCREENS) + " |")
    print("\nBoxes mask: the default minus each screen, paired by seed [cm] (seeds where the default is lower)\n")
    print("| scenario | " + " | ".join(SCREENS[1:]) + " |")
    print("|---|" + "---|" * (len(SCREENS) - 1))
    for scenario in ["walking_xyz", "walking_rpy"]:
        base = ate_cm(after, scenario, "boxes", "default")
        row = []
        for screen in SCREENS[1:]:
            d = [x - y for x, y in zip(base, ate_cm(after, scenario, "boxes", screen))]
            row.append(f"{st.mean(d):+.2f} ± {st.stdev(d):.2f} ({sum(1 for x in d if x < 0)})")
        print(f"| {scenario} | " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
