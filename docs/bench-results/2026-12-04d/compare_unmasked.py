"""Table for docs/results.md, "Every screen without a mask (stop 26)".

Reads dynbench_unmasked.json (hbos-dynbench --variants '' --every-screen-unmasked --seeds
1,2,3,4,5: every screen on the rendered walking_xyz and walking_rpy sequences with no mask; or
the file named on the command line, e.g. dynbench_unmasked_history_consensus.json) and
prints, per scenario and screen, ATE and RPE (mean ± sd over the seeds) and the default's paired
difference to each screen (default minus screen, mean ± sd over the seeds; on how many seeds the
default is lower).
Run: python3 compare_unmasked.py [FILE.json]
"""
import json
import os
import statistics as st
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SEEDS = [1, 2, 3, 4, 5]
SCREENS = ["none", "fixed", "chi2", "quantile", "mad", "magnitude", "paper", "default"]


def main():
    name = sys.argv[1] if len(sys.argv) > 1 else "dynbench_unmasked.json"
    with open(os.path.join(HERE, name)) as f:
        cells = {c["id"]: c["metrics"] for c in json.load(f)["cells"]}

    def column(scenario, screen, metric, scale):
        return [scale * cells[f"{scenario}_s{s}_none_{screen}"][metric] for s in SEEDS]

    print("| scenario | screen | ATE [cm] | default - screen, ATE (lower on) | RPE [mm/frame] "
          "| default - screen, RPE (lower on) | dynamic kept [%] | statics dropped [%] |")
    print("|---|---|---|---|---|---|---|---|")
    for scenario in ["walking_xyz", "walking_rpy"]:
        d_ate = column(scenario, "default", "ate_rmse_m", 100)
        d_rpe = column(scenario, "default", "rpe_trans_m_per_frame", 1000)
        for screen in SCREENS:
            ate = column(scenario, screen, "ate_rmse_m", 100)
            rpe = column(scenario, screen, "rpe_trans_m_per_frame", 1000)
            dyn = column(scenario, screen, "dynamic_kept_share", 100)
            sta = column(scenario, screen, "static_dropped_share", 100)

            def paired(a, b):
                d = [x - y for x, y in zip(a, b)]
                return f"{st.mean(d):+.2f} ± {st.stdev(d):.2f} ({sum(x < 0 for x in d)} of 5)"

            same = screen == "default"
            print(f"| {scenario} | {screen} | {st.mean(ate):.2f} ± {st.stdev(ate):.2f} | "
                  f"{'—' if same else paired(d_ate, ate)} | {st.mean(rpe):.2f} ± {st.stdev(rpe):.2f} | "
                  f"{'—' if same else paired(d_rpe, rpe)} | {st.mean(dyn):.1f} | {st.mean(sta):.1f} |")
    print()
    print("Per seed, ATE [cm]:")
    for scenario in ["walking_xyz", "walking_rpy"]:
        for screen in SCREENS:
            v = column(scenario, screen, "ate_rmse_m", 100)
            print(f"  {scenario:12s} {screen:10s} " + " ".join(f"{x:6.2f}" for x in v))


if __name__ == "__main__":
    main()
