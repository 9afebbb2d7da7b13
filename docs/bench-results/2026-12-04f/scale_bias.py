#!/usr/bin/env python3
"""Stop 28: each cell's per-frame translation error against the ground truth's motion:
the least-squares scale bias (estimated minus true motion, projected on the true motion),
the mean error vector in the camera frame and the mean rotation error.
Usage: scale_bias.py SEQUENCE_DIR CELL_DIR...
"""
import sys, numpy as np
from scipy.spatial.transform import Rotation as R
from tum_poses import GroundTruth, load_poses
truth = GroundTruth(sys.argv[1])
for c in sys.argv[2:]:
    tr = load_poses(c + '/trajectory.txt'); ks = sorted(tr)
    E = []; M = []; ROT = []
    for a, b in zip(ks[:-1], ks[1:]):
        G = np.linalg.inv(truth.at(a)) @ truth.at(b); T = np.linalg.inv(tr[a]) @ tr[b]
        E.append(T[:3,3] - G[:3,3]); M.append(G[:3,3])
        ROT.append(R.from_matrix(G[:3,:3].T @ T[:3,:3]).as_rotvec())
    E = np.array(E); M = np.array(M); ROT=np.array(ROT)
    scale = (E*M).sum()/ (M*M).sum()
    perp = E - np.outer((E*M).sum(1)/np.maximum((M*M).sum(1),1e-12), 1)*M
    print(c.split('/')[-1], f'translation scale bias {100*scale:+.2f} %, mean err vec (cam) mm {np.round(E.mean(0)*1000,3)}, mean |e| mm {1000*np.linalg.norm(E,axis=1).mean():.3f}, |mean|/mean|e| {np.linalg.norm(E.mean(0))/np.linalg.norm(E,axis=1).mean():.3f}, mean rot err vec mdeg {np.round(np.degrees(ROT.mean(0))*1000,2)}')
