"""A copy of rendered sequences with every depth map moved by whole pixels against its colour
image (stop 50): a depth-colour registration offset like the one the real fr1 frames seem to
carry. Everything but depth/ is a link to the original sequence.
usage: python3 shift_cache.py SRC_CACHE DST_CACHE DX,DY SEQUENCE..."""
import os
import sys
from multiprocessing import Pool

from make_registration_datasets import move_file


def main():
    src, dst, shift, *names = sys.argv[1:]
    dx, dy = (int(s) for s in shift.split(","))
    jobs = []
    for name in names:
        s, d = f"{src}/{name}", f"{dst}/{name}"
        os.makedirs(f"{d}/depth", exist_ok=True)
        for entry in os.listdir(s):
            if entry != "depth" and not os.path.exists(f"{d}/{entry}"):
                os.symlink(os.path.abspath(f"{s}/{entry}"), f"{d}/{entry}")
        jobs += [(f"{s}/depth/{f}", f"{d}/depth/{f}", dx, dy) for f in os.listdir(f"{s}/depth")
                 if not os.path.exists(f"{d}/depth/{f}")]
    with Pool(2) as pool:
        pool.starmap(move_file, jobs, chunksize=64)
    print(f"{len(jobs)} depth maps moved by ({dx}, {dy}) px into {dst}")


if __name__ == "__main__":
    main()
