"""Screens through the map tracker with a perfect person mask (no dynamic match at all).

Usage: perfect_mask_table.py DIR > perfect_mask_map_tracker.md
DIR holds <screen>/<run> folders (Huber width 2.447, the default) and hw1.0/<screen>/<run>
(--huber-width 1.0), runs named <scenario>_s<seed>_perfect (/work/ab/spread/run.sh's layout).
"""
import glob, json, os, statistics, sys

root = sys.argv[1]


def load(folder):
    out = {}
    for f in glob.glob(os.path.join(folder, '*', 'summary.json')):
        j = json.load(open(f))
        out[os.path.basename(os.path.dirname(f))] = (
            j['ate_m']['rmse'] * 100, j['rpe_trans_mm_per_frame']['rmse'],
            j['static_match_loss_share'] * 100, j['person_matches'])
    return out


print('| scenario | Huber width | screen | runs | ATE [cm] mean (per seed 6..10) | RPE [mm/frame] '
      '| statics dropped [%] | dynamic matches |')
print('|---|---:|---|---:|---|---:|---:|---:|')
for scenario in ('walking_xyz', 'walking_rpy'):
    for width, prefix in (('2.447', ''), ('1.0', 'hw1.0')):
        for screen in ('default', 'chi2', 'quantile', 'magnitude'):
            runs = load(os.path.join(root, prefix, screen))
            keys = sorted((k for k in runs if k.startswith(scenario + '_s')),
                          key=lambda k: int(k.split('_s')[-1].split('_')[0]))
            if not keys:
                continue
            ate = [runs[k][0] for k in keys]
            print(f'| {scenario} | {width} | {screen} | {len(keys)} | {statistics.mean(ate):.3f} ('
                  + ', '.join(f'{a:.2f}' for a in ate) + ') | '
                  f'{statistics.mean(runs[k][1] for k in keys):.2f} | '
                  f'{statistics.mean(runs[k][2] for k in keys):.1f} | '
                  f'{sum(runs[k][3] for k in keys)} |')
