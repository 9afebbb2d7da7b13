"""Mean rank by ATE among a fixed set of screens, from hbos-dynbench's dynbench.json: the runs
(scenario, seed, mask) where every listed screen ran, split into masked and unmasked runs; ties
share their ranks. Also each screen's mean ATE over those runs and, against the default, how
many runs it beat (lower ATE) and a two-sided Wilcoxon signed-rank p.
Lets runs with eight screens be compared with older ones that had six.
usage: python3 ranks_among.py dynbench.json [screen,screen,...]   (default: the six of stops 33-35)
"""
import json
import sys
from collections import defaultdict

from scipy.stats import rankdata, wilcoxon


def main():
    data = json.load(open(sys.argv[1]))
    screens = (sys.argv[2] if len(sys.argv) > 2 else "magnitude,quantile,mad,default,chi2,fixed").split(",")
    ate = defaultdict(dict)
    for cell in data["cells"]:
        if "metrics" not in cell:
            continue
        scenario_seed_mask, screen = cell["id"].rsplit("_", 1)
        ate[scenario_seed_mask][screen] = 100 * cell["metrics"]["ate_rmse_m"]
    for label, masked in (("with a mask", True), ("without a mask", False)):
        runs = [k for k, v in sorted(ate.items())
                if all(s in v for s in screens) and (("_none" not in k) == masked)]
        if not runs:
            continue
        ranks = defaultdict(float)
        for run in runs:
            for s, r in zip(screens, rankdata([ate[run][s] for s in screens])):
                ranks[s] += r / len(runs)
        order = sorted(screens, key=lambda s: ranks[s])
        print(f"{label}, {len(runs)} runs. Mean rank by ATE among {len(screens)}: "
              + ", ".join(f"{s} {ranks[s]:.2f}" for s in order))
        print("| screen | mean rank | mean ATE [cm] | default lower | default higher | Wilcoxon p |")
        print("|---|---:|---:|---:|---:|---:|")
        for s in order:
            mean = sum(ate[r][s] for r in runs) / len(runs)
            if s == "default":
                print(f"| {s} | {ranks[s]:.2f} | {mean:.3f} | | | |")
                continue
            d = [ate[r]["default"] - ate[r][s] for r in runs]
            lower = sum(x < 0 for x in d)
            higher = sum(x > 0 for x in d)
            p = wilcoxon(d).pvalue if any(d) else 1.0
            print(f"| {s} | {ranks[s]:.2f} | {mean:.3f} | {lower} | {higher} | {p:.3g} |")
        print()


if __name__ == "__main__":
    main()
