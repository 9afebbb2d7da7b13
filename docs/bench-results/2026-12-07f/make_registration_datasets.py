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


def moved(z, dx, dy):
    """z with every pixel moved by (dx, dy): out[v + dy, u + dx] = z[v, u] inside the image."""
    out = np.zeros_like(z)
    h, w = z.shape
    out[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)] = \
        z[max(-dy, 0):h + min(-dy, 0), max(-dx, 0):w + min(-dx, 0)]
    return out


def move_file(src_png, dst_png, dx, dy):
    Image.fromarray(moved(np.asarray(Image.open(src_png)), dx, dy)).save(dst_png)


def main():
    src, out, *shifts = sys.argv[1:]
    for shift in shifts:
        dx, dy = (int(s) for s in shift.split(","))
        d = f"{out}/depth_shift_{dx}_{dy}"
        os.makedirs(f"{d}/depth", exist_ok=True)
        for entry in ("rgb", "rgb.txt", "depth.txt", "groundtruth.txt"):
            if not os.path.exists(f"{d}/{entry}"):
                os.symlink(os.path.abspath(f"{src}/{entry}"), f"{d}/{entry}")
        for name in sorted(os.listdir(f"{src}/depth")):
            move_file(f"{src}/depth/{name}", f"{d}/depth/{name}", dx, dy)
        print(f"{d}: {len(os.listdir(f'{d}/depth'))} depth maps moved by ({dx}, {dy}) px")


if __name__ == "__main__":
    main()
