#!/usr/bin/env python3
"""Stop 28: item 7's verdict per masked row of the rendered benchmark through the map tracker.

For each scenario and mask (not 'none') of a hbos-dynbench JSON: the default's mean ATE and RPE
over the seeds, the lowest other screen's, and the paired difference (default minus that
screen, mean ± sd over the seeds). Verdict: 'lowest' when the default's mean is the lowest,
'tied' when the paired difference's mean is within its sd, else 'behind'.
Run: python3 map_tracker_verdicts.py dynbench_map_tracker.json [more.json ...]
"""
import os
import statistics as st
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-12-04e"))
from compare_new_scenarios import by_row, values  # noqa: E402


def verdict(screens, key):
    own = values(screens["default"], key)
    others = {s: values(m, key) for s, m in screens.items() if s not in ("default", "none")}
    best = min(others, key=lambda s: st.mean(others[s]))
    d = [a - b for a, b in zip(own, others[best])]
    if st.mean(own) <= st.mean(others[best]):
        word = "lowest"
    elif st.mean(d) <= st.stdev(d):
        word = "tied"
    else:
        word = "behind"
    return (f"{st.mean(own):.2f} ± {st.stdev(own):.2f} | {best} {st.mean(others[best]):.2f} ± "
            f"{st.stdev(others[best]):.2f} | {st.mean(d):+.2f} ± {st.stdev(d):.2f} | **{word}**")


print("| scenario | mask | default ATE [cm] | lowest other | default - it | ATE | default RPE "
      "[mm/frame] | lowest other | default - it | RPE |")
print("|---|---|---|---|---|---|---|---|---|---|")
for path in sys.argv[1:]:
    for (scenario, mask), screens in sorted(by_row(path).items()):
        if mask == "none":
            continue
        print(f"| {scenario} | {mask} | {verdict(screens, 'ate')} | {verdict(screens, 'rpe')} |")
