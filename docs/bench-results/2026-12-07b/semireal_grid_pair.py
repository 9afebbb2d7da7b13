import json,glob,sys,os
mask=sys.argv[1]; confs=sys.argv[2:]  # entries name:screen
rows={}
for c in confs:
  name,screen=c.split(':')
  for f in sorted(glob.glob(f'{name}/{mask}_{screen}_*/summary.json')):
    v=f.split('/')[1].split('_',2)[2]
    d=json.load(open(f));e=d['evaluation']
    rows.setdefault(v,{})[c]=(e['ate']['rmse']*100,e['rpe']['trans_m']['rmse']*1000)
print('variant'.ljust(22)+''.join(c.ljust(18) for c in confs))
for v,r in rows.items():
  print(v.ljust(22)+''.join(('%.3f/%.2f'%r[c]).ljust(18) if c in r else '-'.ljust(18) for c in confs))
