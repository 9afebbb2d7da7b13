#!/bin/bash
# usage: run.sh NAME BIN MASK SCREEN [extra hbos-slam args...]; env passes through
name=$1; bin=$2; mask=$3; screen=$4; shift 4
mkdir -p /work/ab/s50/grid && cd /work/ab/s50/grid
for d in 0.7 1.2; do for v in 5.5 -5.5; do for m in 40 200; do
  if [ "$v" = "5.5" ]; then x=$m; else x=$((640-210-m)); fi
  out=$name/${mask}_${screen}_d${d}_v${v}_x${x}
  [ -f $out/summary.json ] || $bin --scenario person --mask $mask --screen $screen --person-depth $d --person-speed $v --person-start $x --quiet --out $out "$@" >/dev/null 2>&1
done; done; done
python3 - "$name" "$mask" "$screen" <<'PY'
import json,glob,sys,statistics as st
name,mask,screen=sys.argv[1:]
A=[];R=[];sl=[];pk=[]
for f in sorted(glob.glob(f'{name}/{mask}_{screen}_*/summary.json')):
  d=json.load(open(f));e=d['evaluation']
  A.append(e['ate']['rmse']*100);R.append(e['rpe']['trans_m']['rmse']*1000)
  sl.append(d['static_match_loss_share']*100); pk.append((d['person_survivors'],d['person_matches']))
print(f"{name:14s} {mask:9s} {screen:9s} n={len(A)} ATE {st.mean(A):.3f}±{st.stdev(A):.3f} RPE {st.mean(R):.2f}±{st.stdev(R):.2f} static_loss {st.mean(sl):.2f}% person kept {sum(a for a,b in pk)}/{sum(b for a,b in pk)}")
PY
