#!/bin/bash
# usage: semireal_grid_all_screens.sh SHIFT  (every screen, every mask, frame tracker, today's binary)
# GRID_RUN: ../2026-12-07b/semireal_grid_run.sh with its `cd` pointed at a scratch folder.
sh=$1
for mask in none degraded detector; do for s in default chi2 fixed quantile mad magnitude; do
  $GRID_RUN today_$sh /work/ab/s48/bin_v3/hbos-slam $mask $s --dataset /work/ab/s50/reg/ds/depth_shift_$sh
done; done
