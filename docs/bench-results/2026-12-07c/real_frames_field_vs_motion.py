"""Per frame of the 37 real fr1/xyz frames (static, as recorded): the later rounds' mean F
(field_significance.py) against the camera's step (ground truth) and the depth map's time offset
from the colour image (the nearest stamp in depth.txt). Stop 47.
usage: python3 real_frames_field_vs_motion.py FDIAG_FILE DATASET_DIR
"""
import re
import sys

import numpy as np

fdiag, dataset = sys.argv[1:]
lines = [l for l in open(fdiag) if l.startswith("FDIAG")]
stamps = lambda f: [float(l.split()[0]) for l in open(f"{dataset}/{f}") if not l.startswith("#")]
rgb, depth = stamps("rgb.txt"), stamps("depth.txt")
offset_ms = [(min(depth, key=lambda d: abs(d - t)) - t) * 1000 for t in rgb]
gt = np.loadtxt(f"{dataset}/groundtruth.txt", comments="#")
position = lambda t: np.array([np.interp(t, gt[:, 0], gt[:, k]) for k in (1, 2, 3)])
assert len(lines) == 4 * (len(rgb) - 1), "expected 4 rounds per tracked frame"
rows = []
print("frame  depth offset prev/cur [ms]  step [mm]  F round 1  F rounds 2-4 (mean)")
for f in range(len(rgb) - 1):
    F = [float(re.search(r"F=(\S+)", lines[4 * f + k]).group(1)) for k in range(4)]
    step = np.linalg.norm(position(rgb[f + 1]) - position(rgb[f])) * 1000
    rows.append((offset_ms[f], step, F[0], np.mean(F[1:])))
    print(f"{f + 1:5d}  {offset_ms[f]:7.1f} / {offset_ms[f + 1]:6.1f}        {step:6.1f}     {F[0]:7.2f}     {np.mean(F[1:]):7.2f}")
a = np.array(rows)
print(f"correlation of the later rounds' F with the step: {np.corrcoef(a[:, 1], a[:, 3])[0, 1]:.2f}")
print(f"later rounds' F, previous depth map after the colour image: {a[a[:, 0] > 0, 3].mean():.2f}"
      f" ({int((a[:, 0] > 0).sum())} frames); before it: {a[a[:, 0] < 0, 3].mean():.2f} ({int((a[:, 0] < 0).sum())})")
