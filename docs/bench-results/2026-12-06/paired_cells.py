# Paired comparison of two hbos-dynbench JSON outputs, cell by cell (same ids): mean ATE, RPE,
# static loss and dynamics kept per (scenario, mask); how many cells the second run lowers.
# usage: python3 paired_cells.py A.json B.json
import json,sys
def load(p): return {c['id']:c['metrics'] for c in json.load(open(p))['cells']}
a=load(sys.argv[1]); b=load(sys.argv[2])
common = sorted(set(a) & set(b))
import collections
rows = collections.defaultdict(list)
for k in common:
    # id: <scenario>_s<seed>_<mask>_<screen>; scenario and mask may hold underscores
    toks = k.split('_')
    si = [j for j, t in enumerate(toks) if t.startswith('s') and t[1:].isdigit()][0]
    scen = '_'.join(toks[:si]); mask = '_'.join(toks[si + 1:-1])
    share = lambda m: 100 * m['dynamic_kept_share'] if m['dynamic_kept_share'] is not None else 0
    rows[(scen, mask)].append((a[k]['ate_rmse_m'] * 100, b[k]['ate_rmse_m'] * 100,
                               a[k]['rpe_trans_m_per_frame'] * 1000, b[k]['rpe_trans_m_per_frame'] * 1000,
                               a[k]['static_dropped_share'] * 100, b[k]['static_dropped_share'] * 100,
                               share(a[k]), share(b[k])))
tot=[0,0,0]
print("scenario mask n | ATE a->b (lower in) | RPE a->b | static lost a->b | dyn kept a->b")
for key,v in sorted(rows.items()):
    n=len(v); m=lambda j: sum(x[j] for x in v)/n
    lower=sum(1 for x in v if x[1]<x[0]); higher=sum(1 for x in v if x[1]>x[0])
    tot[0]+=lower; tot[1]+=higher; tot[2]+=n
    print(f"{key[0]:20s} {key[1]:14s} {n} | {m(0):.3f}->{m(1):.3f} ({lower}/{higher}) | {m(2):.2f}->{m(3):.2f} | {m(4):.1f}->{m(5):.1f} | {m(6):.1f}->{m(7):.1f}")
allv=[x for v in rows.values() for x in v]
print("all: lower", tot[0], "higher", tot[1], "of", tot[2], " mean ATE %.3f -> %.3f"%(sum(x[0] for x in allv)/len(allv), sum(x[1] for x in allv)/len(allv)))
try:
    from scipy.stats import wilcoxon
    print("wilcoxon p", wilcoxon([x[1]-x[0] for x in allv]).pvalue)
except Exception as e: print(e)
