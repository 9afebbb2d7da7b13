# Candidate default vs current default vs chi2, cell by cell, from hbos-dynbench JSONs.
# usage: compare3.py current.json candidate_with_chi2.json (the same file twice: the default against chi2)
import json, sys, collections
from scipy.stats import wilcoxon
def cells(p):
    out = {}
    for c in json.load(open(p))['cells']:
        toks = c['id'].split('_'); screen = toks[-1]
        out[(tuple(toks[:-1]), screen)] = c['metrics']
    return out
cur = cells(sys.argv[1]); cand = cells(sys.argv[2])
keys = sorted(k for (k, s) in cand if s == 'default' and (k, 'chi2') in cand and (k, 'default') in cur)
def row(k):
    toks = list(k); si = [j for j, t in enumerate(toks) if t.startswith('s') and t[1:].isdigit()][0]
    return '_'.join(toks[:si]), '_'.join(toks[si + 1:]) or 'none'
rows = collections.defaultdict(list)
for k in keys:
    a, b, c = cur[(k, 'default')], cand[(k, 'default')], cand[(k, 'chi2')]
    rows[row(k)].append([m['ate_rmse_m'] * 100 for m in (a, b, c)] + [m['rpe_trans_m_per_frame'] * 1000 for m in (a, b, c)]
                        + [m['static_dropped_share'] * 100 for m in (a, b, c)])
print("scenario mask n | ATE cm: current / candidate / chi2 | cand<chi2 | cur<chi2 | cand<cur | RPE mm: cur / cand / chi2 | static lost %: cur / cand / chi2")
allv = []
for key, v in sorted(rows.items()):
    n = len(v); m = lambda j: sum(x[j] for x in v) / n; allv += v
    print(f"{key[0]:12s} {key[1]:14s} {n} | {m(0):.3f} / {m(1):.3f} / {m(2):.3f} | {sum(x[1]<x[2] for x in v)} | {sum(x[0]<x[2] for x in v)} | {sum(x[1]<x[0] for x in v)}/{sum(x[1]>x[0] for x in v)} | {m(3):.2f} / {m(4):.2f} / {m(5):.2f} | {m(6):.1f} / {m(7):.1f} / {m(8):.1f}")
n = len(allv); m = lambda j: sum(x[j] for x in allv) / n
print(f"all {n} runs: mean ATE {m(0):.3f} / {m(1):.3f} / {m(2):.3f} cm; RPE {m(3):.2f} / {m(4):.2f} / {m(5):.2f} mm/frame")
for name, i, j in (("candidate vs chi2", 1, 2), ("current vs chi2", 0, 2), ("candidate vs current", 1, 0)):
    d = [x[i] - x[j] for x in allv]
    if not any(d):
        print(f"{name}: identical on all {n} runs"); continue
    print(f"{name}: ATE lower on {sum(e<0 for e in d)}, higher on {sum(e>0 for e in d)} of {n}; Wilcoxon p = {wilcoxon(d).pvalue:.3g}; RPE lower on {sum(x[i+3]<x[j+3] for x in allv)}")
