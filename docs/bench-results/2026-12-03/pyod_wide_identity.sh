#!/bin/bash
# Throwaway: the new binary's models, scores and labels must equal the old binary's byte for byte.
set -u
OLD=${OLD:-./hbos-score-old}; NEW=${NEW:-./hbos-score-new}
D=/tmp/pyodwide/id; mkdir -p $D; fails=0; checks=0
c() { checks=$((checks+1)); if [ ! -e "$1" ] && [ ! -e "$2" ]; then echo "both absent: $1"; return; fi
  if cmp -s "$1" "$2"; then :; else echo "DIFF $1 $2"; fails=$((fails+1)); fi; }
run() { # tag, file, extra fit/one-shot args...
  local tag=$1 f=$2; shift 2
  for b in old new; do B=$OLD; [ $b = new ] && B=$NEW
    $B fit $f --no-header "$@" -o $D/$tag.$b.hbos 2>$D/$tag.fit.$b.err >/dev/null
    $B $f --no-header "$@" -q -o $D/$tag.one.$b.csv 2>$D/$tag.one.$b.err
    $B score $D/$tag.old.hbos $f --no-header -o $D/$tag.score.$b.csv 2>$D/$tag.score.$b.err
  done
  $NEW score $D/$tag.new.hbos $f --no-header -o $D/$tag.score.newmodel.csv 2>/dev/null
  c $D/$tag.old.hbos $D/$tag.new.hbos; c $D/$tag.one.old.csv $D/$tag.one.new.csv
  c $D/$tag.score.old.csv $D/$tag.score.new.csv; c $D/$tag.score.old.csv $D/$tag.score.newmodel.csv
  sed -i "s/$tag[.]old[.]hbos/MODEL/; s/$tag[.]new[.]hbos/MODEL/" $D/$tag.fit.*.err
  for k in fit one score; do c $D/$tag.$k.old.err $D/$tag.$k.new.err; done
  ls -s $D/$tag.old.hbos $D/$tag.one.old.csv $D/$tag.score.old.csv | tr '\n' ' '; echo " <- $tag"
}
for f in w1e5 w2e5 w1e6 t1e6 t500 m300 bad_nan bad_inf bad_range bad_denorm ${EXTRA:-}; do
  run $f.pyod $f.csv --mode pyod
  run $f.def $f.csv
done
run w1e5.auto w1e5.csv --mode pyod --bins auto
run m300.auto m300.csv --mode pyod --bins auto
run t500.b40 t500.csv --mode pyod --bins 40
run t1e6.b3000 t1e6.csv --mode pyod --bins 3000
for t in m300 w1e5; do for b in old new; do B=$OLD; [ $b = new ] && B=$NEW
  $B $t.csv --no-header --mode pyod --contributions -q -o $D/$t.contrib.$b.csv 2>&1; done
  c $D/$t.contrib.old.csv $D/$t.contrib.new.csv; done
run t1e6.auto t1e6.csv --mode pyod --bins auto
# a model of few rows scoring many (whole model assembled from grid-less features)
for b in old new; do B=$OLD; [ $b = new ] && B=$NEW
  $B score $D/t500.pyod.old.hbos t1e6.csv --no-header -o $D/cross.$b.csv 2>/dev/null
  $B score $D/t500.b40.old.hbos t1e6.csv --no-header -o $D/cross40.$b.csv 2>/dev/null; done
c $D/cross.old.csv $D/cross.new.csv; c $D/cross40.old.csv $D/cross40.new.csv
echo "checks $checks, differences $fails"
