#!/usr/bin/env python3
"""Tabulates hbos-slam --tracker map runs of the rendered cache, one folder per setting.

usage: spread_table.py OUT.md OUT.csv NAME=FOLDER [NAME=FOLDER ...]
Each FOLDER holds <scenario>_s<seed>_<mask>/summary.json. The first setting is the baseline:
the table gives each row's mean ATE RMSE over the seeds every setting ran, and for each other
setting the seeds on which its ATE is lower than the baseline's. Runs without a summary (a run
that did not finish) are listed, not skipped silently."""
import csv, glob, json, os, re, sys

out_md, out_csv, settings = sys.argv[1], sys.argv[2], [a.split('=', 1) for a in sys.argv[3:]]
ate = {}  # (scenario, mask) -> name -> seed -> cm
runs = []
for name, folder in settings:
    for f in sorted(glob.glob(os.path.join(folder, '*/summary.json'))):
        m = re.match(r'(walking_\w+?)_s(\d+)_(\w+)$', os.path.basename(os.path.dirname(f)))
        cm = json.load(open(f))['ate_m']['rmse'] * 100.0
        ate.setdefault((m.group(1), m.group(3)), {}).setdefault(name, {})[int(m.group(2))] = cm
        runs.append((name, m.group(1), m.group(3), int(m.group(2)), cm))
names = [n for n, _ in settings]
base = names[0]
lines = ['| scenario | mask | seeds | ' + ' | '.join(f'{n} [cm]' for n in names) + ' | ' +
         ' | '.join(f'{n} lower' for n in names[1:]) + ' |',
         '|---|---|---:|' + '---:|' * len(names) + '---:|' * (len(names) - 1)]
missing = []
for (scenario, mask) in sorted(ate):
    row = ate[(scenario, mask)]
    seeds = sorted(set.intersection(*[set(row.get(n, {})) for n in names]))
    every = sorted(set.union(*[set(row.get(n, {})) for n in names]))
    missing += [f'{scenario} {mask} seed {s}' for s in every if s not in seeds]
    if not seeds:
        continue
    mean = lambda n: sum(row[n][s] for s in seeds) / len(seeds)
    lower = lambda n: sum(row[n][s] < row[base][s] for s in seeds)
    lines.append(f'| {scenario} | {mask} | {len(seeds)} | ' +
                 ' | '.join(f'{mean(n):.2f}' for n in names) + ' | ' +
                 ' | '.join(f'{lower(n)} of {len(seeds)}' for n in names[1:]) + ' |')
lines.append('')
# Matches off the people per frame (stats.csv: matches - person_matches), mean over the runs.
statics = {}
for name, folder in settings:
    for f in sorted(glob.glob(os.path.join(folder, '*/stats.csv'))):
        scenario = re.match(r'(walking_\w+?)_s\d+_', os.path.basename(os.path.dirname(f))).group(1)
        rows = list(csv.DictReader(open(f)))
        if rows:
            per_frame = sum(int(r['matches']) - int(r['person_matches']) for r in rows) / len(rows)
            statics.setdefault(scenario, {}).setdefault(name, []).append(per_frame)
lines.append('Static matches per frame (matches off the people, mean over every run of the scenario):')
lines.append('')
lines.append('| scenario | ' + ' | '.join(names) + ' |')
lines.append('|---|' + '---:|' * len(names))
for scenario in sorted(statics):
    row = statics[scenario]
    lines.append(f'| {scenario} | ' + ' | '.join(
        f'{sum(row[n]) / len(row[n]):.0f}' if n in row else '-' for n in names) + ' |')
lines.append('')
lines.append('Runs missing from some setting: ' + ('; '.join(missing) if missing else 'none') + '.')
tmp = out_md + '.tmp'
open(tmp, 'w').write('\n'.join(lines) + '\n')
os.replace(tmp, out_md)
tmp = out_csv + '.tmp'
with open(tmp, 'w', newline='') as f:
    w = csv.writer(f, lineterminator='\n')
    w.writerow(['setting', 'scenario', 'mask', 'seed', 'ate_rmse_cm'])
    for r in sorted(runs):
        w.writerow([r[0], r[1], r[2], r[3], f'{r[4]:.4f}'])
os.replace(tmp, out_csv)
