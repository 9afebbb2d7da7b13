"""Three pairings of the 37 real fr1/xyz frames (PNG originals in ../shared) with their depth maps,
to test whether the depth-colour time offset is what leaves an affine residual field after the
refinement (stop 47). rec: each colour image with the nearest depth map, as recorded (12-17 ms);
prev / next: with the depth map one before / after that one (17-52 ms). The depth stamps are set
to the colour stamps so that the front end pairs them; the true offsets go to offsets.txt.
usage: python3 make_timing_datasets.py SHARED_FR1_DIR OUT_DIR
"""
import os
import sys

src, out = sys.argv[1:]
rows = lambda f: [l.split() for l in open(f"{src}/{f}") if not l.startswith("#")]
rgb, dep = rows("rgb.txt"), rows("depth.txt")
nearest = [min(range(len(dep)), key=lambda j: abs(float(dep[j][0]) - float(r[0]))) for r in rgb]
for name, shift in (("rec", 0), ("prev", -1), ("next", 1)):
    d = f"{out}/timing_{name}"
    os.makedirs(d, exist_ok=True)
    for entry in ("rgb", "depth", "groundtruth.txt"):
        if not os.path.exists(f"{d}/{entry}"):
            os.symlink(os.path.abspath(f"{src}/{entry}"), f"{d}/{entry}")
    colour, depth, offsets = [], [], []
    for k, r in enumerate(rgb):
        j = nearest[k] + shift
        if not 0 <= j < len(dep):
            continue
        colour.append(f"{r[0]} {r[1]}")
        depth.append(f"{r[0]} {dep[j][1]}")
        offsets.append((float(dep[j][0]) - float(r[0])) * 1000)
    open(f"{d}/rgb.txt", "w").write("# colour images\n" + "\n".join(colour) + "\n")
    open(f"{d}/depth.txt", "w").write("# depth maps, stamped with their colour image's stamp\n" + "\n".join(depth) + "\n")
    open(f"{d}/offsets.txt", "w").write("\n".join(f"{o:.1f}" for o in offsets) + "\n")
    mean = sum(abs(o) for o in offsets) / len(offsets)
    print(f"{name}: {len(colour)} pairs, mean |depth - colour| {mean:.1f} ms, {min(offsets):.1f} .. {max(offsets):.1f}")
