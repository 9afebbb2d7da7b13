"""Path by path on the semi-real grid: on how many of the 8 paths the default's ATE / RPE is lower
than each other screen's, per run set and mask. usage: python3 pathwise.py GRID_DIR NAME..."""
import glob, json, os, sys
root, names = sys.argv[1], sys.argv[2:]
screens = ["chi2", "fixed", "quantile", "mad", "magnitude"]
for name in names:
    for mask in ("none", "degraded", "detector"):
        def runs(screen):
            out = {}
            for f in glob.glob(f"{root}/{name}/{mask}_{screen}_*/summary.json"):
                path = os.path.basename(os.path.dirname(f))[len(f"{mask}_{screen}_"):]
                e = json.load(open(f))["evaluation"]
                out[path] = (e["ate"]["rmse"] * 100, e["rpe"]["trans_m"]["rmse"] * 1000)
            return out
        d = runs("default")
        cells = []
        for s in screens:
            o = runs(s)
            common = sorted(set(d) & set(o))
            if not common:
                continue
            a = sum(d[p][0] < o[p][0] for p in common)
            r = sum(d[p][1] < o[p][1] for p in common)
            cells.append(f"{s} {a}/{r} of {len(common)}")
        print(f"{name:12s} {mask:9s} default lower ATE/RPE than: " + ", ".join(cells))
