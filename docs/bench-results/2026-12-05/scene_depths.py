#!/usr/bin/env python3
"""Stop 29: how far the room and the person are, and how much of the image the person covers,
in the rendered frames results.md cites (median and 5-95 % depths from the depth image, the
person's share of pixels from objects/); then the frames of walking_rpy seed 5 where a person is
in view and the person_missed mask covers none of it.
Run: python3 scene_depths.py CACHE_DIR
"""
import os
import sys

import numpy as np
from PIL import Image

FRAMES = {"walking_rpy_seed5_300f": (150, 158, 162, 165), "walking_rpy_seed3_300f": (160, 170, 180)}


def main():
    cache = sys.argv[1]
    for sequence, frames in FRAMES.items():
        d = os.path.join(cache, sequence)
        names = [line.split()[1] for line in open(os.path.join(d, "rgb.txt"))
                 if not line.startswith("#")]
        for f in frames:
            name = os.path.basename(names[f])
            depth = np.array(Image.open(os.path.join(d, "depth", name))).astype(float) / 5000.0
            person = np.array(Image.open(os.path.join(d, "objects", name))) > 0
            room = depth[~person & (depth > 0)]
            them = depth[person & (depth > 0)]
            print(f"{sequence} frame {f}: room depth median {np.median(room):.2f} m "
                  f"(5-95 % {np.percentile(room, 5):.2f}-{np.percentile(room, 95):.2f}), person "
                  f"median {np.median(them):.2f} m (5-95 % {np.percentile(them, 5):.2f}-"
                  f"{np.percentile(them, 95):.2f}), person pixels {100 * person.mean():.1f} %")
    d = os.path.join(cache, "walking_rpy_seed5_300f")
    names = [line.split()[1] for line in open(os.path.join(d, "rgb.txt")) if not line.startswith("#")]
    missed = []
    for f, path in enumerate(names):
        name = os.path.basename(path)
        person = np.array(Image.open(os.path.join(d, "objects", name))) > 0
        masked = np.array(Image.open(os.path.join(d, "masks", "person_missed", name))) == 0
        if person.any() and not (person & masked).any():
            missed.append(f)
    print(f"walking_rpy_seed5_300f: the person is in view and wholly unmasked in {len(missed)} "
          f"frames, {missed[0]}-{missed[-1]}" + (" (contiguous)" if missed[-1] - missed[0] + 1 ==
                                                  len(missed) else ""))


if __name__ == "__main__":
    main()
