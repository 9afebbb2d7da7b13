"""A picture of what a small camera motion leaves unexplained in the later rounds' field
(stop 49): real fr1/xyz frame pairs against rendered walking_xyz ones.

For each chosen fit (the last field fit of a frame pair, round 4), on the support the affine fit
picks (field_pose_likeness.support): fit P (a constant plus the pixel shift of a small camera
motion, stop 48), take each match's residual left after P, and average it in the cells of a
6 x 4 grid over the image (weights 1/sigma^2; cells with under 8 matches left out). Arrows are
drawn 300 times their length. A field only a pose error leaves would show no pattern; noise
leaves short arrows pointing anywhere.

Also prints, over every last fit of each dump, the cell means' rms, the matches a fit has and
the share of them in the left 60 % of the image.

usage: python3 field_after_rigid_fit_plot.py REAL_DUMP RENDERED_DUMP OUT.png
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-12-07d"))
import field_pose_likeness as fpl  # noqa: E402

SCALE, NX, NY, MIN_CELL = 300.0, 6, 4, 8


def left_after_pose(d, cam):
    rx, ry, w = d[:, 2], d[:, 3], d[:, 4]
    n = len(rx)
    const, _, pose = fpl.design_columns(d, cam)
    P = np.hstack([const, pose])
    target, ww = np.concatenate([rx, ry]), np.concatenate([w, w])
    sw = np.sqrt(ww)
    coef = np.linalg.lstsq(P * sw[:, None], target * sw, rcond=None)[0]
    left = target - P @ coef
    return left[:n], left[n:]


def cell_means(d, ex, ey):
    u, v, w = d[:, 0], d[:, 1], d[:, 4]
    cu = np.clip((u / 640 * NX).astype(int), 0, NX - 1)
    cv = np.clip((v / 480 * NY).astype(int), 0, NY - 1)
    out = []
    for i in range(NX):
        for j in range(NY):
            m = (cu == i) & (cv == j)
            if m.sum() >= MIN_CELL:
                out.append(((i + 0.5) * 640 / NX, (j + 0.5) * 480 / NY,
                            np.average(ex[m], weights=w[m]), np.average(ey[m], weights=w[m])))
    return np.array(out)


def last_fits(path, count):
    fits = list(fpl.blocks(path))
    per_pair = [fits[i] for i in range(3, len(fits), 4)]
    step = max(1, len(per_pair) // count)
    return per_pair[::step][:count]


def main():
    real, rendered, out = sys.argv[1:4]
    rows = (("real fr1/xyz", real, fpl.CAMERAS["tum1"]), ("rendered walking_xyz", rendered, fpl.CAMERAS["tum3"]))
    fig, axes = plt.subplots(2, 4, figsize=(16, 6.4))
    for r, (label, path, cam) in enumerate(rows):
        for c, (head, d) in enumerate(last_fits(path, 4)):
            d = d[fpl.support(d, d[:, 4], float(head["window"]))]
            ex, ey = left_after_pose(d, cam)
            cells = cell_means(d, ex, ey)
            ax = axes[r, c]
            ax.quiver(cells[:, 0], cells[:, 1], cells[:, 2] * SCALE, cells[:, 3] * SCALE, angles="xy",
                      scale_units="xy", scale=1, color="tab:red" if r == 0 else "tab:blue", width=0.006)
            rms = np.sqrt(np.mean(cells[:, 2] ** 2 + cells[:, 3] ** 2))
            ax.set_title(f"{label}, fit {c + 1}: cell means rms {rms:.2f} px", fontsize=9)
            ax.set_xlim(0, 640)
            ax.set_ylim(480, 0)
            ax.set_aspect("equal")
            ax.set_xticks([0, 320, 640])
            ax.set_yticks([0, 240, 480])
    for label, path, cam in rows:
        rms, size, left_share = [], [], []
        for head, d in list(fpl.blocks(path))[3::4]:
            d = d[fpl.support(d, d[:, 4], float(head["window"]))]
            size.append(len(d))
            left_share.append(np.mean(d[:, 0] < 0.6 * 640))
            cells = cell_means(d, *left_after_pose(d, cam))
            if len(cells):
                rms.append(np.sqrt(np.mean(cells[:, 2] ** 2 + cells[:, 3] ** 2)))
        q1, q2, q3 = np.percentile(rms, [25, 50, 75])
        print(f"{label}: cell means rms over {len(rms)} last fits: median {q2:.3f} px, quartiles {q1:.3f}-{q3:.3f}; "
              f"matches per fit (support) median {np.median(size):.0f}; "
              f"share in the left 60 % of the image median {np.median(left_share):.2f}")
    fig.suptitle("The later rounds' field after the best small camera motion is removed "
                 f"(cell means, arrows x{SCALE:.0f}); real frames above, rendered below", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
