#!/usr/bin/env python3
"""Per-match residuals under the ground truth, from a map-tracker dump (diagnostic_dump.patch,
HBOS_DUMP=file). usage: gt_residuals.py SEQUENCE_DIR DUMP. Static/dynamic from the objects/ map
at the observed pixel; whitened by the keypoint sigma 1.2^octave."""
import numpy as np, sys, json
from scipy.spatial.transform import Rotation as R
from PIL import Image
S=sys.argv[1]; dump=sys.argv[2]
def load(f): return np.array([l.split() for l in open(f) if not l.startswith('#')],float)
def T(r):
    M=np.eye(4);M[:3,:3]=R.from_quat(r[4:8]).as_matrix();M[:3,3]=r[1:4];return M
g=load(S+'/groundtruth.txt'); G=[T(r) for r in g]
e=load(dump.replace('dump','x')) if False else None
sc=json.load(open(S+'/scenario.json'))['intrinsics']; fx,fy,cx,cy=sc['fx'],sc['fy'],sc['cx'],sc['cy']
stamps=[l.split()[0] for l in open(S+'/rgb.txt') if not l.startswith('#')]
d=np.loadtxt(dump)
fr=d[:,0].astype(int)
res=[];dyn=[]
for f in np.unique(fr):
    sel=fr==f; X=d[sel,2:5]
    Tc=np.linalg.inv(G[f])@G[0]   # c0 -> cf
    Pc=X@Tc[:3,:3].T+Tc[:3,3]
    u=fx*Pc[:,0]/Pc[:,2]+cx; v=fy*Pc[:,1]/Pc[:,2]+cy
    r=np.hypot(u-d[sel,5],v-d[sel,6]); res.append(r)
    obj=np.array(Image.open(S+'/objects/'+stamps[f]+'.png'))
    uu=np.clip(np.round(d[sel,5]).astype(int),0,obj.shape[1]-1); vv=np.clip(np.round(d[sel,6]).astype(int),0,obj.shape[0]-1)
    dyn.append(obj[vv,uu]>0)
res=np.concatenate(res); dyn=np.concatenate(dyn)
inl=d[:,9]>0; sig=d[:,7]
rw=res/sig
st=~dyn
print('matches',len(d),'dynamic(by object map at observed px)',dyn.sum())
print('static: whitened GT residual quantiles 50/90/95/99:',np.round(np.percentile(rw[st],[50,90,95,99]),2))
for th in [2.447,4,8]:
    print(f' static with GT res > {th} sigma: {np.mean(rw[st]>th)*100:.1f}%  of those kept by screen: {np.mean(inl[st][rw[st]>th])*100:.1f}%')
print('static <2.447 dropped by screen: %.1f%%'%(100*np.mean(~inl[st][rw[st]<2.447])))
print('per-octave median raw px residual (static):',[ (o, round(float(np.median(res[st&(d[:,8]==o)])),2), int((st&(d[:,8]==o)).sum())) for o in range(8)])
# signed residual per octave, early frames
du=[];dv=[];oc=[];ff=[]
for f in np.unique(fr):
    sel=fr==f; X=d[sel,2:5]
    Tc=np.linalg.inv(G[f])@G[0]; Pc=X@Tc[:3,:3].T+Tc[:3,3]
    u=fx*Pc[:,0]/Pc[:,2]+cx; v=fy*Pc[:,1]/Pc[:,2]+cy
    du.append(d[sel,5]-u); dv.append(d[sel,6]-v)
du=np.concatenate(du);dv=np.concatenate(dv)
early=(fr<=5)&st&(rw<4)
print('frames1-5 static inliers: median |res| px by octave', [(o,round(float(np.median(res[early&(d[:,8]==o)])),2),round(float(np.mean(du[early&(d[:,8]==o)])),2),round(float(np.mean(dv[early&(d[:,8]==o)])),2)) for o in range(8)])
ok=st&(rw<4)
print('all frames: mean signed du,dv by octave',[(o,round(float(np.mean(du[ok&(d[:,8]==o)])),2),round(float(np.mean(dv[ok&(d[:,8]==o)])),2)) for o in range(8)])
