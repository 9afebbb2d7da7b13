"""The labelled real residual cases built from the 37 fr1 frames (PNG originals) as recorded and
with every depth map moved up 8 px (stop 50): per case, the default's and chi^2's static loss
and dynamics kept, and issue 7's per-case verdict, side by side; then the counts.
usage: python3 cases_depth_shift_compare.py EVAL_AS_RECORDED.json EVAL_MOVED.json"""
import json
import sys

a, b = (json.load(open(p)) for p in sys.argv[1:3])
rows = {c["name"]: c for c in a["cases"]}
print("case | as recorded: default static% / dyn% , chi2 static% / dyn% , verdict | depth moved up 8 px: the same")
gap = {"as recorded": [], "moved": []}
for c in b["cases"]:
    o = rows[c["name"]]
    cells = []
    for label, x in (("as recorded", o), ("moved", c)):
        d, q = x["strategies"]["default"], x["strategies"]["chi2"]
        dyn = lambda s: "-" if s["dynamics"] == 0 else f"{s['dynamic_kept_pct']:.1f}"
        cells.append(f"{d['static_dropped_pct']:.1f} / {dyn(d)} , {q['static_dropped_pct']:.1f} / {dyn(q)} , "
                     f"{'pass' if x['acceptance']['pass'] else 'FAIL'}")
        if x["rough_pose"] == "ransac":
            gap[label].append(d["static_dropped_pct"] - q["static_dropped_pct"])
    print(f"{c['name']:28s} | {cells[0]:34s} | {cells[1]}")
for label, x in (("as recorded", a), ("moved", b)):
    passed = sum(c["acceptance"]["pass"] for c in x["cases"])
    over = sum(g > 0 for g in gap[label])
    print(f"{label}: {passed} of {len(x['cases'])} pass; under RANSAC the default loses more statics "
          f"than chi^2 in {over} of {len(gap[label])} cases (mean gap {sum(gap[label]) / len(gap[label]):+.2f} points)")
