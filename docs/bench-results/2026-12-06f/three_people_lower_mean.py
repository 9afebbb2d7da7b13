#!/usr/bin/env python3
"""Where the masked runs' lower mean ATE with three people comes from (stop 41's runs A and B).

For each screen: of the masked runs (eroded, person missed), how many have a lower ATE with the
third person than the same scenario, seed and mask with two; the mean difference per scenario;
and the three runs whose ATE falls most.

usage: three_people_lower_mean.py TWO_PEOPLE.json THREE_PEOPLE.json
"""
import collections
import json
import sys

SCENARIOS = ("walking_xyz", "walking_rpy", "walking_halfsphere", "walking_static")


def ate_cm(path):
    with open(path) as f:
        return {c["id"]: 100 * c["metrics"]["ate_rmse_m"] for c in json.load(f)["cells"]}


def main(two_path, three_path):
    two, three = ate_cm(two_path), ate_cm(three_path)
    screens = sorted({k.rsplit("_", 1)[1] for k in three})
    for screen in screens:
        ids = [k for k in three if k.endswith("_" + screen) and k in two and "_none_" not in k]
        diff = {k: three[k] - two[k] for k in ids}
        lower = sum(d < 0 for d in diff.values())
        per = collections.defaultdict(list)
        for k, d in diff.items():
            per[next(s for s in SCENARIOS if k.startswith(s + "_"))].append(d)
        mean_two = sum(two[k] for k in ids) / len(ids)
        mean_three = sum(three[k] for k in ids) / len(ids)
        print(f"{screen}: lower with three people on {lower} of {len(ids)} masked runs; mean "
              f"{mean_two:.3f} -> {mean_three:.3f} cm")
        print("  mean difference per scenario [cm]: " + ", ".join(
            f"{s} {sum(per[s]) / len(per[s]):+.2f} ({sum(d < 0 for d in per[s])} of {len(per[s])} lower)"
            for s in SCENARIOS))
        most = sorted(diff, key=diff.get)[:3]
        print("  largest falls: " + ", ".join(f"{k} {two[k]:.2f} -> {three[k]:.2f}" for k in most))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
