#!/usr/bin/env python3
"""Tabulates hbos-slam --tracker map runs of the rendered cache, one folder per setting, by ATE
and RPE.

usage: far_points_table.py OUT.md OUT.csv NAME=FOLDER [NAME=FOLDER ...]
Each FOLDER holds <scenario>_s<seed>_<mask>/summary.json. The first setting is the baseline: each
row gives every setting's mean ATE RMSE [cm] and mean RPE [mm/frame] over the seeds every setting
ran, and for each other setting the seeds on which it is lower than the baseline. Runs missing
from some setting are listed, not skipped silently."""
import glob, json, os, re, sys

out_md, out_csv, settings = sys.argv[1], sys.argv[2], [a.split('=', 1) for a in sys.argv[3:]]
runs = {}  # (scenario, mask) -> name -> seed -> (ATE cm, RPE mm/frame)
rows_csv = []
for name, folder in settings:
    for f in sorted(glob.glob(os.path.join(folder, '*/summary.json'))):
        m = re.match(r'(walking_\w+?)_s(\d+)_(\w+)$', os.path.basename(os.path.dirname(f)))
        e = json.load(open(f))['evaluation']
        value = (e['ate']['rmse'] * 100.0, e['rpe']['trans_m']['mean'] * 1000.0)
        runs.setdefault((m.group(1), m.group(3)), {}).setdefault(name, {})[int(m.group(2))] = value
        rows_csv.append((name, m.group(1), m.group(3), int(m.group(2))) + value)
names = [n for n, _ in settings]
base = names[0]
lines = ['| scenario | mask | seeds | ' + ' | '.join(f'{n} ATE [cm] / RPE [mm/frame]' for n in names) +
         ' | ' + ' | '.join(f'{n}: ATE lower / RPE lower' for n in names[1:]) + ' |',
         '|---|---|---:|' + '---:|' * (2 * len(names) - 1)]
missing, total, lower_ate, lower_rpe = [], 0, 0, 0
for key in sorted(runs):
    row = runs[key]
    seeds = sorted(set.intersection(*[set(row.get(n, {})) for n in names]))
    every = sorted(set.union(*[set(row.get(n, {})) for n in names]))
    missing += [f'{key[0]} {key[1]} seed {s}' for s in every if s not in seeds]
    if not seeds:
        continue
    mean = lambda n, i: sum(row[n][s][i] for s in seeds) / len(seeds)
    lower = lambda n, i: sum(row[n][s][i] < row[base][s][i] for s in seeds)
    total += len(seeds)
    if len(names) > 1:
        lower_ate += lower(names[1], 0)
        lower_rpe += lower(names[1], 1)
    lines.append(f'| {key[0]} | {key[1]} | {len(seeds)} | ' +
                 ' | '.join(f'{mean(n, 0):.2f} / {mean(n, 1):.2f}' for n in names) + ' | ' +
                 ' | '.join(f'{lower(n, 0)} / {lower(n, 1)} of {len(seeds)}' for n in names[1:]) + ' |')
lines.append('')
if len(names) > 1:
    lines.append(f'{names[1]} against {base}: ATE lower on {lower_ate} of {total} runs, '
                 f'RPE lower on {lower_rpe} of {total}.')
lines.append('Runs missing from some setting: ' + ('; '.join(missing) if missing else 'none') + '.')
def write_atomically(path, text):
    """The table appears whole or not at all: written beside, then renamed."""
    with open(path + '.tmp', 'w', newline='') as f:
        f.write(text)
    os.replace(path + '.tmp', path)


write_atomically(out_md, '\n'.join(lines) + '\n')
table = [['setting', 'scenario', 'mask', 'seed', 'ate_rmse_cm', 'rpe_trans_mean_mm']]
table += [list(r[:4]) + [f'{r[4]:.4f}', f'{r[5]:.4f}'] for r in sorted(rows_csv)]
write_atomically(out_csv, ''.join(','.join(str(v) for v in row) + '\n' for row in table))
