#!/usr/bin/env python3
"""Every screen's runs before and after the far points, paired by run (scenario, mask, seed).

usage: every_screen_before_after.py BEFORE.json AFTER.json
Both are hbos-dynbench --tracker map outputs of the same cells. Prints, per screen, on how many
runs the ATE and the RPE fell and the mean ATE before and after."""
import json, sys
from collections import defaultdict


def runs(path):
    out = {}
    for cell in json.load(open(path))['cells']:
        out[cell['id']] = (cell['metrics']['ate_rmse_m'] * 100.0,
                           cell['metrics']['rpe_trans_m_per_frame'] * 1000.0)
    return out


before, after = runs(sys.argv[1]), runs(sys.argv[2])
by_screen = defaultdict(list)
for cell_id in sorted(set(before) & set(after)):
    by_screen[cell_id.rsplit('_', 1)[1]].append((before[cell_id], after[cell_id]))
print('| screen | runs | ATE lower | RPE lower | mean ATE before -> after [cm] | mean RPE before -> after [mm/frame] |')
print('|---|---:|---:|---:|---|---|')
for screen, pairs in sorted(by_screen.items()):
    n = len(pairs)
    mean = lambda k, i: sum(p[k][i] for p in pairs) / n
    print(f'| {screen} | {n} | {sum(a[0] < b[0] for b, a in pairs)} | {sum(a[1] < b[1] for b, a in pairs)} | '
          f'{mean(0, 0):.2f} -> {mean(1, 0):.2f} | {mean(0, 1):.2f} -> {mean(1, 1):.2f} |')
print(f'\nRuns in only one of the two: {len(set(before) ^ set(after))}.')
