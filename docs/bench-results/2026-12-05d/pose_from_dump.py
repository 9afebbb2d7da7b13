#!/usr/bin/env python3
"""Re-solves each frame's pose from the dumped survivors (scipy least_squares, Huber 2.447 on the
whitened error, as pose_refiner) and prints its error against the ground truth next to the
tracker's. usage: pose_from_dump.py SEQUENCE_DIR DUMP TRAJECTORY N_FRAMES"""
import numpy as np, sys, json
from scipy.spatial.transform import Rotation as R
from scipy.optimize import least_squares
S=sys.argv[1]; dump=sys.argv[2]; traj=sys.argv[3]
def load(f): return np.array([l.split() for l in open(f) if not l.startswith('#')],float)
def T(r):
    M=np.eye(4);M[:3,:3]=R.from_quat(r[4:8]).as_matrix();M[:3,3]=r[1:4];return M
G=[T(r) for r in load(S+'/groundtruth.txt')]; E=[T(r) for r in load(traj)]
sc=json.load(open(S+'/scenario.json'))['intrinsics']; fx,fy,cx,cy=sc['fx'],sc['fy'],sc['cx'],sc['cy']
d=np.loadtxt(dump); fr=d[:,0].astype(int)
def proj(x,X):
    Rm=R.from_rotvec(x[:3]).as_matrix(); P=X@Rm.T+x[3:]
    return np.stack([fx*P[:,0]/P[:,2]+cx, fy*P[:,1]/P[:,2]+cy],1)
for f in range(1,int(sys.argv[4])):
    sel=(fr==f)&(d[:,9]>0); X=d[sel,2:5]; obs=d[sel,5:7]; sig=d[sel,7]
    Tcw=np.linalg.inv(E[f]); x0=np.r_[R.from_matrix(Tcw[:3,:3]).as_rotvec(),Tcw[:3,3]]
    fun=lambda x:((proj(x,X)-obs)/sig[:,None]).ravel()
    r=least_squares(fun,x0,loss='huber',f_scale=2.447/np.sqrt(2))
    Tls=np.eye(4);Tls[:3,:3]=R.from_rotvec(r.x[:3]).as_matrix();Tls[:3,3]=r.x[3:]
    Tgt=np.linalg.inv(G[f])@G[0]
    def err(Tcw): 
        # position of camera in c0-frame vs gt
        return np.linalg.norm(np.linalg.inv(Tcw)[:3,3]-np.linalg.inv(Tgt)[:3,3])*1000
    print(f, 'n',sel.sum(),'tracker err mm %.2f  lsq err mm %.2f  cost tracker %.1f lsq %.1f  gt-pose cost %.1f'%(err(Tcw),err(Tls),np.sum(np.minimum(fun(x0)**2,50)),np.sum(np.minimum(fun(r.x)**2,50)), np.sum(np.minimum(fun(np.r_[R.from_matrix(Tgt[:3,:3]).as_rotvec(),Tgt[:3,3]])**2,50))))
