#!/usr/bin/env python3
"""Stop 28: each cell's per-frame translation error against the ground truth's motion:
the least-squares scale bias (estimated minus true motion, projected on the true motion),
the mean error vector in the camera frame and the mean rotation error.
Usage: scale_bias.py SEQUENCE_DIR CELL_DIR...
"""
import sys, numpy as np
from scipy.spatial.transform import Rotation as R
def load(p):
    d = {}
    for l in open(p):
        if l.startswith('#') or not l.strip(): continue
        v = [float(x) for x in l.split()]
        T = np.eye(4); T[:3,:3] = R.from_quat(v[4:8]).as_matrix(); T[:3,3] = v[1:4]; d[round(v[0],4)] = T
    return d
gt = load(sys.argv[1] + '/groundtruth.txt'); g = np.array(sorted(gt))
for c in sys.argv[2:]:
    tr = load(c + '/trajectory.txt'); ks = sorted(tr)
    E = []; M = []; ROT = []
    for a, b in zip(ks[:-1], ks[1:]):
        ga = gt[g[np.argmin(abs(g-a))]]; gb = gt[g[np.argmin(abs(g-b))]]
        G = np.linalg.inv(ga) @ gb; T = np.linalg.inv(tr[a]) @ tr[b]
        E.append(T[:3,3] - G[:3,3]); M.append(G[:3,3])
        ROT.append(R.from_matrix(G[:3,:3].T @ T[:3,:3]).as_rotvec())
    E = np.array(E); M = np.array(M); ROT=np.array(ROT)
    scale = (E*M).sum()/ (M*M).sum()
    perp = E - np.outer((E*M).sum(1)/np.maximum((M*M).sum(1),1e-12), 1)*M
    print(c.split('/')[-1], f'translation scale bias {100*scale:+.2f} %, mean err vec (cam) mm {np.round(E.mean(0)*1000,3)}, |mean|/mean|e| {np.linalg.norm(E.mean(0))/np.linalg.norm(E,axis=1).mean():.3f}, mean rot err vec mdeg {np.round(np.degrees(ROT.mean(0))*1000,2)}')
