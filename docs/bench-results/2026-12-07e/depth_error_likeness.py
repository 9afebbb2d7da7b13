"""Is the real frames' non-rigid residual field a smooth error of the depth sensor? (stop 49)

Reads the X_FDUMP file of stop 48's throwaway dump build (../2026-12-07d/
field_dump_real_fr1_png_static.txt.gz, gunzipped; four field fits per frame pair, round 1 first)
and the ground truth of ../shared/data/tum_fr1_xyz_first37.

A relative depth error e(p) on the previous frame's point moves it along that camera's ray, and
its prediction in the current frame by
    du = -e fx q (tx - x tz),   dv = -e fy q (ty - y tz)
where t is the previous camera's centre in the current camera (from the ground truth), (x, y)
the normalised prediction and q its inverse depth. With e a polynomial in (x, y), each term is
one more linear column. A constant e is a global depth scale (stop 47: ruled out) and lies in
the span of the pose columns. The test is the quadratic e: its five non-constant terms.

On the support the affine fit picks (field_pose_likeness.support), per fit:
  P      a constant plus the pixel motion of a small camera motion (stop 48);
  P+D    P plus the depth-error columns built with the true t;
  P+D'   the same columns built with a placebo t: another pair's (pair + 11) or a random
         direction of the same length. A smooth depth error explains the field only if the
         true t does clearly better than the placebos.
Also the quadratic coefficients of the last round of each pair: a sensor's error map is the
same in every pair, so its coefficients would agree in sign across pairs.

usage: python3 depth_error_likeness.py DUMP GROUND_TRUTH_DIR
"""
import sys
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-12-07d"))
import field_pose_likeness as fpl  # noqa: E402  (the stop 48 script: blocks, support, rss, f_test)

TERMS = ("x", "y", "xx", "xy", "yy")


def relative_translations(ground_truth_dir):
    """t of T_{k <- k-1} for consecutive colour frames, the ground truth interpolated."""
    stamps = [float(line.split()[0]) for line in open(ground_truth_dir / "rgb.txt") if not line.startswith("#")]
    gt = np.array([[float(v) for v in line.split()] for line in open(ground_truth_dir / "groundtruth.txt")
                   if not line.startswith("#")])

    def pose_at(t):
        i = np.searchsorted(gt[:, 0], t)
        a, b = gt[i - 1], gt[i]
        s = (t - a[0]) / (b[0] - a[0])
        T = np.eye(4)
        T[:3, :3] = Rotation.from_quat(a[4:8] if s < 0.5 else b[4:8]).as_matrix()
        T[:3, 3] = a[1:4] * (1 - s) + b[1:4] * s
        return T

    poses = [pose_at(t) for t in stamps]
    return [(np.linalg.inv(poses[k]) @ poses[k - 1])[:3, 3] for k in range(1, len(poses))]


def designs(d, cam):
    """P's columns, the affine ones, and the depth-error columns for a translation t."""
    fx, fy, cx, cy = cam
    const, affine, pose = fpl.design_columns(d, cam)
    x, y, q = (d[:, 0] - cx) / fx, (d[:, 1] - cy) / fy, 1.0 / d[:, 5]
    terms = {"x": x, "y": y, "xx": x * x, "xy": x * y, "yy": y * y}

    def depth_error(t):
        bu, bv = -fx * q * (t[0] - x * t[2]), -fy * q * (t[1] - y * t[2])
        return np.vstack([np.column_stack([terms[k] * bu for k in TERMS]),
                          np.column_stack([terms[k] * bv for k in TERMS])])

    return np.hstack([const, pose]), affine, depth_error


def main():
    dump, gt_dir = sys.argv[1], Path(sys.argv[2])
    cam = fpl.CAMERAS["tum1"]
    ts = relative_translations(gt_dir)
    fits = list(fpl.blocks(dump))
    assert len(fits) == 4 * len(ts), f"{len(fits)} fits for {len(ts)} pairs: expected four per pair"
    rng = np.random.default_rng(1)
    stats_by_round = {}
    last_round_coefficients = []
    for i, (head, d) in enumerate(fits):
        pair, rnd = divmod(i, 4)
        keep = fpl.support(d, d[:, 4], float(head["window"]))
        d = d[keep]
        if len(d) < 20:
            continue
        P, A, depth_error = designs(d, cam)
        target = np.concatenate([d[:, 2], d[:, 3]])
        w = np.concatenate([d[:, 4], d[:, 4]])
        rows = len(target)
        mP, mPA = fpl.rss(P, target, w), fpl.rss(np.hstack([P, A]), target, w)
        t_true = ts[pair]
        t_random = rng.normal(size=3)
        t_random *= np.linalg.norm(t_true) / np.linalg.norm(t_random)
        rec = {"A|P": fpl.f_test(mP, mPA, rows)[0], "|t| mm": 1000 * np.linalg.norm(t_true)}
        for label, t in (("true t", t_true), ("other pair's t", ts[(pair + 11) % len(ts)]),
                         ("random direction", t_random)):
            PD = np.hstack([P, depth_error(t)])
            mPD, mPDA = fpl.rss(PD, target, w), fpl.rss(np.hstack([PD, A]), target, w)
            rec[f"D|P, {label}"] = fpl.f_test(mP, mPD, rows)[0]
            rec[f"A|P+D, {label}"] = fpl.f_test(mPD, mPDA, rows)[0]
            if label == "true t" and rnd == 3:
                sw = np.sqrt(w)
                coef = np.linalg.lstsq(PD * sw[:, None], target * sw, rcond=None)[0]
                last_round_coefficients.append(coef[P.shape[1]:])
        stats_by_round.setdefault("round 1" if rnd == 0 else "rounds 2-4", []).append(rec)
    for label, recs in stats_by_round.items():
        print(f"{label}: {len(recs)} fits; medians over the fits")
        for key in recs[0]:
            print(f"  {key:32s} {np.median([r[key] for r in recs]):8.2f}")
    depths = np.concatenate([d[:, 5] for _, d in fits])
    step = np.median([np.linalg.norm(t) for t in ts])
    print(f"median depth {np.median(depths):.3f} m, median step {1000 * step:.2f} mm: a prediction moves "
          f"{fpl.CAMERAS['tum1'][0] * step / np.median(depths):.2f} px per unit of relative depth error")
    C = np.array(last_round_coefficients)
    print("quadratic depth error, true t, last round of each pair (%d pairs):" % len(C))
    for j, k in enumerate(TERMS):
        lo, mid, hi = np.percentile(C[:, j], [25, 50, 75])
        print(f"  {k:3s} median {mid:+.3f}  quartiles {lo:+.3f} .. {hi:+.3f}  share positive {np.mean(C[:, j] > 0):.2f}")


if __name__ == "__main__":
    main()
