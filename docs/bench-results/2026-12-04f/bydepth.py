#!/usr/bin/env python3
"""Stop 28: static matches' residuals under the ground-truth motion, inside the 2.447 px/sigma
gate: their component along the image motion the step alone causes (the translation's part of
the predicted motion), by depth; and their radial component by distance from the principal
point. Reads a segment written by static_residuals.py.
Usage: bydepth.py SEQUENCE_DIR SEGMENT.npy
"""
import numpy as np, sys
seq = sys.argv[1]; S = np.load(sys.argv[2])
from tum_poses import GroundTruth
fr = S[:,0].astype(int); res = S[:,17]; st = S[:,11]==0
truth = GroundTruth(seq)
along = np.zeros(len(S)); trans_flow = np.zeros(len(S)); rad = np.zeros(len(S)); radial_res = np.zeros(len(S))
for f in np.unique(fr):
    m = fr == f
    G = truth.motion(f)
    fx, fy, cx, cy = S[m][0, 13:17]
    X = S[m][:, 5:8]
    P = X @ G[:3, :3].T + G[:3, 3]
    pred = np.stack([fx * P[:, 0] / P[:, 2] + cx, fy * P[:, 1] / P[:, 2] + cy], 1)
    Pr = X @ G[:3, :3].T  # rotation only
    predr = np.stack([fx * Pr[:, 0] / Pr[:, 2] + cx, fy * Pr[:, 1] / Pr[:, 2] + cy], 1)
    tf = pred - predr  # the translation's part of the image motion
    n = np.linalg.norm(tf, axis=1)
    r = S[m][:, 8:10] - pred
    along[m] = (r * tf).sum(1) / np.maximum(n, 1e-9); trans_flow[m] = n
    c = S[m][:, 8:10] - np.array([cx, cy]); rn = np.linalg.norm(c, axis=1)
    rad[m] = rn; radial_res[m] = (r * c).sum(1) / np.maximum(rn, 1e-9)
ok = st & (res < 2.447) & (trans_flow > 0.5)
z = S[:, 4]
print('residual along the translation part of the predicted image motion, by depth:')
for lo, hi in [(0, 2), (2, 2.5), (2.5, 3), (3, 4), (4, 5), (5, 9)]:
    s = ok & (z >= lo) & (z < hi)
    if s.sum(): print(f'  depth [{lo},{hi}) m: n={s.sum():6d} mean {along[s].mean():+.4f} px (se {along[s].std()/np.sqrt(s.sum()):.4f}) = {100*along[s].sum()/trans_flow[s].sum():+.2f} % of the translation flow {trans_flow[s].mean():.2f} px')
ok2 = st & (res < 2.447)
print('radial residual by distance from the principal point:')
for lo, hi in [(0, 100), (100, 200), (200, 300), (300, 500)]:
    s = ok2 & (rad >= lo) & (rad < hi)
    print(f'  r [{lo},{hi}) px: n={s.sum():6d} mean radial residual {radial_res[s].mean():+.4f} px (se {radial_res[s].std()/np.sqrt(s.sum()):.4f})')
