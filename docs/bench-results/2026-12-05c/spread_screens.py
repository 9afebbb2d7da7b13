#!/usr/bin/env python3
"""Every screen with and without the keypoint spread, where the camera turns.

usage: spread_screens.py HELDOUT_DYNBENCH.json RUNS_DIR OUT.md
HELDOUT_DYNBENCH.json: stop 30's hbos-dynbench output for seeds 6-10 (spread off).
RUNS_DIR: scr_<screen>/<scenario>_s<seed>_<mask>/summary.json, the same runs with
--orb-spread-px 128. Per screen: the mean ATE over the runs, and its mean rank by ATE among the
screens (1 = lowest, ties share their ranks) run by run, spread off and on."""
import glob, json, os, re, sys

heldout, runs_dir, out = sys.argv[1:4]
screens = ['default', 'magnitude', 'chi2', 'quantile', 'mad', 'fixed']
off, on = {}, {}
for c in json.load(open(heldout))['cells']:
    m = re.match(r'(walking_\w+?)_s(\d+)_(eroded|person_missed)_(\w+)$', c['id'])
    if m and m.group(1) in ('walking_rpy', 'walking_halfsphere'):
        off[(m.group(1), int(m.group(2)), m.group(3), m.group(4))] = 100 * c['metrics']['ate_rmse_m']
for s in screens:
    for f in glob.glob(os.path.join(runs_dir, f'scr_{s}', '*/summary.json')):
        m = re.match(r'(walking_\w+?)_s(\d+)_(\w+)$', os.path.basename(os.path.dirname(f)))
        on[(m.group(1), int(m.group(2)), m.group(3), s)] = 100 * json.load(open(f))['ate_m']['rmse']
runs = sorted({k[:3] for k in on if all(k[:3] + (s,) in on and k[:3] + (s,) in off for s in screens)})

def ranks(table):
    total = {s: 0.0 for s in screens}
    for r in runs:
        vals = [table[r + (s,)] for s in screens]
        for s, v in zip(screens, vals):
            lower = sum(x < v for x in vals)
            equal = sum(x == v for x in vals)
            total[s] += lower + (equal + 1) / 2
    return {s: total[s] / len(runs) for s in screens}

lines = [f'walking_rpy and walking_halfsphere, eroded and person missed, seeds 6-10: {len(runs)} runs per screen.', '',
         '| screen | mean ATE, off [cm] | mean ATE, 128 px [cm] | mean rank, off | mean rank, 128 px |',
         '|---|---:|---:|---:|---:|']
r_off, r_on = ranks(off), ranks(on)
for s in screens:
    mo = sum(off[r + (s,)] for r in runs) / len(runs)
    mn = sum(on[r + (s,)] for r in runs) / len(runs)
    lines.append(f'| {s} | {mo:.2f} | {mn:.2f} | {r_off[s]:.2f} | {r_on[s]:.2f} |')
above = [f'{r[0]} s{r[1]} {r[2]} {s}: {on[r + (s,)]:.1f}' for r in runs for s in screens if on[r + (s,)] > 5]
lines += ['', 'Runs above 5 cm with the spread: ' + ('; '.join(above) if above else 'none') + '.']
tmp = out + '.tmp'
open(tmp, 'w').write('\n'.join(lines) + '\n')
os.replace(tmp, out)
