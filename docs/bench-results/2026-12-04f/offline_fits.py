#!/usr/bin/env python3
"""Stop 28: refit each frame's pose offline on the static matches inside the 2.447 px/sigma
gate under the ground-truth motion (scipy's least_squares, Huber 2.447, started at the ground
truth), and report the translation's scale bias (estimated minus true step,
projected on the true step, summed over frames) with a jackknife standard error over frames.
Fits: the full 6-DoF pose; the translation alone with the rotation held at the ground truth;
the same 3D points with synthetic observations (Gaussian noise of 0.43 px/sigma per axis,
the frame's measured scale), with and without the same noise on the previous keypoints
(errors in variables); the chained and the new tracks alone.
Where no match continues another by pixel (distorted images: the dump's previous keypoint is
raw, its observation undistorted), the chained / new split is left out.
Usage: offline_fits.py SEQUENCE_DIR SEGMENT.npy
"""
import sys
import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation as R

from match_chains import predecessors
from tum_poses import GroundTruth

seq, segment = sys.argv[1], sys.argv[2]
S = np.load(segment)
frame = S[:, 0].astype(int)
res = S[:, 17]
static = S[:, 11] == 0
truth = GroundTruth(seq)


chained = predecessors(S) >= 0


def project(T, X, fx, fy, cx, cy):
    P = X @ T[:3, :3].T + T[:3, 3]
    return np.stack([fx * P[:, 0] / P[:, 2] + cx, fy * P[:, 1] / P[:, 2] + cy], 1)


def fit(X, obs, sig, cam, T0, rotation_fixed=False):
    def to_pose(x):
        T = np.eye(4)
        T[:3, :3] = T0[:3, :3] if rotation_fixed else R.from_rotvec(x[:3]).as_matrix()
        T[:3, 3] = x[-3:]
        return T

    def f(x):
        return ((project(to_pose(x), X, *cam) - obs) / sig[:, None]).ravel()

    x0 = T0[:3, 3] if rotation_fixed else np.concatenate(
        [R.from_matrix(T0[:3, :3]).as_rotvec(), T0[:3, 3]])
    return to_pose(least_squares(f, x0, loss='huber', f_scale=2.447).x)


rng = np.random.default_rng(1)
fits = ['6-DoF', 'translation only, rotation at the ground truth', '6-DoF, synthetic observations',
        '6-DoF, synthetic observations and previous keypoints', '6-DoF, chained tracks only',
        '6-DoF, new tracks only']
split = chained.mean() > 0.2  # a handful of chance coincidences do not make chains
if not split:
    fits = fits[:4]
errors = {k: [] for k in fits}
steps = []
for f in np.unique(frame):
    m = (frame == f) & static & (res < 2.447)
    if (split and ((m & chained).sum() < 30 or (m & ~chained).sum() < 30)) or m.sum() < 30:
        continue
    G = truth.motion(f)  # T_cur_prev
    fx, fy, cx, cy = cam = tuple(S[m][0, 13:17])
    sig, X, obs, ch = S[m][:, 10], S[m][:, 5:8], S[m][:, 8:10], chained[m]
    z = X[:, 2]
    prev_px = np.stack([fx * X[:, 0] / z + cx, fy * X[:, 1] / z + cy], 1)
    synthetic = project(G, X, *cam) + rng.normal(0, 0.43, (len(X), 2)) * sig[:, None]
    noisy_prev = prev_px + rng.normal(0, 0.43, (len(X), 2)) * sig[:, None]
    X_noisy = np.stack([(noisy_prev[:, 0] - cx) * z / fx, (noisy_prev[:, 1] - cy) * z / fy, z], 1)
    T = {fits[0]: fit(X, obs, sig, cam, G), fits[1]: fit(X, obs, sig, cam, G, True),
         fits[2]: fit(X, synthetic, sig, cam, G), fits[3]: fit(X_noisy, synthetic, sig, cam, G)}
    if split:
        T[fits[4]] = fit(X[ch], obs[ch], sig[ch], cam, G)
        T[fits[5]] = fit(X[~ch], obs[~ch], sig[~ch], cam, G)
    step = np.linalg.inv(G)[:3, 3]
    for k in fits:
        errors[k].append(np.linalg.inv(T[k])[:3, 3] - step)
    steps.append(step)
M = np.array(steps)
print(f'{len(M)} frames (those with >= 30 static matches in the gate' + (', >= 30 chained and >= 30 new)' if split else ')'))
for k in fits:
    E = np.array(errors[k])
    num, den = (E * M).sum(1), (M * M).sum(1)
    bias = num.sum() / den.sum()
    jack = np.array([(num.sum() - num[i]) / (den.sum() - den[i]) for i in range(len(M))])
    se = np.sqrt((len(M) - 1) / len(M) * ((jack - jack.mean()) ** 2).sum())
    print(f'{k:55s} scale bias {100 * bias:+.2f} % (se {100 * se:.2f}), mean |error| {1000 * np.linalg.norm(E, axis=1).mean():.2f} mm')
