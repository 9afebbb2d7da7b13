"""Stop 32's every-screen map-tracker comparison with the default's cells replaced by a new run's.

Usage: recompare.py STOP32_DYNBENCH_JSON [NEW_CELLS_DIR]
Without NEW_CELLS_DIR it recomputes stop 32's own comparison (a check of this script against
the `comparison` hbos-dynbench wrote into the JSON). With it, every cell `<run>_default` is
replaced by NEW_CELLS_DIR/<run>_default/cell.json; the other screens' cells stay stop 32's:
their code path did not change (the new setting acts on the default screen's coherence only).
Writes Markdown on stdout: the mean rank by ATE with and without a mask, the default against
each screen run by run (lower / higher, Wilcoxon p from scipy), and per (scenario, mask) the
default against the screen with the lowest mean ATE by hbos-dynbench's rule (best; tied: the gap
within the larger of the two standard deviations over the seeds; behind).
"""
import collections, json, os, re, statistics, sys
from scipy.stats import rankdata, wilcoxon

data = json.load(open(sys.argv[1]))
cells = {c['id']: c['metrics'] for c in data['cells']}
replaced = 0
if len(sys.argv) > 2:
    for cid in list(cells):
        if cid.endswith('_default'):
            path = os.path.join(sys.argv[2], cid, 'cell.json')
            cells[cid] = json.load(open(path))['metrics']
            replaced += 1

SCREENS = ['default', 'chi2', 'fixed', 'quantile', 'mad', 'magnitude', 'none']
runs = collections.defaultdict(dict)  # (scenario, seed, mask) -> screen -> ATE cm
for cid, m in cells.items():
    head, seed, rest = re.match(r'^(.*)_s(\d+)_(.*)$', cid).groups()
    screen = next(s for s in SCREENS if rest.endswith('_' + s))
    mask = rest[:-len(screen) - 1]
    runs[(head, int(seed), mask)][screen] = m['ate_rmse_m'] * 100
print(f'Cells: {len(cells)}, of which {replaced} default cells replaced.\n')
for masked in (True, False):
    group = {k: v for k, v in runs.items() if (k[2] != 'none') == masked}
    screens = sorted(set.intersection(*(set(v) for v in group.values())))
    rank_sum = collections.Counter()
    for v in group.values():
        for s, r in zip(screens, rankdata([v[s] for s in screens])):
            rank_sum[s] += r
    n = len(group)
    order = sorted(screens, key=lambda s: rank_sum[s] / n)
    print(f"{'With' if masked else 'Without'} a mask, {n} runs. Mean rank by ATE: " +
          ', '.join(f'{s} {rank_sum[s] / n:.2f}' for s in order))
    print('\n| default against | lower | higher | median difference [cm] | Wilcoxon p |')
    print('|---|---:|---:|---:|---:|')
    for s in screens:
        if s == 'default':
            continue
        d = [v['default'] - v[s] for v in group.values()]
        p = wilcoxon(d).pvalue if any(x != 0 for x in d) else float('nan')
        print(f'| {s} | {sum(x < 0 for x in d)} | {sum(x > 0 for x in d)} | '
              f'{statistics.median(d):+.3f} | {p:.3g} |')
    print()
print('| scenario | mask | lowest other | its ATE [cm] | default [cm] | spread [cm] | verdict |')
print('|---|---|---|---:|---:|---:|---|')
rows = collections.defaultdict(lambda: collections.defaultdict(list))
for (scen, seed, mask), v in runs.items():
    for s, ate in v.items():
        rows[(scen, mask)][s].append(ate)
for (scen, mask), by in sorted(rows.items()):
    mean = {s: statistics.mean(a) for s, a in by.items()}
    sd = {s: statistics.stdev(a) if len(a) > 1 else 0.0 for s, a in by.items()}
    best = min((s for s in by if s != 'default'), key=lambda s: mean[s])
    spread = max(sd[best], sd['default'])
    gap = mean['default'] - mean[best]
    verdict = 'best' if gap <= 0 else ('tied' if gap <= spread else 'behind')
    print(f'| {scen} | {mask} | {best} | {mean[best]:.2f} | {mean["default"]:.2f} | '
          f'{spread:.2f} | {verdict} |')
