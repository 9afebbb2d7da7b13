# The cells of two hbos-dynbench JSON outputs whose ATE or tracked frame count differ (same ids).
# usage: python3 changed_cells.py before.json [more_before.json ...] after.json
# (every file but the last is a "before"; a later one wins for an id in several: for the
# seeds 16-20 runs pass the candidate's file first, then the default's, so that chi2 comes from the
# first and the default from the second)
import json, sys
def load(p): return {c['id']: c['metrics'] for c in json.load(open(p))['cells']}
before = {}
for p in sys.argv[1:-1]: before.update(load(p))
after = load(sys.argv[-1])
changed = 0
for k in sorted(after):
    if k not in before: print("not in before:", k); continue
    a, b = before[k], after[k]
    if a['ate_rmse_m'] != b['ate_rmse_m'] or a['frames_tracked'] != b['frames_tracked']:
        changed += 1
        print(f"{k:42s} ATE {a['ate_rmse_m']*100:8.3f} -> {b['ate_rmse_m']*100:8.3f} cm  "
              f"tracked {a['frames_tracked']} -> {b['frames_tracked']}")
print(f"changed {changed} of {len(after)}")
