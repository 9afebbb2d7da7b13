"""docs/img/dynbench_five_seeds.png: per-seed ATE of every screen in the masked rows, five seeds.
Usage, from the repository root:
  python3 docs/bench-results/2026-12-03/dynbench_five_seeds_plot.py \
      docs/bench-results/2026-12-03/dynbench_all_seeds45.json \
      docs/bench-results/2026-12-03/dynbench_default_seeds123_ab4e42c.json - docs/img/dynbench_five_seeds.png
"""
import json, sys
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
import os
R = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..') + '/'
def cells(path):
    return {c['id']: c['metrics'] for c in json.load(open(path))['cells']}
s15 = cells(R + '2026-12-02b/dynbench_default.json')
s20 = cells(R + '2026-12-03/dynbench_default_history_floor.json')
now = cells(sys.argv[1])
s123 = cells(sys.argv[2]) if len(sys.argv) > 3 else s20
screens = ['chi2', 'fixed', 'quantile', 'mad', 'magnitude', 'default']
fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
for ax, (scen, mask) in zip(axes.flat, [(s, m) for s in ('walking_xyz', 'walking_rpy') for m in ('eroded', 'person_missed')]):
    for x, scr in enumerate(screens):
        ys = []
        for seed in (1, 2, 3, 4, 5):
            k = f'{scen}_s{seed}_{mask}_{scr}'
            src = now if seed >= 4 else (s123 if scr == 'default' else s15)
            ys.append(100 * src[k]['ate_rmse_m'])
        colour = 'tab:red' if scr == 'default' else 'tab:blue'
        for seed, y in zip((1, 2, 3, 4, 5), ys):
            ax.scatter(x + (seed - 3) * 0.07, y, s=22, color=colour, alpha=0.8)
        ax.hlines(sum(ys) / 5, x - 0.25, x + 0.25, color='black', lw=1.5)
    ax.set_yscale('log')
    from matplotlib.ticker import ScalarFormatter, LogLocator
    ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xticks(range(len(screens)), screens)
    ax.set_title(f'{scen}, mask {mask}')
    ax.set_ylabel('ATE RMSE [cm] (log)')
    ax.grid(axis='y', which='both', alpha=0.3)
fig.suptitle('Rendered default subset, 5 seeds per screen (dots: seeds 1-5 left to right; bar: mean)')
fig.tight_layout()
fig.savefig(sys.argv[-1], dpi=110)
