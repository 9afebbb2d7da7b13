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
import importlib.util
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
# The row format is stop 26's (compare_history_consensus.py beside ../2026-12-04d).
_spec = importlib.util.spec_from_file_location(
    "compare_history_consensus",
    os.path.join(HERE, "..", "2026-12-04d", "compare_history_consensus.py"))
_stop26 = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_stop26)
row = _stop26.row


def load(*parts):
    with open(os.path.join(HERE, *parts)) as f:
        return {c["id"]: c["metrics"] for c in json.load(f)["cells"]}


# (before, after, masks, screens) per block of the table.
BLOCKS = [
    (("..", "2026-12-04d", "dynbench_unmasked_history_consensus.json"),
     ("dynbench_unmasked_static_trust.json",), ["none"],
     ["none", "fixed", "chi2", "quantile", "mad", "magnitude", "paper", "default"]),
    (("..", "2026-12-04d", "dynbench_masked_history_consensus.json"),
     ("dynbench_masked_static_trust.json",), ["eroded", "boxes", "person_missed"], ["default"]),
]


def main():
    print("| scenario | mask | screen | ATE [cm] before -> after | paired change | seeds fell / "
          "rose / same | RPE [mm/frame] before -> after |")
    print("|---|---|---|---|---|---|---|")
    for before_path, after_path, masks, screens in BLOCKS:
        before, after = load(*before_path), load(*after_path)
        for scenario in ["walking_xyz", "walking_rpy"]:
            for mask in masks:
                for screen in screens:
                    row(before, after, scenario, mask, screen)


if __name__ == "__main__":
    main()
