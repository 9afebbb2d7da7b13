"""docs/img/dynbench_guard.png: per-seed ATE of each screen without and with the leverage guard,
in the two eroded-mask rows (the guard needs a mask; with the person missed nothing moved).
Without: stop 22's pooled five seeds; with: this stop's run. Usage, from the repository root:
  python3 docs/bench-results/2026-12-04/dynbench_guard_plot.py \
      docs/bench-results/2026-12-04/dynbench_guard.json docs/img/dynbench_guard.png
"""
import json, os, sys
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter
R = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..') + '/'
def cells(path):
    return {c['id']: c['metrics'] for c in json.load(open(path))['cells']}
s15 = cells(R + '2026-12-02b/dynbench_default.json')
s20 = cells(R + '2026-12-03/dynbench_default_history_floor.json')
s22 = cells(R + '2026-12-03/dynbench_all_seeds45.json')
new = cells(sys.argv[1])
screens = [s for s in ['none', 'chi2', 'fixed', 'quantile', 'mad', 'magnitude', 'paper', 'default']
           if all(f'walking_xyz_s{k}_eroded_{s}' in new for k in range(1, 6))]
fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
for ax, scen in zip(axes, ('walking_xyz', 'walking_rpy')):
    for x, scr in enumerate(screens):
        for side, (src, colour) in enumerate([('old', 'tab:gray'), ('new', 'tab:red' if scr == 'default' else 'tab:blue')]):
            ys = []
            for seed in range(1, 6):
                k = f'{scen}_s{seed}_eroded_{scr}'
                m = new[k] if src == 'new' else (s22 if seed >= 4 else (s20 if scr == 'default' else s15))[k]
                ys.append(100 * m['ate_rmse_m'])
            xc = x + (side - 0.5) * 0.36
            for seed, y in enumerate(ys):
                ax.scatter(xc + (seed - 2) * 0.05, y, s=16, color=colour, alpha=0.85)
            ax.hlines(sum(ys) / 5, xc - 0.15, xc + 0.15, color='black', lw=1.5)
    ax.set_yscale('log')
    ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xticks(range(len(screens)), screens)
    ax.set_title(f'{scen}, eroded mask: grey without the guard, colour with it')
    ax.set_ylabel('ATE RMSE [cm] (log)')
    ax.grid(axis='y', which='both', alpha=0.3)
fig.suptitle('The leverage guard, 5 seeds per screen (dots: seeds 1-5 left to right; bar: mean)')
fig.tight_layout()
fig.savefig(sys.argv[-1], dpi=110)
