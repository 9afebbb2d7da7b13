"""Per screen, the mean ATE [cm] and RPE [mm/frame] over the same (scenario, seed, mask) runs of two
hbos-dynbench outputs (the scenes with the scenarios' two people, then with three), split into
masked and unmasked runs; and per output, how many runs the default's ATE is lower than each other
screen's, with a two-sided Wilcoxon signed-rank p.
usage: python3 two_and_three_people.py two_people.json three_people.json"""
import json
import statistics
import sys
from collections import defaultdict

from scipy.stats import wilcoxon


def load(path):
    runs = defaultdict(dict)
    for cell in json.load(open(path))["cells"]:
        if "metrics" not in cell:
            continue
        run, screen = cell["id"].rsplit("_", 1)
        m = cell["metrics"]
        runs[run][screen] = (100 * m["ate_rmse_m"], 1000 * m["rpe_trans_m_per_frame"])
    return runs


def main():
    two, three = load(sys.argv[1]), load(sys.argv[2])
    screens = sorted({s for r in three.values() for s in r})
    for label, masked in (("with a mask", True), ("without a mask", False)):
        runs = [r for r in sorted(three) if r in two and (("_none" not in r) == masked)
                and all(s in three[r] and s in two[r] for s in screens)]
        if not runs:
            continue
        print(f"\n{label}: {len(runs)} runs")
        print(f"{'screen':10s} {'ATE 2p':>8s} {'ATE 3p':>8s} {'RPE 2p':>8s} {'RPE 3p':>8s}"
              "   default lower (2p)   default lower (3p)")
        for s in screens:
            a2 = [two[r][s][0] for r in runs]
            a3 = [three[r][s][0] for r in runs]
            e2 = [two[r][s][1] for r in runs]
            e3 = [three[r][s][1] for r in runs]
            line = (f"{s:10s} {statistics.mean(a2):8.3f} {statistics.mean(a3):8.3f} "
                    f"{statistics.mean(e2):8.3f} {statistics.mean(e3):8.3f}")
            if s != "default":
                for data in (two, three):
                    d = [data[r]["default"][0] for r in runs]
                    o = [data[r][s][0] for r in runs]
                    lower = sum(x < y for x, y in zip(d, o))
                    p = wilcoxon(d, o).pvalue if any(x != y for x, y in zip(d, o)) else 1.0
                    line += f"   {lower:3d} of {len(runs)} p={p:.2g}"
            print(line)


main()
