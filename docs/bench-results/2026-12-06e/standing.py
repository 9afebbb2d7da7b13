"""The default's standing in one hbos-dynbench output, by ATE and by RPE: mean rank among the
screens present (runs where all ran; ties share ranks), split into masked and unmasked runs; how
many runs the default is lower than each other screen, with a two-sided Wilcoxon signed-rank p;
and the row rule of frontend/standing.hpp (per scenario and mask, the default's mean against the
best other screen's: best when lower or equal, tied when above by at most the larger sample
standard deviation of the two, behind otherwise).
usage: python3 standing.py dynbench.json [screen,screen,...]   (default: every screen present)"""
import json
import re
import statistics
import sys
from collections import defaultdict

from scipy.stats import rankdata, wilcoxon

METRICS = {"ATE [cm]": lambda m: 100 * m["ate_rmse_m"],
           "RPE [mm/frame]": lambda m: 1000 * m["rpe_trans_m_per_frame"]}


def main():
    cells = [c for c in json.load(open(sys.argv[1]))["cells"] if "metrics" in c]
    if len(sys.argv) > 2:
        keep = sys.argv[2].split(",")
        cells = [c for c in cells if c["id"].rsplit("_", 1)[1] in keep]
    for name, metric in METRICS.items():
        runs = defaultdict(dict)
        for c in cells:
            run, screen = c["id"].rsplit("_", 1)
            runs[run][screen] = metric(c["metrics"])
        screens = sorted({s for r in runs.values() for s in r})
        print(f"\n## {name}")
        for label, masked in (("with a mask", True), ("without a mask", False)):
            keys = [k for k in sorted(runs) if all(s in runs[k] for s in screens)
                    and (("_none" not in k) == masked)]
            if not keys:
                continue
            rank = defaultdict(float)
            for k in keys:
                for s, r in zip(screens, rankdata([runs[k][s] for s in screens])):
                    rank[s] += r / len(keys)
            print(f"{label}, {len(keys)} runs")
            for s in sorted(screens, key=lambda s: rank[s]):
                line = f"  {s:10s} rank {rank[s]:.2f}  mean {statistics.mean(runs[k][s] for k in keys):8.3f}"
                if s != "default":
                    d = [runs[k]["default"] for k in keys]
                    o = [runs[k][s] for k in keys]
                    lower = sum(x < y for x, y in zip(d, o))
                    p = wilcoxon(d, o).pvalue if any(x != y for x, y in zip(d, o)) else 1.0
                    line += f"  default lower on {lower} of {len(keys)}, p = {p:.2g}"
                print(line)
        # The row rule.
        rows = defaultdict(lambda: defaultdict(list))
        for k, by in runs.items():
            scenario, _, mask = re.match(r"(.*)_s(\d+)_(.*)$", k).groups()
            for s, v in by.items():
                rows[(scenario, mask)][s].append(v)
        verdicts = defaultdict(int)
        for (scenario, mask), by in sorted(rows.items()):
            if "default" not in by or len(by) < 2:  # no other screen ran in this row
                continue
            d = by["default"]
            best = min((s for s in by if s != "default"), key=lambda s: statistics.mean(by[s]))
            gap = statistics.mean(d) - statistics.mean(by[best])
            spread = max(statistics.stdev(d), statistics.stdev(by[best]))
            v = "best" if gap <= 0 else ("tied" if gap <= spread else "behind")
            verdicts[v] += 1
            print(f"  {scenario:20s} {mask:14s} default {statistics.mean(d):8.3f}  best other "
                  f"{best} {statistics.mean(by[best]):8.3f}  gap {gap:+.3f} spread {spread:.3f}  {v}")
        print("  row rule:", dict(verdicts))


main()
