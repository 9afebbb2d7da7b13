"""Table for docs/results.md, "Two scenarios never run before (stop 27)".

Reads dynbench_new_scenarios.json (hbos-dynbench --scenarios walking_halfsphere,walking_static
--variants eroded,person_missed --every-screen-unmasked --seeds 1,2,3,4,5), or the file named on
the command line. For every scenario and mask in it, and every screen: ATE and RPE (mean ± sd
over the seeds), the default's paired difference to the screen (default minus screen, mean ± sd;
on how many seeds the default is lower), the dynamic matches kept and the statics dropped. Then
which screen has the lowest mean ATE and RPE per row.
Run: python3 compare_new_scenarios.py [FILE.json]
"""
import collections
import json
import os
import re
import statistics as st
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCREENS = ["none", "paper", "fixed", "chi2", "quantile", "mad", "magnitude", "default"]
METRICS = {"ate": ("ate_rmse_m", 100), "rpe": ("rpe_trans_m_per_frame", 1000),
           "dyn": ("dynamic_kept_share", 100), "sta": ("static_dropped_share", 100)}


def by_row(path):
    """{(scenario, mask): {screen: {seed: metrics}}}"""
    rows = collections.defaultdict(lambda: collections.defaultdict(dict))
    with open(path) as f:
        for cell in json.load(f)["cells"]:
            # id: <scenario>_s<seed>_<mask>_<screen>; screen names hold no underscore
            scenario, seed, mask, screen = re.fullmatch(r"(.+?)_s(\d+)_(.+)_([^_]+)",
                                                        cell["id"]).groups()
            rows[(scenario, mask)][screen][int(seed)] = cell["metrics"]
    return rows


def values(seeds_metrics, key):
    """Per seed; a share is None where a run had no match of that kind (left out)."""
    name, scale = METRICS[key]
    v = [seeds_metrics[s][name] for s in sorted(seeds_metrics)]
    return [scale * x for x in v if x is not None]


def mean(v):
    return f"{st.mean(v):.1f}" if v else "-"


def paired(own, other):
    d = [a - b for a, b in zip(own, other)]
    return f"{st.mean(d):+.2f} ± {st.stdev(d):.2f} ({sum(x < 0 for x in d)} of {len(d)})"


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "dynbench_new_scenarios.json")
    rows = by_row(path)
    print("| scenario | mask | screen | ATE [cm] | default - screen, ATE (lower on) | "
          "RPE [mm/frame] | default - screen, RPE (lower on) | dynamic kept [%] | "
          "statics dropped [%] |")
    print("|---|---|---|---|---|---|---|---|---|")
    best = []
    for (scenario, mask), screens in sorted(rows.items()):
        own = {k: values(screens["default"], k) for k in ("ate", "rpe")}
        means = {}
        for screen in [s for s in SCREENS if s in screens]:
            v = {k: values(screens[screen], k) for k in METRICS}
            means[screen] = (st.mean(v["ate"]), st.mean(v["rpe"]))
            mine = screen == "default"
            print(f"| {scenario} | {mask} | {screen} | {st.mean(v['ate']):.2f} ± "
                  f"{st.stdev(v['ate']):.2f} | {'—' if mine else paired(own['ate'], v['ate'])} | "
                  f"{st.mean(v['rpe']):.2f} ± {st.stdev(v['rpe']):.2f} | "
                  f"{'—' if mine else paired(own['rpe'], v['rpe'])} | "
                  f"{mean(v['dyn'])} | {mean(v['sta'])} |")
        ate_best = min(means, key=lambda s: means[s][0])
        rpe_best = min(means, key=lambda s: means[s][1])
        best.append(f"  {scenario} / {mask}: lowest ATE {ate_best} ({means[ate_best][0]:.2f}), "
                    f"lowest RPE {rpe_best} ({means[rpe_best][1]:.2f}); default "
                    f"{means['default'][0]:.2f} / {means['default'][1]:.2f}")
    print()
    print("Lowest means per row:")
    print("\n".join(best))


if __name__ == "__main__":
    main()
