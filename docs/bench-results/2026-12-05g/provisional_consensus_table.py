"""The map tracker's default screen with and without the new points' own consensus, run by run.

Usage: provisional_consensus_table.py WITHOUT_DIR WITH_DIR [CSV]
Each DIR is an `hbos-dynbench --tracker map --screens default` output folder; runs are paired by
cell name. Markdown on stdout, per (scenario, mask): mean ATE, runs lower / higher, the
person's matches kept and the statics dropped (pooled), the runs that moved by more than
0.05 cm. Then all runs: mean ATE and RPE, counts, Wilcoxon p. CSV (optional): every run.
"""
import json,glob,os,sys,collections,statistics
from scipy.stats import wilcoxon
def load(d):
    out={}
    for f in glob.glob(os.path.join(d,'cells','*','cell.json')):
        j=json.load(open(f))['metrics']
        out[os.path.basename(os.path.dirname(f))]=j
    return out
a=load(sys.argv[1]); b=load(sys.argv[2])
common=sorted(set(a)&set(b))
g=collections.defaultdict(list)
for k in common:
    parts=k.split('_')
    scen='_'.join(parts[:2]); mask='_'.join(parts[3:-1])
    g[(scen,mask)].append(k)
print('| scenario | mask | runs | mean ATE cm base -> var | lower/higher | dyn kept % | static dropped % | changed runs |')
print('|---|---|---:|---:|---:|---:|---:|---|')
A=[];B=[];RA=[];RB=[]
for key,ks in sorted(g.items()):
    x=[a[k]['ate_rmse_m']*100 for k in ks]; y=[b[k]['ate_rmse_m']*100 for k in ks]
    A+=x;B+=y
    RA+=[a[k]['rpe_trans_m_per_frame']*1000 for k in ks]; RB+=[b[k]['rpe_trans_m_per_frame']*1000 for k in ks]
    dk=lambda m,ks: 100*sum(m[k]['dynamic_kept'] for k in ks)/max(1,sum(m[k]['dynamic_matches'] for k in ks))
    sd=lambda m,ks: 100*sum(m[k]['static_dropped'] for k in ks)/max(1,sum(m[k]['static_matches'] for k in ks))
    ch=' '.join(f"{k.split('_')[2]}:{a[k]['ate_rmse_m']*100:.2f}->{b[k]['ate_rmse_m']*100:.2f}" for k in ks if abs(a[k]['ate_rmse_m']-b[k]['ate_rmse_m'])>0.0005)
    print(f"| {key[0]} | {key[1]} | {len(ks)} | {statistics.mean(x):.3f} -> {statistics.mean(y):.3f} | {sum(q<p for p,q in zip(x,y))}/{sum(q>p for p,q in zip(x,y))} | {dk(a,ks):.1f} -> {dk(b,ks):.1f} | {sd(a,ks):.2f} -> {sd(b,ks):.2f} | {ch} |")
p=wilcoxon(A,B).pvalue if any(p!=q for p,q in zip(A,B)) else 1
if len(sys.argv) > 3:
    import csv
    with open(sys.argv[3], 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['run', 'ate_cm_without', 'ate_cm_with', 'rpe_mm_without', 'rpe_mm_with'])
        for k in common:
            w.writerow([k, f"{a[k]['ate_rmse_m']*100:.4f}", f"{b[k]['ate_rmse_m']*100:.4f}",
                        f"{a[k]['rpe_trans_m_per_frame']*1000:.4f}",
                        f"{b[k]['rpe_trans_m_per_frame']*1000:.4f}"])
print(f"\nall {len(A)} runs: ATE mean {statistics.mean(A):.3f} -> {statistics.mean(B):.3f} cm, lower {sum(q<p for p,q in zip(A,B))} higher {sum(q>p for p,q in zip(A,B))}, Wilcoxon p {p:.3g}; RPE mean {statistics.mean(RA):.3f} -> {statistics.mean(RB):.3f} mm/frame, lower {sum(q<p for p,q in zip(RA,RB))} higher {sum(q>p for p,q in zip(RA,RB))}; worst {max(B):.2f} cm")
