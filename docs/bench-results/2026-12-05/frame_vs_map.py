#!/usr/bin/env python3
"""Stop 29: the two trackers on the same rendered cells (masked rows, 5 seeds, 300 frames).

Frame tracker: the latest runs of each row (stop 27: ../2026-12-04e/dynbench_masked_static_trust
.json and dynbench_masked_baselines_static_trust.json for walking_xyz and walking_rpy,
dynbench_new_scenarios.json for walking_halfsphere and walking_static). Map tracker: this stop's
dynbench_map_tracker.json. Per row and screen: ATE [cm] and RPE [mm/frame], mean over the seeds.
Run: python3 frame_vs_map.py
"""
import collections
import json
import os
import re
import statistics as st

HERE = os.path.dirname(os.path.abspath(__file__))
STOP27 = os.path.join(HERE, "..", "2026-12-04e")
FRAME = [os.path.join(STOP27, n) for n in ("dynbench_masked_static_trust.json",
                                           "dynbench_masked_baselines_static_trust.json",
                                           "dynbench_new_scenarios.json")]
MAP = [os.path.join(HERE, "dynbench_map_tracker.json")]
SCREENS = ["fixed", "chi2", "quantile", "mad", "magnitude", "default"]


def load(paths):
    rows = collections.defaultdict(dict)  # (scenario, mask, screen) -> {seed: metrics}
    for path in paths:
        for c in json.load(open(path))["cells"]:
            scenario, seed, mask, screen = re.fullmatch(r"(.+?)_s(\d+)_(.+)_([^_]+)",
                                                        c["id"]).groups()
            rows[(scenario, mask, screen)][int(seed)] = c["metrics"]
    return rows


def mean(seeds, key, scale):
    return st.mean(scale * m[key] for m in seeds.values()) if len(seeds) == 5 else None


def main():
    frame, mapped = load(FRAME), load(MAP)
    print("| scenario | mask | screen | ATE frame [cm] | ATE map | RPE frame [mm/frame] | RPE map |")
    print("|---|---|---|---:|---:|---:|---:|")
    for key in sorted(set(frame) & set(mapped), key=lambda k: (k[0], k[1], SCREENS.index(k[2])
                                                                if k[2] in SCREENS else -1)):
        if key[1] == "none":
            continue
        f, m = frame[key], mapped[key]
        values = [mean(f, "ate_rmse_m", 100), mean(m, "ate_rmse_m", 100),
                  mean(f, "rpe_trans_m_per_frame", 1000), mean(m, "rpe_trans_m_per_frame", 1000)]
        if None in values:
            continue
        print(f"| {key[0]} | {key[1]} | {key[2]} | " + " | ".join(f"{v:.2f}" for v in values) + " |")


if __name__ == "__main__":
    main()
