"""Stop 50, R6: rendered frames with every depth map moved down 8 px against the same cells as
rendered. Per screen: masked / unmasked runs with a lower ATE with the offset, mean ATE; and the
default against chi^2 within each condition (runs lower, means).
usage: python3 r6_compare.py DEFAULT_AS_RENDERED.json CHI2_AS_RENDERED.json SHIFTED.json"""
import json
import statistics
import sys

def cells(path):
    return {c["id"]: c["metrics"] for c in json.load(open(path))["cells"]}

base_default, base_every, shifted = (cells(p) for p in sys.argv[1:4])
base = {**{k: v for k, v in base_every.items() if k.endswith("_chi2")},
        **{k: v for k, v in base_default.items() if k.endswith("_default")}}
ate = lambda m: m["ate_rmse_m"] * 100
for masked in (True, False):
    label = "masked" if masked else "no mask"
    keep = lambda k: ("_none_" not in k) == masked
    print(f"\n{label}")
    for screen in ("default", "chi2"):
        ids = sorted(k for k in shifted if k.endswith("_" + screen) and keep(k) and k in base)
        lower = sum(ate(shifted[k]) < ate(base[k]) for k in ids)
        print(f"  {screen:8s} {len(ids)} runs: ATE with the offset lower on {lower}; mean "
              f"{statistics.mean(ate(base[k]) for k in ids):.3f} -> {statistics.mean(ate(shifted[k]) for k in ids):.3f} cm; "
              f"median {statistics.median(ate(base[k]) for k in ids):.3f} -> {statistics.median(ate(shifted[k]) for k in ids):.3f}")
    for name, src in (("as rendered", base), ("depth moved 8 px", shifted)):
        ids = sorted(k[:-len("_default")] for k in src if k.endswith("_default") and keep(k)
                     and k[:-len("_default")] + "_chi2" in src)
        lower = sum(ate(src[i + "_default"]) < ate(src[i + "_chi2"]) for i in ids)
        print(f"  {name:17s} default lower than chi^2 on {lower} of {len(ids)}; means "
              f"{statistics.mean(ate(src[i + '_default']) for i in ids):.3f} against "
              f"{statistics.mean(ate(src[i + '_chi2']) for i in ids):.3f} cm")
