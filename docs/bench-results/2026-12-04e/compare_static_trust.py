"""Before/after table for docs/results.md, "Newborn tracks earn no trust (stop 27)".

Reads
  ../2026-12-04d/dynbench_unmasked_history_consensus.json   every screen, no mask, stop 26
                                                            (history consensus rule 1)
  dynbench_unmasked_static_trust.json                       the same cells, rule 2
  ../2026-12-04d/dynbench_masked_history_consensus.json     the default with the eroded, boxes
                                                            and person_missed masks, stop 26
  dynbench_masked_static_trust.json                         the same cells, rule 2
and prints, per scenario, mask and screen, ATE and RPE before -> after (mean over seeds 1-5), the
paired change (after - before, mean ± sd) and on how many seeds ATE fell, rose or stayed (a
change under 0.005 cm counts as the same).
Run: python3 compare_static_trust.py
"""
import json
import os
import statistics as st

HERE = os.path.dirname(os.path.abspath(__file__))
SEEDS = [1, 2, 3, 4, 5]


def load(*parts):
    with open(os.path.join(HERE, *parts)) as f:
        return {c["id"]: c["metrics"] for c in json.load(f)["cells"]}


def row(before, after, scenario, mask, screen):
    ids = [f"{scenario}_s{s}_{mask}_{screen}" for s in SEEDS]
    b = [100 * before[i]["ate_rmse_m"] for i in ids]
    a = [100 * after[i]["ate_rmse_m"] for i in ids]
    rb = [1000 * before[i]["rpe_trans_m_per_frame"] for i in ids]
    ra = [1000 * after[i]["rpe_trans_m_per_frame"] for i in ids]
    d = [x - y for x, y in zip(a, b)]
    fell = sum(x < -0.005 for x in d)
    rose = sum(x > 0.005 for x in d)
    print(f"| {scenario} | {mask} | {screen} | {st.mean(b):.2f} -> {st.mean(a):.2f} | "
          f"{st.mean(d):+.2f} ± {st.stdev(d):.2f} | {fell} / {rose} / {5 - fell - rose} | "
          f"{st.mean(rb):.2f} -> {st.mean(ra):.2f} |")


def main():
    print("| scenario | mask | screen | ATE [cm] before -> after | paired change | seeds fell / "
          "rose / same | RPE [mm/frame] before -> after |")
    print("|---|---|---|---|---|---|---|")
    before = load("..", "2026-12-04d", "dynbench_unmasked_history_consensus.json")
    after = load("dynbench_unmasked_static_trust.json")
    for scenario in ["walking_xyz", "walking_rpy"]:
        for screen in ["none", "fixed", "chi2", "quantile", "mad", "magnitude", "paper",
                       "default"]:
            row(before, after, scenario, "none", screen)
    before = load("..", "2026-12-04d", "dynbench_masked_history_consensus.json")
    after = load("dynbench_masked_static_trust.json")
    for scenario in ["walking_xyz", "walking_rpy"]:
        for mask in ["eroded", "boxes", "person_missed"]:
            row(before, after, scenario, mask, "default")


if __name__ == "__main__":
    main()
