import json,sys
def load(d):
    j=json.load(open(d+'/dynbench.json'))
    return {c['id']:c['metrics'] for c in j['cells']}
names=sys.argv[1:]; D=[load(n) for n in names]
print('cell'.ljust(45)+''.join(n[-18:].rjust(20) for n in names))
for k in sorted(D[0]):
    print(k.ljust(45)+''.join(('%.3f/%.1f%%'%(d[k]['ate_rmse_m']*100, 100*d[k]['static_dropped_share'])).rjust(20) if k in d else ''.rjust(20) for d in D))
