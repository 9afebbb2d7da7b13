#!/usr/bin/env python3
"""Stop 28: ATE [cm], RPE [mm/frame], dynamic kept and statics dropped [%] (mean of the
seeds' shares) per scenario, mask and screen, for hbos-dynbench output folders.
Usage: cells_table.py OUT_DIR...
"""
import json, os, sys, re, collections, statistics as st
dirs = sys.argv[1:]
rows = collections.defaultdict(dict)
for d in dirs:
    cd = os.path.join(d, 'cells')
    if not os.path.isdir(cd): continue
    for c in sorted(os.listdir(cd)):
        f = os.path.join(cd, c, 'cell.json')
        if not os.path.exists(f): continue
        m = re.match(r'(walking_\w+?)_s(\d+)_(none|eroded|person_missed|boxes|detector)_(\w+)$', c)
        if not m: continue
        scen, seed, mask, screen = m.groups()
        x = json.load(open(f))['metrics']
        rows[(scen, mask, screen, os.path.basename(d))][int(seed)] = (x['ate_rmse_m']*100, x['rpe_trans_m_per_frame']*1000, (x['dynamic_kept_share'] or 0)*100, (x['static_dropped_share'] or 0)*100)
keys = sorted(rows)
print(f"{'scenario':20s} {'mask':14s} {'screen':9s} {'run':14s} n  ATE    RPE   dyn%  stat%  per-seed ATE")
for k in keys:
    v = rows[k]; s = sorted(v)
    a = [v[i][0] for i in s]
    print(f"{k[0]:20s} {k[1]:14s} {k[2]:9s} {k[3]:14s} {len(s)} {st.mean(a):5.2f} {st.mean(v[i][1] for i in s):5.2f} {st.mean(v[i][2] for i in s):5.1f} {st.mean(v[i][3] for i in s):5.1f}  " + " ".join(f"{x:.2f}" for x in a))
