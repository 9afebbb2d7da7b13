"""Summarise the FDIAG lines of field_significance_diag_patch.diff (stop 47).

Each line is one call of the default screen's last field fit (the refit on the matches that look
static): floor = the noise gate's floor (2.447: the first round; 1.225: rounds 2-4 of the frame
tracker), n = samples within the window of the affine field, F = the F statistic of the affine
field against a constant one on those samples ((S0 - S1) / 4) / (S1 / (2 n - 6)), where S0 and
S1 are the weighted squared residuals about the constant and the affine field), grad = |G| x 300
[px], G = the gradient's entries [px/px] (xu, xv, yu, yv).
usage: python3 field_significance.py FILE...
"""
import gzip
import re
import statistics
import sys

F_CRIT = 2.38  # F(4, ~1000) at p = 0.05

for path in sys.argv[1:]:
    opener = gzip.open if path.endswith(".gz") else open
    lines = [l for l in opener(path, "rt") if l.startswith("FDIAG")]
    for floor, label in (("2.447", "round 1"), ("1.225", "rounds 2-4")):
        rows = [l for l in lines if f"floor={floor}" in l]
        if not rows:
            continue
        F = sorted(float(re.search(r"F=(\S+)", l).group(1)) for l in rows)
        g = [float(re.search(r"grad=(\S+)", l).group(1)) for l in rows]
        G = [[abs(float(x)) * 300 for x in re.search(r"G=(\S+)", l).group(1).split(",")] for l in rows]
        mean_G = [statistics.mean(c[k] for c in G) for k in range(4)]
        print(f"{path:28s} {label:10s} fits {len(F):5d}  F median {statistics.median(F):6.2f}"
              f"  90th pct {F[int(0.9 * len(F))]:6.2f}  share p<0.05 {sum(f > F_CRIT for f in F) / len(F):.2f}"
              f"  |G|x300 median {statistics.median(g):.3f} px"
              f"  mean |entry|x300 xu {mean_G[0]:.3f} xv {mean_G[1]:.3f} yu {mean_G[2]:.3f} yv {mean_G[3]:.3f}")
