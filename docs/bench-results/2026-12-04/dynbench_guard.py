"""The leverage guard's five-seed tables of docs/results.md ("The mask neighbourhood's leverage").

With the guard: every cell of one run (seeds 1-5, this stop's code). Without it: stop 22's
pooled five seeds (the baselines' seeds 1-3 from stop 15, the default's from stop 20, every
screen's seeds 4-5 from stop 22; pooling checked in dynbench_five_seeds.py). Usage, from the
repository root:
  python3 docs/bench-results/2026-12-04/dynbench_guard.py \
      docs/bench-results/2026-12-04/dynbench_guard.json
"""
import json, os, statistics as st, sys
R = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..') + '/'
def cells(path):
    return {c['id']: c['metrics'] for c in json.load(open(path))['cells']}
s15 = cells(R + '2026-12-02b/dynbench_default.json')
s20 = cells(R + '2026-12-03/dynbench_default_history_floor.json')
s22 = cells(R + '2026-12-03/dynbench_all_seeds45.json')
new = cells(sys.argv[1])
screens = ['none', 'chi2', 'fixed', 'quantile', 'mad', 'magnitude', 'paper', 'default']
scenarios = ('walking_xyz', 'walking_rpy')
masks = ('none', 'eroded', 'person_missed')
seeds = (1, 2, 3, 4, 5)
def old_cell(k, seed, scr):
    return (s22 if seed >= 4 else (s20 if scr == 'default' else s15)).get(k)
def series(src, scen, mask, scr):
    vals = []
    for seed in seeds:
        k = f'{scen}_s{seed}_{mask}_{scr}'
        m = new.get(k) if src == 'new' else old_cell(k, seed, scr)
        if m is None: return None
        vals.append(m)
    return vals
ate = lambda v: [100 * x['ate_rmse_m'] for x in v]
rpe = lambda v: [1000 * x['rpe_trans_m_per_frame'] for x in v]
def table(src, metric, title):
    print(f'\n{title}\n')
    print('| scenario | mask | ' + ' | '.join(screens) + ' |')
    print('|---|---|' + '---:|' * len(screens))
    for scen in scenarios:
        for mask in masks:
            rows = {s: series(src, scen, mask, s) for s in screens}
            means = {s: st.mean(metric(v)) for s, v in rows.items() if v}
            if not means: continue
            best = min(means, key=means.get)
            out = []
            for s in screens:
                if not rows[s]: out.append(''); continue
                a = metric(rows[s]); t = f'{st.mean(a):.2f} ± {st.stdev(a):.2f}'
                out.append(f'**{t}**' if s == best else t)
            print(f'| {scen} | {mask} | ' + ' | '.join(out) + ' |')
table('new', ate, 'ATE RMSE [cm] with the guard, mean ± sd over seeds 1-5; bold: lowest mean')
table('old', ate, 'ATE RMSE [cm] without the guard (stop 22)')
table('new', rpe, 'RPE [mm/frame] with the guard')
print('\nGuard on minus off, per screen (paired by seed, mean ± sd [cm]; seeds lower with the guard)\n')
print('| scenario | mask | ' + ' | '.join(screens) + ' |')
print('|---|---|' + '---|' * len(screens))
for scen in scenarios:
    for mask in ('eroded', 'person_missed'):
        out = []
        for s in screens:
            a, b = series('new', scen, mask, s), series('old', scen, mask, s)
            if not a or not b: out.append(''); continue
            g = [x - y for x, y in zip(ate(a), ate(b))]
            out.append(f'{st.mean(g):+.2f} ± {st.stdev(g):.2f} ({sum(x < 0 for x in g)})')
        print(f'| {scen} | {mask} | ' + ' | '.join(out) + ' |')
print('\nWith the guard: the default minus each screen (paired by seed, mean ± sd [cm]; seeds where the default is lower)\n')
others = [s for s in screens if s not in ('default', 'none', 'paper')]
print('| scenario | mask | ' + ' | '.join(others) + ' |')
print('|---|---|' + '---|' * len(others))
for scen in scenarios:
    for mask in ('eroded', 'person_missed'):
        d = series('new', scen, mask, 'default')
        out = []
        for s in others:
            o = series('new', scen, mask, s)
            if not d or not o: out.append(''); continue
            g = [x - y for x, y in zip(ate(d), ate(o))]
            out.append(f'{st.mean(g):+.2f} ± {st.stdev(g):.2f} ({sum(x < 0 for x in g)})')
        print(f'| {scen} | {mask} | ' + ' | '.join(out) + ' |')
print('\nMatches with the guard (pooled over the seeds): dynamic kept % / static dropped %\n')
for scen in scenarios:
    for mask in ('eroded', 'person_missed'):
        parts = []
        for s in screens:
            v = series('new', scen, mask, s)
            if not v: continue
            dk = 100 * sum(x['dynamic_kept'] for x in v) / max(1, sum(x['dynamic_matches'] for x in v))
            sd = 100 * sum(x['static_dropped'] for x in v) / sum(x['static_matches'] for x in v)
            parts.append(f'{s} {dk:.1f} / {sd:.1f}')
        print(f'- {scen} {mask}: ' + '; '.join(parts))
# Cells without a mask: the guard has nothing to measure, so they must equal stop 22's to the bit.
same = diff = 0
for k, m in new.items():
    if '_none_' not in k: continue
    seed = int(k.split('_s')[1].split('_')[0]); scr = k.rsplit('_', 1)[1]
    o = old_cell(k, seed, scr)
    if o is None: continue
    if o['ate_rmse_m'] == m['ate_rmse_m']: same += 1
    else: diff += 1; print('unmasked cell differs:', k, o['ate_rmse_m'], m['ate_rmse_m'])
print(f'\nunmasked cells equal to stop 22\'s (or their pooled sources): {same}, different: {diff}')
