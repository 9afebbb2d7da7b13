"""Share of valid depth pixels and of sharp depth edges (a 4-neighbour more than 10 % nearer or
farther, both valid) in 5 depth maps spread over each sequence (stop 50): is the real sensor's
depth smoother or holier at edges than the renderer's?
usage: python3 depth_edge_stats.py DEPTH_DIR..."""
import os
import sys

import numpy as np
from PIL import Image

for d in sys.argv[1:]:
    names = sorted(os.listdir(d))
    picked = names[::max(1, len(names) // 5)][:5]
    valid, edges = [], []
    for name in picked:
        z = np.asarray(Image.open(f"{d}/{name}")).astype(float)
        valid.append((z > 0).mean())
        sharp = np.zeros_like(z, bool)
        for a, b, at in ((z[:, 1:], z[:, :-1], (slice(None), slice(1, None))),
                         (z[1:, :], z[:-1, :], (slice(1, None), slice(None)))):
            sharp[at] |= (a > 0) & (b > 0) & (np.abs(a - b) > 0.1 * np.minimum(a, b))
        edges.append(sharp.mean())
    print(f"{d}: valid {np.mean(valid):.3f}, sharp-edge pixels {np.mean(edges):.4f}")
