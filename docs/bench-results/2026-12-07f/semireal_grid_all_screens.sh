#!/bin/bash
# usage: grid_all.sh SHIFT  (every screen, every mask, frame tracker, today's binary)
sh=$1
for mask in none degraded detector; do for s in default chi2 fixed quantile mad magnitude; do
  ./grid_run.sh today_$sh /work/ab/s48/bin_v3/hbos-slam $mask $s --dataset /work/ab/s50/reg/ds/depth_shift_$sh
done; done
