"""Local bundle adjustment variants against the map tracker without it, run by run.

Usage: local_ba_table.py [--csv PATH] BASELINE_DIR NAME=DIR [NAME=DIR ...] > local_ba_seeds1to5.md
Each DIR holds one hbos-slam --tracker map output folder per run (<scenario>_s<seed>_<mask>,
/work/ab/spread/run.sh's layout); runs are paired with BASELINE_DIR's by folder name.
Writes a Markdown summary on stdout and the runs as CSV to PATH (default: local_ba_runs.csv
beside this script).
"""
import csv, glob, json, os, statistics, sys
from scipy.stats import wilcoxon


def load(folder):
    runs = {}
    for f in glob.glob(os.path.join(folder, '*', 'summary.json')):
        j = json.load(open(f))
        runs[os.path.basename(os.path.dirname(f))] = (j['ate_m']['rmse'] * 100,
                                                      j['rpe_trans_mm_per_frame']['rmse'])
    return runs


args = sys.argv[1:]
csv_path = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'local_ba_runs.csv')
if args[:1] == ['--csv']:
    csv_path, args = args[1], args[2:]
base = load(args[0])
variants = [a.split('=', 1) for a in args[1:]]
print('| variant | runs | ATE lower / higher | mean ATE [cm], without -> with | worst ATE [cm] '
      '| RPE lower / higher | mean RPE [mm/frame] | Wilcoxon p (ATE) |')
print('|---|---:|---:|---:|---:|---:|---:|---:|')
rows = []
for name, folder in variants:
    v = load(folder)
    common = sorted(set(v) & set(base))
    a = [base[r][0] for r in common]
    b = [v[r][0] for r in common]
    ra = [base[r][1] for r in common]
    rb = [v[r][1] for r in common]
    lower = sum(y < x for x, y in zip(a, b))
    higher = sum(y > x for x, y in zip(a, b))
    rlower = sum(y < x for x, y in zip(ra, rb))
    rhigher = sum(y > x for x, y in zip(ra, rb))
    worst = max(common, key=lambda r: v[r][0])
    print(f'| {name} | {len(common)} | {lower} / {higher} | {statistics.mean(a):.3f} -> '
          f'{statistics.mean(b):.3f} | {v[worst][0]:.2f} ({worst}) | {rlower} / {rhigher} | '
          f'{statistics.mean(ra):.2f} -> {statistics.mean(rb):.2f} | {wilcoxon(a, b).pvalue:.3g} |')
    rows += [(name, r, base[r][0], v[r][0], base[r][1], v[r][1]) for r in common]
with open(csv_path, 'w',
          newline='') as out:
    w = csv.writer(out)
    w.writerow(['variant', 'run', 'ate_cm_without', 'ate_cm_with', 'rpe_mm_without',
                'rpe_mm_with'])
    for row in rows:
        w.writerow([row[0], row[1]] + [f'{x:.4f}' for x in row[2:]])
