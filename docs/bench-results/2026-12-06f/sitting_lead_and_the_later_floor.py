#!/usr/bin/env python3
"""Why the frame tracker's default lost its stop-36 lead over chi^2 with people sitting.

Counts, per mask variant, the runs where the default's ATE is below chi^2's, once for the default
without the later-rounds floor (stop 40's `floor_off` runs, the code stop 36 measured) and once with
it (stop 40's `floor1.22` runs, today's default), against the same chi^2 runs (run D of stop 41;
chi^2 has no floor, so its runs do not depend on the setting). Also checks that run D's default
runs are stop 40's floor1.22 runs to the bit, so the two sets differ only by the floor.

usage: sitting_lead_and_the_later_floor.py FLOOR_OFF.json FLOOR_ON.json EVERY_SCREEN.json
"""
import json
import sys

from scipy.stats import wilcoxon


def ate_by_id(path):
    with open(path) as f:
        return {c["id"]: c["metrics"]["ate_rmse_m"] for c in json.load(f)["cells"]}


def main(off_path, on_path, every_path):
    off, on, every = ate_by_id(off_path), ate_by_id(on_path), ate_by_id(every_path)
    defaults = sorted(k for k in every if k.endswith("_default"))
    same = sum(every[k] == on[k] for k in defaults)
    print(f"run D's default runs equal to stop 40's floor1.22 runs: {same} of {len(defaults)}")
    for label, variants in (("masked (eroded, person_missed)", ("_eroded_", "_person_missed_")),
                            ("no mask", ("_none_",))):
        ids = [k for k in defaults if any(v in k for v in variants)]
        chi2 = [every[k.replace("_default", "_chi2")] for k in ids]
        print(f"\n{label}: {len(ids)} runs")
        for name, runs in (("floor off", off), ("floor 1.22", on)):
            ate = [runs[k] for k in ids]
            lower = sum(a < c for a, c in zip(ate, chi2))
            ties = sum(a == c for a, c in zip(ate, chi2))
            p = wilcoxon(ate, chi2).pvalue
            mean = 100 * sum(ate) / len(ate)
            print(f"  default, {name:10s}: lower than chi2 on {lower:2d}, equal on {ties}, "
                  f"Wilcoxon p = {p:.2g}, mean ATE {mean:.3f} cm (chi2 {100 * sum(chi2) / len(chi2):.3f})")
        for scen in ("sitting_static", "sitting_xyz"):
            sub = [k for k in ids if k.startswith(scen)]
            o = sum(off[k] < every[k.replace("_default", "_chi2")] for k in sub)
            n = sum(on[k] < every[k.replace("_default", "_chi2")] for k in sub)
            print(f"    {scen}: lower than chi2, floor off {o} of {len(sub)}, floor 1.22 {n} of {len(sub)}")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
