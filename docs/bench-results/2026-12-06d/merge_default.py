"""Replace the default's cells of a dynbench.json with those of another run (same ids)."""
import json,sys
base=json.load(open(sys.argv[1])); new={c['id']:c for c in json.load(open(sys.argv[2]))['cells']}
n=0
for i,c in enumerate(base['cells']):
    if c['id'] in new and c['id'].endswith('_default'):
        base['cells'][i]=new[c['id']]; n+=1
json.dump(base,open(sys.argv[3],'w'))
print("replaced",n)
