"""Prints the "Core: full grid" tables of docs/benchmarks.md from bench_core's JSON.

    build-bench/bench/bench_core --benchmark_filter='^(stream|core)/' --benchmark_min_time=0.01 \
        --benchmark_out=grid.json --benchmark_out_format=json
    python3 docs/bench-results/grid_tables.py grid.json

Rates are M items/s (items = matrix entries n*d) from CPU time; the last column is
fit_and_score time / streaming-sum time for double.
"""
import json
import sys

SPECS = [("static10", "EqualWidth, 10 bins"), ("default", "5 bins x 5 shifts"),
         ("dynamic10", "EqualFrequency, 10 bins"), ("auto", "EqualWidth, Birge-Rozenblac")]
OPS = [("fit", "fit"), ("score", "score"), ("fitscore", "fit, score"),
       ("fit_and_score", "fit_and_score"), ("fitscorethr", "+thr")]


def main(path):
    runs = json.load(open(path))["benchmarks"]
    rate = {b["name"]: b["items_per_second"] / 1e6 for b in runs if "items_per_second" in b}
    time = {b["name"]: b["cpu_time"] for b in runs}
    shapes = sorted({tuple(int(v) for v in b["name"].split("/")[-2:]) for b in runs
                     if b["name"].startswith("stream/")})
    for spec, title in SPECS:
        print(f"**{spec} ({title})**\n")
        head = ["n", "d"]
        for scalar in ("f64", "f32"):
            head += [f"sum {scalar}"] + [f"{label} {scalar}" for _, label in OPS]
        head.append("fit_and_score / sum")
        print("| " + " | ".join(head) + " |")
        print("|" + "---:|" * len(head))
        for n, d in shapes:
            cells = [f"{n:.0e}".replace("e+0", "e"), str(d)]
            for scalar in ("double", "float"):
                cells.append(f"{rate[f'stream/sum/{scalar}/{n}/{d}']:,.0f}")
                for op, _ in OPS:
                    cells.append(f"{rate[f'core/{op}/{spec}/{scalar}/{n}/{d}']:,.0f}")
            ratio = (time[f"core/fit_and_score/{spec}/double/{n}/{d}"]
                     / time[f"stream/sum/double/{n}/{d}"])
            cells.append(f"{ratio:.1f}")
            print("| " + " | ".join(cells) + " |")
        print()


if __name__ == "__main__":
    main(sys.argv[1])
