#!/usr/bin/env python3
"""Stop 28: static matches' residuals under the ground-truth motion by the depth jump (max-min
over 5 x 5 pixels / depth) at the previous keypoint, and their mean component along the
keypoint's image motion.
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
# the translational flow direction of each match under GT: approximated by the residual-free motion is not stored; use signed parallax: the component of the GT residual along (observed - previous keypoint)
flow = S[:,8:10] - S[:,2:4]; fl = np.linalg.norm(flow,axis=1)
along = (S[:,19:21]*S[:,10:11]*flow).sum(1)/np.maximum(fl,1e-9)
for lo,hi in [(0,0.02),(0.02,0.1),(0.1,0.3),(0.3,10)]:
    s = (jump>=lo)&(jump<hi)&(res<2.447)
    print(f'depth jump 5x5 [{lo},{hi}): n={s.sum():6d} ({100*s.mean():4.1f} %) GT-res median {np.median(res[s]):.3f} p90 {np.percentile(res[s],90):.3f}  residual along image motion: mean {along[s].mean():+.4f} px  kept {100*kept[s].mean():.1f} %')
