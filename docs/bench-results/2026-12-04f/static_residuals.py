#!/usr/bin/env python3
"""Stop 28: the static matches' residuals under the ground-truth motion, from a dump written by
the tracker with diagnostic.patch applied (HBOS_DUMP=file). One segment per dynbench cell.
Usage: static_residuals.py DUMP SEQUENCE_DIR OUT_PREFIX
"""
import numpy as np, sys
from tum_poses import GroundTruth
from PIL import Image
seq = sys.argv[2]
D = np.loadtxt(sys.argv[1])
fr = D[:,0].astype(int)
resets = np.where(np.diff(fr) < 0)[0]
segs = np.split(np.arange(len(D)), resets+1)
truth = GroundTruth(seq)
deps = [l.split() for l in open(seq+'/depth.txt') if not l.startswith('#')]
depth_cache = {}
def depth_img(idx):
    if idx not in depth_cache:
        depth_cache[idx] = np.asarray(Image.open(seq+'/'+deps[idx][1])).astype(float)/5000.0
    return depth_cache[idx]
for si, seg in enumerate(segs):
    S = D[seg]
    onp = S[:,11] > 0; kept = S[:,12] > 0
    print(f'segment {si}: {len(S)} matches, person {onp.sum()}')
    res = np.zeros(len(S)); edge = np.zeros(len(S)); resv = np.zeros((len(S),2))
    for f in np.unique(S[:,0].astype(int)):
        m = S[:,0] == f
        T = truth.motion(f)
        X = S[m][:,5:8]
        P = X @ T[:3,:3].T + T[:3,3]
        fx, fy, cx, cy = S[m][0,13:17]
        u = fx*P[:,0]/P[:,2]+cx; v = fy*P[:,1]/P[:,2]+cy
        r = np.stack([S[m][:,8]-u, S[m][:,9]-v],1) / S[m][:,10:11]
        res[m] = np.linalg.norm(r,axis=1); resv[m] = r
        dimg = depth_img(f-1)
        for j, k in enumerate(np.where(m)[0]):
            x, y = int(round(S[k,2])), int(round(S[k,3]))
            w = dimg[max(0,y-3):y+4, max(0,x-3):x+4]; w = w[w>0]
            edge[k] = (w.max()-w.min())/S[k,4] if len(w) else np.nan
    st = ~onp
    print('  static GT residual px/sigma quantiles 50/80/90/95/99:', np.round(np.percentile(res[st],[50,80,90,95,99]),3))
    print('  static kept: %d dropped: %d; dropped GT-res median %.3f' % ((st&kept).sum(), (st&~kept).sum(), np.median(res[st&~kept]) if (st&~kept).any() else np.nan))
    for lo, hi in [(0,0.5),(0.5,1),(1,1.5),(1.5,2.447),(2.447,5),(5,1e9)]:
        sel = st & (res>=lo) & (res<hi)
        if sel.sum()==0: continue
        print(f'  GT res [{lo},{hi}): {sel.sum():6d} statics, kept {100*(sel&kept).sum()/sel.sum():5.1f} %, depth-edge>0.05: {100*np.nanmean(edge[sel]>0.05):5.1f} %, octave-0 share {100*np.mean(S[sel,10]==1):.0f} %, mean residual vec {np.round(resv[sel].mean(0),3)}')
    np.save(f'{sys.argv[3]}_seg{si}.npy', np.column_stack([S, res, edge, resv]))
