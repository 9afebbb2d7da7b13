import json,sys
a={c['id']:c['metrics'] for c in json.load(open(sys.argv[1]))['cells']}
b={c['id']:c['metrics'] for c in json.load(open(sys.argv[2]))['cells']}
rows=[]
for k in sorted(set(a)&set(b)):
    rows.append((b[k]['ate_rmse_m']*100-a[k]['ate_rmse_m']*100,k,a[k]['ate_rmse_m']*100,b[k]['ate_rmse_m']*100))
rows.sort()
for r in rows[:4]+rows[-5:]: print("%+.3f %s %.3f -> %.3f"%r)
print("worst a %.3f worst b %.3f"%(max(r[2] for r in rows),max(r[3] for r in rows)))
