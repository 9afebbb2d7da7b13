"""Is the real frames' non-rigid residual field a rolling shutter's? (stop 49)

Same input and support as depth_error_likeness.py (stop 48's dump of the real fr1/xyz frames).
A rolling shutter exposes row v at time (v - v0) tau: a motion that changes between two frames
then leaves a residual J(p) (m0 + s(p) m1), where J is the pinhole's motion Jacobian and s(p)
the row's place in the readout, (v - 240) / 480. So the model P + R adds the six columns
s(p) J(p) to P (a constant plus J). The placebo takes s(p) from the column, (u - 320) / 640,
which no shutter reads out by. A rolling shutter explains the field only if the row version
does clearly better than the column one.

usage: python3 rolling_shutter_likeness.py DUMP
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-12-07d"))
import field_pose_likeness as fpl  # noqa: E402


def main():
    by_round = {}
    for i, (head, d) in enumerate(fpl.blocks(sys.argv[1])):
        d = d[fpl.support(d, d[:, 4], float(head["window"]))]
        if len(d) < 20:
            continue
        u, v, rx, ry, w = d[:, :5].T
        const, A, J = fpl.design_columns(d, fpl.CAMERAS["tum1"])
        target, ww = np.concatenate([rx, ry]), np.concatenate([w, w])
        rows = len(target)
        P = np.hstack([const, J])
        mP = fpl.rss(P, target, ww)
        rec = {"A|P": fpl.f_test(mP, fpl.rss(np.hstack([P, A]), target, ww), rows)[0]}
        for label, s in (("row, a rolling shutter", (v - 240) / 480), ("column, the placebo", (u - 320) / 640)):
            PR = np.hstack([P, J * np.concatenate([s, s])[:, None]])
            mPR = fpl.rss(PR, target, ww)
            rec[f"R|P, {label}"] = fpl.f_test(mP, mPR, rows)[0]
            rec[f"A|P+R, {label}"] = fpl.f_test(mPR, fpl.rss(np.hstack([PR, A]), target, ww), rows)[0]
        by_round.setdefault("round 1" if i % 4 == 0 else "rounds 2-4", []).append(rec)
    for label, recs in by_round.items():
        print(f"{label}: {len(recs)} fits; F medians over the fits")
        for key in recs[0]:
            print(f"  {key:36s} {np.median([r[key] for r in recs]):7.2f}")


if __name__ == "__main__":
    main()
