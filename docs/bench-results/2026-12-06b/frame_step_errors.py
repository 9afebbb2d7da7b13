# Frame-to-frame steps of estimated trajectories that are off the ground truth's own step by more than
# a threshold [m] in translation: frame index, translation error, rotation error.
# usage: python3 frame_step_errors.py THRESHOLD_M groundtruth.txt trajectory.txt [more.txt ...]
import numpy as np, sys
from scipy.spatial.transform import Rotation as R
def load(p):
    d={}
    for l in open(p):
        if l.startswith('#') or not l.strip(): continue
        v=[float(x) for x in l.split()]
        d[round(v[0],4)]=v[1:]
    return d
def T(v):
    m=np.eye(4); m[:3,:3]=R.from_quat(v[3:7]).as_matrix(); m[:3,3]=v[:3]; return m
gt=load(sys.argv[2]); gk=np.array(sorted(gt))
for p in sys.argv[3:]:
    est=load(p); ks=sorted(est)
    for i,(a,b) in enumerate(zip(ks,ks[1:])):
        ga=gk[np.abs(gk-a).argmin()]; gb=gk[np.abs(gk-b).argmin()]
        de=np.linalg.inv(T(est[a]))@T(est[b]); dg=np.linalg.inv(T(gt[ga]))@T(gt[gb])
        err=np.linalg.inv(dg)@de
        te=np.linalg.norm(err[:3,3]); 
        if te>float(sys.argv[1]): print(p.split('/')[-2], i+1, f"{te*1000:.0f} mm", f"{np.degrees(np.linalg.norm(R.from_matrix(err[:3,:3]).as_rotvec())):.1f} deg")
