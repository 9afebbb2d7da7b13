"""B1: the share of the matches between the later gate (floor 2.0) and chi^2's floor, per frame,
in the map tracker's lost run (walking_rpy seed 19, no mask, later-rounds floor 2.0).

Input: the lines the throwaway diagnostic (tried_band_share_guard.diff, HBOS_BAND_DIAG=1) printed,
one per later round: round, fit-set matches, kept, band, noise scale s, later gate, first-round
gate at this s, band / (kept + band). The fourth round of each frame is read; the first frame (the map's start) has no rounds, so the
k-th line is frame k.
"""
import statistics
import sys

rows = [line.split() for line in open(sys.argv[1])]
last = [r for r in rows if r[0] == "4"]
share = [float(r[7]) for r in last]
kept = [int(r[2]) for r in last]
band = [int(r[3]) for r in last]
print(f"frames with a fourth round: {len(last)}")
before = share[:150]
print(f"frames 1-150: band share median {statistics.median(before):.3f}, "
      f"90th percentile {sorted(before)[int(0.9 * len(before))]:.3f}, max {max(before):.3f}")
print("frames 166-179 (the pose leaves the room; stop 40: the person holds 75-97 % of the matches):")
for f in range(165, 179):
    print(f"  frame {f + 1}: kept {kept[f]}, band {band[f]}, share {share[f]:.3f}")
inside = share[165:179]
print(f"frames 166-179: band share median {statistics.median(inside):.3f}, max {max(inside):.3f}")
