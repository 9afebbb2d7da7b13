"""Cells of run B against the same ids in run A: ATE, RPE, static and dynamic shares and tracked
frames equal to the bit, or not. usage: python3 identity.py A.json B.json"""
import json,sys
a={c['id']:c['metrics'] for c in json.load(open(sys.argv[1]))['cells'] if 'metrics' in c}
b={c['id']:c['metrics'] for c in json.load(open(sys.argv[2]))['cells'] if 'metrics' in c}
keys=['ate_rmse_m','rpe_trans_m_per_frame','rpe_rot_deg_per_frame','static_dropped','dynamic_kept','frames_tracked']
same=0
for k in sorted(set(a)&set(b)):
    eq=all(a[k][f]==b[k][f] for f in keys)
    same+=eq
    print(k, 'same to the bit' if eq else 'DIFFERENT', a[k]['ate_rmse_m'], b[k]['ate_rmse_m'])
print(f"{same} of {len(set(a)&set(b))} cells the same to the bit")
