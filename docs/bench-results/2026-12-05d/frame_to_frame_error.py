#!/usr/bin/env python3
"""Frame-to-frame error of trajectories against a ground truth, per frame (the RPE at one frame)
usage: frame_to_frame_error.py GROUNDTRUTH TRAJ [TRAJ ...]"""
import numpy as np, sys
from scipy.spatial.transform import Rotation as R
def load(f):
    return np.array([l.split() for l in open(f) if not l.startswith('#')],float)
def T(r):
    M=np.eye(4);M[:3,:3]=R.from_quat(r[4:8]).as_matrix();M[:3,3]=r[1:4];return M
g=load(sys.argv[1]); G={round(r[0],4):T(r) for r in g}
for f in sys.argv[2:]:
    e=load(f); E=[(round(r[0],4),T(r)) for r in e]
    out=[]
    for (t0,a),(t1,b) in zip(E[:-1],E[1:]):
        d=np.linalg.inv(np.linalg.inv(G[t0])@G[t1])@(np.linalg.inv(a)@b)
        out.append((np.linalg.norm(d[:3,3])*1000, np.degrees(np.linalg.norm(R.from_matrix(d[:3,:3]).as_rotvec()))))
    out=np.array(out)
    print(f, 'mean mm %.2f deg %.4f'%tuple(out.mean(0)), ' first10 mm', np.round(out[:10,0],2))
