#!/usr/bin/env python3
"""Stop 28: the same keypoint's residuals in consecutive matches of a chain (the keypoint
observed in frame f-1 is the previous keypoint of a match in frame f), static matches inside
the 2.447 px/sigma gate in both. Reads a segment written by static_residuals.py.
Usage: chains.py SEGMENT.npy
"""
import sys
import numpy as np

from match_chains import predecessors

S = np.load(sys.argv[1])
res = S[:, 17]
residual_px = S[:, 19:21] * S[:, 10:11]
static = S[:, 11] == 0
before = predecessors(S)
pairs = np.array([(j, i) for i, j in enumerate(before) if j >= 0])
print('chained pairs', len(pairs), 'of', len(S), 'matches')
a, b = residual_px[pairs[:, 0]], residual_px[pairs[:, 1]]
ok = (res[pairs[:, 0]] < 2.447) & (res[pairs[:, 1]] < 2.447) & static[pairs[:, 0]] & static[pairs[:, 1]]
print('correlation of consecutive residuals: x %.3f, y %.3f' %
      (np.corrcoef(a[ok, 0], b[ok, 0])[0, 1], np.corrcoef(a[ok, 1], b[ok, 1])[0, 1]))
before, after = res[pairs[:, 0]][ok], res[pairs[:, 1]][ok]
for lo, hi in [(0, 0.5), (0.5, 1), (1, 1.5), (1.5, 2.447)]:
    s = (before >= lo) & (before < hi)
    print(f'residual [{lo}, {hi}) px/sigma: n = {s.sum()}, next residual median {np.median(after[s]):.3f}, share > 1.0 {np.mean(after[s] > 1.0):.3f}')
