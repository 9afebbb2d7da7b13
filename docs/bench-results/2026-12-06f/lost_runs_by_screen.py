#!/usr/bin/env python3
"""Runs over 5 cm ATE, per screen, in dynbench outputs (each cell id ends in its screen's name).

usage: lost_runs_by_screen.py DYNBENCH.json...
"""
import collections
import json
import sys

LOST_M = 0.05


def main(paths):
    total = collections.Counter()
    lost = collections.defaultdict(list)
    for path in paths:
        with open(path) as f:
            for cell in json.load(f)["cells"]:
                run, screen = cell["id"].rsplit("_", 1)
                total[screen] += 1
                ate = cell["metrics"]["ate_rmse_m"]
                if ate > LOST_M:
                    lost[screen].append(f"{run} {100 * ate:.1f} cm ({path.split('/')[-2]})")
    print(f"runs over {100 * LOST_M:.0f} cm ATE, per screen, in {len(paths)} outputs")
    for screen in sorted(total, key=lambda s: (len(lost[s]), s)):
        print(f"{screen}: {len(lost[screen])} of {total[screen]}" +
              "".join(f"\n  {r}" for r in lost[screen]))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
