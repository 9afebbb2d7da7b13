# The default against chi2, pooled over several hbos-dynbench JSON outputs (cells with both).
# usage: python3 pooled_default_vs_chi2.py A.json [B.json ...]
import json, sys
from scipy.stats import wilcoxon
cells = {}
for p in sys.argv[1:]:
    for c in json.load(open(p))['cells']:
        cells[c['id']] = c['metrics']
pairs = []
for k, m in cells.items():
    if k.endswith('_default') and k[:-len('default')] + 'chi2' in cells:
        pairs.append((m['ate_rmse_m'] * 100, cells[k[:-len('default')] + 'chi2']['ate_rmse_m'] * 100))
d = [a - b for a, b in pairs]
n = len(pairs)
print(f"{n} runs: default lower on {sum(x < 0 for x in d)}, higher on {sum(x > 0 for x in d)}; "
      f"mean ATE {sum(a for a, _ in pairs) / n:.3f} against chi2 {sum(b for _, b in pairs) / n:.3f} cm; "
      f"Wilcoxon p = {wilcoxon(d).pvalue:.2g}")
