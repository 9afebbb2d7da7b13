"""The row rule of hbos-dynbench (frontend/standing.hpp) on a dynbench.json: per (scenario, mask),
the default's mean ATE against the best other screen's; best when lower or equal, tied when above
by at most the larger sample standard deviation (n - 1) of the two, behind otherwise.
usage: python3 row_rule.py dynbench.json"""
import json, sys, re, statistics
from collections import defaultdict
ate = defaultdict(list)
for c in json.load(open(sys.argv[1]))['cells']:
    if 'metrics' not in c: continue
    scen, seed, mask, screen = re.match(r'(.*)_s(\d+)_(.*)_([a-z0-9]+)$', c['id']).groups()
    ate[(scen, mask, screen)].append(100 * c['metrics']['ate_rmse_m'])
rows = sorted({(s, m) for s, m, _ in ate})
count = defaultdict(int)
for s, m in rows:
    d = ate.get((s, m, 'default'))
    others = {k[2]: v for k, v in ate.items() if k[:2] == (s, m) and k[2] != 'default'}
    if not d or not others: continue
    best = min(others, key=lambda k: statistics.mean(others[k]))
    gap = statistics.mean(d) - statistics.mean(others[best])
    spread = max(statistics.stdev(d), statistics.stdev(others[best]))
    v = 'best' if gap <= 0 else ('tied' if gap <= spread else 'behind')
    count[v] += 1
    print(f"{s:20s} {m:14s} default {statistics.mean(d):.3f}  best other {best} {statistics.mean(others[best]):.3f}  gap {gap:+.3f} spread {spread:.3f}  {v}")
print(dict(count))
