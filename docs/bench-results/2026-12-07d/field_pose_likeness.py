"""Is the residual field the default screen fits after a refinement one a pose change could give?
(stop 48)

Reads the X_FDUMP files of the throwaway dump build (field_dump_patch.diff): one block per field
fit on the matches that look static, a "FIT floor=... n=... scale=... window=..." line, then one
"u v rx ry information depth" row per match of the fit set (predicted pixel [px], residual [px],
1/sigma^2, depth [m]).

For each fit: the robust affine fit of residual_field.hpp (weighted median start, mean shift,
reweighted affine fits inside the window) picks the supporting matches. On that fixed set, four
weighted least-squares models of the residual vector r(p):
  C   a constant (2 parameters);
  A   affine in p (6), what the screen fits;
  P   a constant plus the pixel motion of a small camera motion (6 + 2): for a point at normalised
      (x, y) and inverse depth q, du = fx (q tx - x q tz - x y wx + (1 + x^2) wy - y wz),
      dv = fy (q ty - y q tz - (1 + y^2) wx + x y wy + x wz);
  PA  both (12; least squares on the stacked columns, rank-checked).
Nested F statistics: A over C (stop 47's diagnostic), P over C, and A over P: the affine structure
a rigid motion of the camera cannot give. A field left by pose error is pose-like (A over P near
1); one left by anything else (the images, the depth maps) is not.

usage: python3 field_pose_likeness.py CAMERA DUMP [DUMP...]   (CAMERA: tum1 or tum3)
"""
import sys

import numpy as np
from scipy import stats

CAMERAS = {"tum1": (517.306408, 516.469215, 318.643040, 255.313989),
           "tum3": (535.4, 539.2, 320.1, 247.6)}


def blocks(path):
    head, rows = None, []
    for line in open(path):
        if line.startswith("FIT"):
            if head is not None:
                yield head, np.array(rows, dtype=float).reshape(-1, 6)
            head = dict(kv.split("=") for kv in line.split()[1:])
            rows = []
        else:
            rows.append(line.split())
    if head is not None:
        yield head, np.array(rows, dtype=float).reshape(-1, 6)


def weighted_median(x, w):
    o = np.argsort(x, kind="stable")
    c = np.cumsum(w[o])
    return x[o][np.searchsorted(c, c[-1] / 2)]


def support(d, w, window):
    """The samples inside the affine fit's window, as residual_field.hpp selects them."""
    u, v, rx, ry = d[:, 0], d[:, 1], d[:, 2], d[:, 3]
    w2 = window * window
    c = np.array([weighted_median(rx, w), weighted_median(ry, w)])
    for _ in range(5):
        inside = ((rx - c[0]) ** 2 + (ry - c[1]) ** 2) * w <= w2
        if w[inside].sum() <= 0:
            break
        c = np.array([np.average(rx[inside], weights=w[inside]), np.average(ry[inside], weights=w[inside])])
    o = np.array([u.mean(), v.mean()])
    X = np.column_stack([np.ones_like(u), (u - o[0]) / 100, (v - o[1]) / 100])
    bx, by = np.array([c[0], 0, 0]), np.array([c[1], 0, 0])
    for _ in range(5):
        ex, ey = rx - X @ bx, ry - X @ by
        inside = (ex * ex + ey * ey) * w <= w2
        if inside.sum() < 6:
            break
        sw = np.sqrt(w[inside])[:, None]
        bx = np.linalg.lstsq(X[inside] * sw, rx[inside] * sw[:, 0], rcond=None)[0]
        by = np.linalg.lstsq(X[inside] * sw, ry[inside] * sw[:, 0], rcond=None)[0]
    ex, ey = rx - X @ bx, ry - X @ by
    return (ex * ex + ey * ey) * w <= w2


def rss(design, target, w):
    """Weighted residual sum of squares of a least-squares fit; the rank used."""
    sw = np.sqrt(w)
    A, b = design * sw[:, None], target * sw
    coef, _, rank, _ = np.linalg.lstsq(A, b, rcond=None)
    r = b - A @ coef
    return float(r @ r), int(rank)


def design_columns(d, cam):
    """The stacked columns of the models for the rows of d (the n u-components, then the n
    v-components): the constant (2), the affine terms (4) and the small camera motion (6)."""
    fx, fy, cx, cy = cam
    u, v, z = d[:, 0], d[:, 1], d[:, 5]
    n = len(u)
    x, y, q = (u - cx) / fx, (v - cy) / fy, 1.0 / z
    zero, one = np.zeros(n), np.ones(n)
    const = np.vstack([np.column_stack([one, zero]), np.column_stack([zero, one])])
    o = np.array([u.mean(), v.mean()])
    du, dv = (u - o[0]) / 100, (v - o[1]) / 100
    affine = np.vstack([np.column_stack([du, dv, zero, zero]), np.column_stack([zero, zero, du, dv])])
    pose = np.vstack([
        np.column_stack([fx * q, zero, -fx * x * q, -fx * x * y, fx * (1 + x * x), -fx * y]),
        np.column_stack([zero, fy * q, -fy * y * q, -fy * (1 + y * y), fy * x * y, fy * x])])
    return const, affine, pose


def models(d, cam):
    u, v, rx, ry, w, z = d.T
    n = len(u)
    const, affine, pose = design_columns(d, cam)
    target = np.concatenate([rx, ry])
    ww = np.concatenate([w, w])
    out = {}
    for name, design in (("C", const), ("A", np.hstack([const, affine])),
                         ("P", np.hstack([const, pose])), ("PA", np.hstack([const, affine, pose]))):
        out[name] = rss(design, target, ww)
    return out, 2 * n


def f_test(small, large, rows):
    (r0, p0), (r1, p1) = small, large
    df1, df2 = p1 - p0, rows - p1
    if df1 <= 0 or df2 <= 0 or r1 <= 0:
        return float("nan"), float("nan")
    F = ((r0 - r1) / df1) / (r1 / df2)
    return F, float(stats.f.sf(F, df1, df2))


def summarise(path, cam):
    groups = {}
    for head, d in blocks(path):
        if len(d) < 20:
            continue
        keep = support(d, d[:, 4], float(head["window"]))
        if keep.sum() < 20:
            continue
        m, rows = models(d[keep], cam)
        rec = {"A|C": f_test(m["C"], m["A"], rows), "P|C": f_test(m["C"], m["P"], rows),
               "A|P": f_test(m["P"], m["PA"], rows), "P|A": f_test(m["A"], m["PA"], rows)}
        groups.setdefault(head["floor"], []).append(rec)
    for floor, recs in sorted(groups.items(), reverse=True):
        label = "round 1   " if float(floor) > 2 else "rounds 2-4"
        parts = []
        for key in ("A|C", "P|C", "A|P", "P|A"):
            F = np.array([r[key][0] for r in recs])
            p = np.array([r[key][1] for r in recs])
            parts.append(f"{key} F median {np.nanmedian(F):6.2f} share p<0.05 {np.nanmean(p < 0.05):.2f}")
        print(f"{path:28s} {label} fits {len(recs):5d}  " + "  ".join(parts))


def main():
    cam = CAMERAS[sys.argv[1]]
    for path in sys.argv[2:]:
        summarise(path, cam)


if __name__ == "__main__":
    main()
