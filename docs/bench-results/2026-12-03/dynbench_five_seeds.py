"""The five-seed table of docs/results.md ("Five seeds per screen", stop 22).

Pools each screen's seeds 1-3 (the baselines from stop 15's run, the default from stop 20's)
with seeds 4-5 of stop 22's run of every screen, and checks that stop 22's baseline cells equal
stop 16's seeds 4-5 to the bit. Usage, from the repository root:
  python3 docs/bench-results/2026-12-03/dynbench_five_seeds.py \
      docs/bench-results/2026-12-03/dynbench_all_seeds45.json
"""
import json, statistics as st, sys
import os
R = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..') + '/'
def cells(path):
    return {c['id']: c['metrics'] for c in json.load(open(path))['cells']}
s15 = cells(R + '2026-12-02b/dynbench_default.json')
s16 = cells(R + '2026-12-02c/dynbench_default_seeds45.json')
s20 = cells(R + '2026-12-03/dynbench_default_history_floor.json')
now = cells(sys.argv[1])
screens = ['none', 'chi2', 'fixed', 'quantile', 'mad', 'magnitude', 'paper', 'default']
# reproduction check
same = diff = 0
for k, m in now.items():
    if k.endswith('_default'): continue
    if k in s16:
        if abs(s16[k]['ate_rmse_m'] - m['ate_rmse_m']) < 1e-12: same += 1
        else:
            diff += 1; print('differs from stop 16:', k, s16[k]['ate_rmse_m'], m['ate_rmse_m'])
print(f'baseline cells of seeds 4-5 equal to stop 16: {same}, different: {diff}')
rows = {}
for scen in ('walking_xyz', 'walking_rpy'):
    for mask in ('none', 'eroded', 'person_missed'):
        for scr in screens:
            vals = []
            for seed in (1, 2, 3, 4, 5):
                k = f'{scen}_s{seed}_{mask}_{scr}'
                src = now if seed >= 4 else (s20 if scr == 'default' else s15)
                if k in src: vals.append(src[k])
            if len(vals) == 5: rows[(scen, mask, scr)] = vals
out = []
out.append('| scenario | mask | ' + ' | '.join(screens) + ' |')
out.append('|---|---|' + '---:|' * len(screens))
for scen in ('walking_xyz', 'walking_rpy'):
    for mask in ('none', 'eroded', 'person_missed'):
        cells_ = []
        means = {s: st.mean(100 * v['ate_rmse_m'] for v in rows[(scen, mask, s)]) for s in screens if (scen, mask, s) in rows}
        best = min(means, key=means.get) if means else None
        for s in screens:
            if (scen, mask, s) not in rows: cells_.append(''); continue
            a = [100 * v['ate_rmse_m'] for v in rows[(scen, mask, s)]]
            t = f'{st.mean(a):.2f} ± {st.stdev(a):.2f}'
            cells_.append(f'**{t}**' if s == best else t)
        out.append(f'| {scen} | {mask} | ' + ' | '.join(cells_) + ' |')
print('\n'.join(out))
# paired: default vs each other screen, seeds where default lower
print()
for scen in ('walking_xyz', 'walking_rpy'):
    for mask in ('eroded', 'person_missed'):
        d = [100 * v['ate_rmse_m'] for v in rows[(scen, mask, 'default')]]
        parts = []
        for s in screens:
            if s in ('default', 'none', 'paper'): continue
            o = [100 * v['ate_rmse_m'] for v in rows[(scen, mask, s)]]
            gaps = [x - y for x, y in zip(d, o)]
            parts.append(f'{s}: {st.mean(gaps):+.2f} ± {st.stdev(gaps):.2f} (lower in {sum(g < 0 for g in gaps)}/5)')
        print(f'{scen} {mask}: default minus ' + '; '.join(parts))
# statics / dynamics
print()
for scen in ('walking_xyz', 'walking_rpy'):
    for mask in ('none', 'eroded', 'person_missed'):
        for s in screens:
            if (scen, mask, s) not in rows: continue
            v = rows[(scen, mask, s)]
            dk = 100 * sum(x['dynamic_kept'] for x in v) / max(1, sum(x['dynamic_matches'] for x in v))
            sd = 100 * sum(x['static_dropped'] for x in v) / sum(x['static_matches'] for x in v)
            r = st.mean(1000 * x['rpe_trans_m_per_frame'] for x in v)
            print(f'{scen} {mask} {s}: RPE {r:.2f} mm/frame, dynamic kept {dk:.1f} %, static dropped {sd:.1f} %')
