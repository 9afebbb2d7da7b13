#!/usr/bin/env python3
"""Stop 28: static matches' residuals under the ground-truth motion by the depth jump (max-min
over 5 x 5 pixels / depth) at the previous keypoint, and their mean component along the
image motion the ground truth predicts.
Usage: depth_edges.py SEQUENCE_DIR SEGMENT.npy
"""
import numpy as np, sys
from PIL import Image
seq = sys.argv[1]
S = np.load(sys.argv[2])
deps = [l.split() for l in open(seq+'/depth.txt') if not l.startswith('#')]
fr = S[:,0].astype(int); res = S[:,17]; kept = S[:,12]>0
jump = np.full(len(S), np.nan)
cache = {}
for i in range(len(S)):
    f = fr[i]-1
    if f not in cache: cache = {f: np.asarray(Image.open(seq+'/'+deps[f][1])).astype(float)/5000.0}
    d = cache[f]; x, y = int(round(S[i,2])), int(round(S[i,3]))
    w = d[max(0,y-2):y+3, max(0,x-2):x+3]; w = w[w>0]
    if len(w): jump[i] = (w.max()-w.min())/S[i,4]
# the residual's component along the image motion the ground truth predicts (not the raw
# flow, observed minus previous keypoint: that shares the observation's noise with the residual)
from tum_poses import GroundTruth
truth = GroundTruth(seq)
along = np.zeros(len(S))
for f in np.unique(fr):
    m = fr == f
    G = truth.motion(f)
    fx, fy, cx, cy = S[m][0, 13:17]
    P = S[m][:, 5:8] @ G[:3, :3].T + G[:3, 3]
    pred = np.stack([fx * P[:, 0] / P[:, 2] + cx, fy * P[:, 1] / P[:, 2] + cy], 1)
    flow = pred - S[m][:, 2:4]
    along[m] = ((S[m][:, 8:10] - pred) * flow).sum(1) / np.maximum(np.linalg.norm(flow, axis=1), 1e-9)
for lo,hi in [(0,0.02),(0.02,0.1),(0.1,0.3),(0.3,10)]:
    s = (jump>=lo)&(jump<hi)&(res<2.447)
    print(f'depth jump 5x5 [{lo},{hi}): n={s.sum():6d} ({100*s.mean():4.1f} %) GT-res median {np.median(res[s]):.3f} p90 {np.percentile(res[s],90):.3f}  residual along the predicted image motion: mean {along[s].mean():+.4f} px  kept {100*kept[s].mean():.1f} %')
