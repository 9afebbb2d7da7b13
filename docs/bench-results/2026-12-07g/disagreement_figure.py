"""Draws docs/figures/static_disagreement.png from the two kept hbos-screening-eval reports
(eval_fixture.json, eval_holdout.json beside this script): per collection and rough pose, the
reference residual of every static, of the statics only the default's evidence drops, and of
those only chi^2 drops (boxes: quartiles, whiskers: deciles 1 and 9, line: median), and the share
of each group that lies beside a person.
Run from the repository root: /usr/bin/python3 docs/bench-results/2026-12-07g/disagreement_figure.py"""
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
out = os.path.join(here, "..", "..", "figures", "static_disagreement.png")
groups = [("all", "every static", "#9e9e9e"),
          ("only_default_by_evidence", "only the default's evidence drops", "#d95f02"),
          ("only_chi2", "only chi² drops", "#1b9e77")]
panels = []
for collection in ("fixture", "holdout"):
    report = json.load(open(os.path.join(here, f"eval_{collection}.json")))
    for pose, pose_name in (("ransac", "RANSAC"), ("pgt", "perturbed GT")):
        panels.append((f"{collection}\n{pose_name}", report["static_disagreement_pooled"][pose]))

fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [3, 2]})
width = 0.26
for k, (name, d) in enumerate(panels):
    q = d["reference_residual_quantiles"]
    for g, (key, label, colour) in enumerate(groups):
        q10, q25, q50, q75, q90 = q[key]
        x = k + (g - 1) * width
        left.bxp([{"whislo": q10, "q1": q25, "med": q50, "q3": q75, "whishi": q90, "fliers": []}],
                 positions=[x], widths=width * 0.85, patch_artist=True, showfliers=False,
                 boxprops={"facecolor": colour, "alpha": 0.8},
                 medianprops={"color": "black"})
left.set_xticks(range(len(panels)))
left.set_xticklabels([p[0] for p in panels])
left.set_ylabel("residual under the reference pose |r| / σ  [px/σ]")
left.set_title("Statics (labels' own) under the reference pose, cases with a person")
left.legend(handles=[matplotlib.patches.Patch(color=c, alpha=0.8, label=l) for _, l, c in groups],
            loc="upper left", fontsize=8, ncol=3)
left.set_ylim(0.0, 3.0)
left.grid(axis="y", alpha=0.3)

share_all = [100.0 * d["beside_person"] / d["statics"] for _, d in panels]
share_ev = [100.0 * d["only_default_by_evidence_beside_person"] / d["only_default_by_evidence"]
            for _, d in panels]
xs = range(len(panels))
right.bar([x - 0.2 for x in xs], share_all, 0.4, color="#9e9e9e", label="every static")
right.bar([x + 0.2 for x in xs], share_ev, 0.4, color="#d95f02",
          label="only the default's evidence drops")
right.set_xticks(list(xs))
right.set_xticklabels([p[0] for p in panels])
right.set_ylabel("% within 15 px of a dynamic keypoint")
right.set_title("Beside the person")
right.legend(fontsize=8)
right.grid(axis="y", alpha=0.3)
fig.tight_layout()
fig.savefig(out, dpi=110)
print("wrote", os.path.normpath(out))
