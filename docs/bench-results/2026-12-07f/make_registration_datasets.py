"""The 37 real fr1/xyz frames (PNG originals in ../shared) with each depth map shifted by whole
pixels against its colour image, to test whether a depth-colour registration error is what leaves
a residual field after the refinement that no camera motion gives (stop 50). A depth pixel moved
off the image is dropped; a pixel with nothing moved into it has no depth (0, as the sensor
writes). Colour images, stamps and ground truth are links to the originals.
usage: python3 make_registration_datasets.py SHARED_FR1_DIR OUT_DIR DX,DY [DX,DY ...]
"""
import os
import sys

import numpy as np
from PIL import Image

src, out, *shifts = sys.argv[1:]
for shift in shifts:
    dx, dy = (int(s) for s in shift.split(","))
    d = f"{out}/depth_shift_{dx}_{dy}"
    os.makedirs(f"{d}/depth", exist_ok=True)
    for entry in ("rgb", "rgb.txt", "depth.txt", "groundtruth.txt"):
        if not os.path.exists(f"{d}/{entry}"):
            os.symlink(os.path.abspath(f"{src}/{entry}"), f"{d}/{entry}")
    for name in sorted(os.listdir(f"{src}/depth")):
        z = np.asarray(Image.open(f"{src}/depth/{name}"))
        moved = np.zeros_like(z)
        h, w = z.shape
        # moved[v + dy, u + dx] = z[v, u] where both are inside the image.
        moved[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)] = \
            z[max(-dy, 0):h + min(-dy, 0), max(-dx, 0):w + min(-dx, 0)]
        Image.fromarray(moved).save(f"{d}/depth/{name}")
    print(f"{d}: {len(os.listdir(f'{d}/depth'))} depth maps moved by ({dx}, {dy}) px")
