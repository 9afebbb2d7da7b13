"""Mean static-dropped and dynamic-kept shares [%] of the default screen's runs in each
hbos-dynbench JSON, masked and unmasked, against the same runs in a reference JSON.
usage: python3 match_shares.py reference.json run.json [run.json ...]"""
import json
import statistics
import sys


def cells(path):
    return {c["id"]: c["metrics"] for c in json.load(open(path))["cells"] if "metrics" in c}


def main():
    reference = cells(sys.argv[1])
    for path in sys.argv[2:]:
        run = cells(path)
        ids = [k for k in run if k.endswith("_default") and k in reference]
        print(path)
        for label, masked in (("masked", True), ("no mask", False)):
            chosen = [k for k in ids if ("_none_" not in k) == masked]
            if not chosen:
                continue
            for key in ("static_dropped_share", "dynamic_kept_share"):
                ref = [reference[k][key] for k in chosen if reference[k][key] is not None]
                new = [run[k][key] for k in chosen if run[k][key] is not None]
                print(f"  {label:8} {key:22} {len(chosen):3} runs: "
                      f"{100 * statistics.mean(ref):6.2f} -> {100 * statistics.mean(new):6.2f} %")


if __name__ == "__main__":
    main()
