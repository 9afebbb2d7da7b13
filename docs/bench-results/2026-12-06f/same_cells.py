#!/usr/bin/env python3
"""How many cells two dynbench outputs share, and how many of those have the same ATE and RPE to
the bit.

usage: same_cells.py EARLIER.json LATER.json
"""
import json
import sys


def metrics(path):
    with open(path) as f:
        return {c["id"]: c["metrics"] for c in json.load(f)["cells"]}


def main(earlier_path, later_path):
    earlier, later = metrics(earlier_path), metrics(later_path)
    common = sorted(set(earlier) & set(later))
    differ = [k for k in common
              if earlier[k]["ate_rmse_m"] != later[k]["ate_rmse_m"]
              or earlier[k]["rpe_trans_m_per_frame"] != later[k]["rpe_trans_m_per_frame"]]
    print(f"{earlier_path}: {len(earlier)} cells; {later_path}: {len(later)} cells; "
          f"{len(common)} in both, {len(common) - len(differ)} the same to the bit")
    for k in differ:
        print(f"  differs: {k}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
