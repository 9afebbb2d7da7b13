#!/usr/bin/env python3
"""Stop 29: the ablation of the map tracker's new-point changes, default screen.

`collect RUNS_DIR` reads ablation.sh's runs (RUNS_DIR/<config>/<cell>/summary.json) into
ablation.json here (ATE, RPE, frames tracked per run). Without arguments: the table.

Three changes were tried: the room's points beyond 3 m ("far"), the new points' probation
("prob"), and no new points from keypoints whose match the screen had just rejected ("skip",
measured worse and not kept). ablation.json's keys name what was switched off (HBOS_ABL of
ablation_and_dump.patch): noprob, nofar, noskip, noprob,noskip, nofar,noskip. The table's
columns:
- kept (far + prob): this stop's dynbench run, dynbench_map_tracker.json (== the noskip runs);
- without probation: noprob,noskip;
- without the room's points: nofar,noskip;
- with skip as well (tried): dynbench_map_tracker_tried_skip.json;
- stop 28 (none of them): ../2026-12-04f/dynbench_map_tracker.json.
Run: python3 ablation_table.py [collect RUNS_DIR]
"""
import glob
import json
import os
import re
import statistics as st
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
COLUMNS = [("kept (far + prob)", "kept"), ("without probation", "noprob,noskip"),
           ("without the room's points", "nofar,noskip"), ("with skip as well (tried)", "skip"),
           ("stop 28", "stop 28")]


def collect(runs_dir):
    out = {}
    for path in sorted(glob.glob(os.path.join(runs_dir, "*", "*", "summary.json"))):
        config = os.path.basename(os.path.dirname(os.path.dirname(path)))
        cell = os.path.basename(os.path.dirname(path))
        s = json.load(open(path))
        out.setdefault(config, {})[cell] = {"ate_m": s["ate_m"]["rmse"],
                                            "rpe_m": s["rpe_trans_mm_per_frame"]["rmse"] / 1000,
                                            "tracked": s["frames_tracked"], "frames": s["frames"]}
    with open(os.path.join(HERE, "ablation.json"), "w") as f:
        json.dump(out, f, indent=1, sort_keys=True)
    print(f"wrote ablation.json: {sum(len(v) for v in out.values())} runs")


def dynbench(path):
    """{cell: {ate_m, rpe_m, tracked, frames}} of the default screen, cell = <scenario>_s<seed>_<mask>"""
    out = {}
    for c in json.load(open(path))["cells"]:
        scenario, seed, mask, screen = re.fullmatch(r"(.+?)_s(\d+)_(.+)_([^_]+)", c["id"]).groups()
        if screen == "default":
            m = c["metrics"]
            out[f"{scenario}_s{seed}_{mask}"] = {"ate_m": m["ate_rmse_m"],
                                                 "rpe_m": m["rpe_trans_m_per_frame"],
                                                 "tracked": m["frames_tracked"], "frames": m["frames"]}
    return out


def table():
    runs = json.load(open(os.path.join(HERE, "ablation.json")))
    runs["kept"] = dynbench(os.path.join(HERE, "dynbench_map_tracker.json"))
    runs["skip"] = dynbench(os.path.join(HERE, "dynbench_map_tracker_tried_skip.json"))
    runs["stop 28"] = dynbench(os.path.join(HERE, "..", "2026-12-04f", "dynbench_map_tracker.json"))
    names = COLUMNS
    print("ATE RMSE [cm], mean over seeds 1-5 (largest seed in brackets); default screen, map "
          "tracker, 300 frames.\n")
    print("| scenario | mask | " + " | ".join(label for label, _ in names) + " |")
    print("|---|---|" + "---:|" * len(names))
    rows = sorted({re.sub(r"_s\d+_", "|", c) for c in runs["noprob,noskip"]})
    for row in rows:
        scenario, mask = row.split("|")
        cells = [f"{scenario}_s{s}_{mask}" for s in range(1, 6)]
        out = []
        for _, key in names:
            v = [100 * runs[key][c]["ate_m"] for c in cells if c in runs[key]]
            out.append(f"{st.mean(v):.2f} ({max(v):.2f})" if len(v) == 5 else "-")
        print(f"| {scenario} | {mask} | " + " | ".join(out) + " |")
    print()
    for label, key in names[1:]:
        d = [runs["kept"][c]["ate_m"] - runs[key][c]["ate_m"] for c in runs["noprob,noskip"]]
        print(f"- kept against {label}: ATE lower on {sum(x < 0 for x in d)} of {len(d)} runs, "
              f"higher on {sum(x > 0 for x in d)}; the largest gain {-100 * min(d):.2f} cm, the "
              f"largest loss {100 * max(d):.2f} cm")
    for label, key in names:
        lost = sum(r["tracked"] < r["frames"] for c, r in runs[key].items()
                   if re.sub(r"_s\d+_", "|", c) in rows)
        print(f"- {label}: {lost} of 60 runs lost frames")


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "collect":
        collect(sys.argv[2])
    else:
        table()
