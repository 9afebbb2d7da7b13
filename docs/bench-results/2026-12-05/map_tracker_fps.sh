#!/usr/bin/env bash
# Stop 29: the map tracker's speed before and after its new-point changes, on the 37 bundled
# fr1/xyz frames, same binary (hbos-slam built with ablation_and_dump.patch): HBOS_ABL=
# noprob,nofar,noskip is stop 28's rules, noskip the kept code. Three rounds, the two rules
# interleaved; prints fps, ATE, map points and the stages from each run's map.json.
# Usage: bash map_tracker_fps.sh HBOS_SLAM OUT
set -euo pipefail
slam=$1 out=$2
for round in 1 2 3; do
  for rules in noprob,nofar,noskip noskip; do
    for run in "static --mask none" "person --mask degraded"; do
      set -- $run
      dir=$out/$round/$rules/$1_$3
      HBOS_ABL=$rules "$slam" --tracker map --scenario "$1" --mask "$3" --quiet --out "$dir" >/dev/null
      python3 - "$dir" "$rules" "$1 $3" <<'PY'
import json, sys
m = json.load(open(sys.argv[1] + "/map.json"))
s = json.load(open(sys.argv[1] + "/summary.json"))
stages = " ".join(f"{k} {v:.2f}" for k, v in sorted(m["stages_ms_per_frame"].items()))
print(f"{sys.argv[2]:20s} {sys.argv[3]:16s} fps {m['fps']:.1f} ATE {100 * s['ate_m']['rmse']:.2f} cm "
      f"points {m['map']['points_created']} | {stages}")
PY
    done
  done
done
