#!/usr/bin/env bash
# Stop 29: which of the map tracker's new-point changes does what. Runs hbos-slam built with
# ablation_and_dump.patch (the throwaway switch HBOS_ABL, and the tried rule "skip", on unless
# HBOS_ABL holds noskip: so noskip is the kept code) with the default screen on the cached
# rendered sequences, with changes switched off (noprob: probation, nofar: the room's points),
# and writes one summary.json per run under OUT/<config>/<scenario>_s<seed>_<mask>/.
# ablation_table.py collects them.
# Usage: bash ablation.sh HBOS_SLAM CACHE OUT
set -euo pipefail
slam=$1 cache=$2 out=$3
run() {  # config scenario seed mask
  local dir=$out/$1/$2_s$3_$4 seq=$cache/$2_seed$3_300f
  [ -f "$dir/summary.json" ] && return 0
  local mask=(--mask none --scenario static)
  [ "$4" != none ] && mask=(--mask-dir "$seq/masks/$4")
  HBOS_ABL=$1 "$slam" --dataset "$seq" --camera tum3 "${mask[@]}" --tracker map --quiet \
    --out "$dir" >/dev/null 2>&1
}
export -f run
export slam cache out
for config in noprob nofar noskip noprob,noskip nofar,noskip; do
  for scenario in walking_xyz walking_rpy walking_halfsphere walking_static; do
    for seed in 1 2 3 4 5; do
      for mask in eroded person_missed none; do
        echo "$config $scenario $seed $mask"
      done
    done
  done
done | xargs -P 2 -L 1 bash -c 'run "$@"' _
