"""Rows per second of the default-mode HBOS fitted and scored in memory (hbos.HBOS), on a Dask
array through a local distributed cluster (hbos.dask), and PyOD 3.6.5's HBOS on the same data,
all in one run (docs/benchmarks.md, "Python and Dask"). The Dask fit includes its exact
threshold (a few extra passes over the scores) unless --no-threshold.

    PYTHONPATH=build/examples/python:../shared/tools/pyod-3.6.5 \
      python3 bench/bench_dask.py --rows 2000000 --cols 10 --chunk 250000 --json dask.json

Leaves out: reading the data (it is generated in memory and handed to Dask with from_array, so
the cluster ships the chunks to its workers from the client), and cluster start-up.
"""

import argparse
import json
import os
import sys
import time

import numpy as np


def best_of(repeats, fn):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def model_only(dX):
    """hbos.dask.fit's two passes without the threshold: the model alone."""
    import dask
    from hbos import _hbos
    from hbos.dask import _add_counts, _count, _merge_ranges, _range, _tree

    blocks = dX.to_delayed().ravel()
    lo, hi, rows = dask.compute(_tree([dask.delayed(_range)(b) for b in blocks], _merge_ranges))[0]
    total = dask.compute(_tree([dask.delayed(_count)(b, lo, hi, rows, "") for b in blocks],
                               _add_counts))[0]
    return _hbos.DefaultModel.from_counts(lo, hi, rows, "", 5, total)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rows", type=int, default=2_000_000)
    ap.add_argument("--cols", type=int, default=10)
    ap.add_argument("--chunk", type=int, default=250_000, help="rows per Dask chunk")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--no-threshold", action="store_true")
    ap.add_argument("--json", help="write the results here")
    a = ap.parse_args()

    import hbos
    import hbos.dask
    import dask.array as da
    import distributed

    rng = np.random.default_rng(1)
    X = rng.standard_normal((a.rows, a.cols)) * rng.uniform(0.1, 100.0, a.cols)
    results = {"rows": a.rows, "cols": a.cols, "chunk": a.chunk, "workers": a.workers,
               "load_average": os.getloadavg()}

    t, clf = best_of(a.repeats, lambda: hbos.HBOS().fit(X))
    results["memory_fit_s"] = t
    t, _ = best_of(a.repeats, lambda: clf.decision_function(X))
    results["memory_score_s"] = t

    with distributed.LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster):
        dX = da.from_array(X, chunks=(a.chunk, a.cols))
        fit = (lambda: model_only(dX)) if a.no_threshold else (lambda: hbos.dask.fit(dX))
        t, dclf = best_of(a.repeats, fit)
        results["dask_fit_s"] = t
        if not a.no_threshold:
            same = np.array_equal(dclf.decision_function(X[:10000]),
                                  clf.decision_function(X[:10000]))
            results["dask_threshold_equal"] = bool(dclf.threshold_ == clf.threshold_)
            results["dask_scores_equal"] = bool(same)
            t, _ = best_of(a.repeats, lambda: hbos.dask.score(dclf, dX).compute())
            results["dask_score_s"] = t

    try:
        from pyod.models.hbos import HBOS as PyodHBOS
        t, _ = best_of(a.repeats, lambda: PyodHBOS().fit(X))
        results["pyod_fit_s"] = t
    except ImportError as e:  # PyOD needs scikit-learn and numba (Debian packages)
        results["pyod_fit_s"] = None
        print(f"PyOD not measured: {e}", file=sys.stderr)

    for key in list(results):
        if key.endswith("_s") and results[key]:
            results[key[:-2] + "_rows_per_s"] = a.rows / results[key]
    print(json.dumps(results, indent=1))
    if a.json:
        with open(a.json + ".tmp", "w") as f:
            json.dump(results, f, indent=1)
        os.replace(a.json + ".tmp", a.json)


if __name__ == "__main__":
    main()
