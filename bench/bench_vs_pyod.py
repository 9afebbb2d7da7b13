"""hbos against PyOD 3.6.5 on the headline job, both measured in this one process: 1e6 x 2 standard
normal doubles, 10 equal-width bins, fit + training scores, scoring new data, n_bins='auto', and a
streaming read of the same array as the floor (docs/benchmarks.md, "Core: headline targets").

    PYTHONPATH=build/examples/python:../shared/tools/pyod-3.6.5 \\
      python3 bench/bench_vs_pyod.py --json vs_pyod.json

Every figure is the best of --repeats wall-clock runs (PyOD's auto fit: one run, it takes half a
minute). hbos' times include allocating the score vector, as PyOD's do. "hbos static10" is the
classic HBOS job (10 equal-width bins, no shifted origins) through the module's DefaultModel;
hbos.HBOS() itself fits the default mode (5 bins x 5 shifts), timed as well. The GIL check scores
the same array twice, one after the other and then from two Python threads at once: with the
GIL released while scoring, the threads take about half the time on two idle cores.

Leaves out: reading the data from disk, numba's compilation of PyOD's scoring (warmed up on a
small array first), and anything but this one shape.
"""

import argparse
import json
import os
import sys
import threading
import time

import numpy as np


def best_of(repeats, fn):
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def two_threads(fn):
    """Wall time of fn() run in two threads at once."""
    threads = [threading.Thread(target=fn) for _ in range(2)]
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return time.perf_counter() - t0


def write_json(path, results):
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w") as f:
        json.dump(results, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rows", type=int, default=1_000_000)
    ap.add_argument("--cols", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--no-auto", action="store_true", help="skip n_bins='auto' (PyOD: ~30 s)")
    ap.add_argument("--json", help="write the results here (atomically)")
    a = ap.parse_args()

    try:
        from pyod.models.hbos import HBOS as PyodHBOS
    except ImportError:
        sys.exit("PyOD is not importable: put ../shared/tools/pyod-3.6.5 on PYTHONPATH")
    import hbos
    from hbos import _hbos

    rng = np.random.default_rng(20240611)
    X_c = rng.standard_normal((a.rows, a.cols))  # numpy's default, row-major
    X_f = np.asfortranarray(X_c)                 # column-major, as the C++ headline
    PyodHBOS().fit(X_c[:2000]).decision_function(X_c[:2000])  # numba compiles here

    r = {"rows": a.rows, "cols": a.cols, "repeats": a.repeats, "load_average": os.getloadavg(),
         "numpy": np.__version__, "seconds": {}}
    s = r["seconds"]
    s["stream_sum"], _ = best_of(a.repeats, X_c.sum)
    s["pyod_fit"], clf = best_of(a.repeats, lambda: PyodHBOS(n_bins=10).fit(X_c))
    s["pyod_decision_function"], _ = best_of(a.repeats, lambda: clf.decision_function(X_c))
    s["pyod_fit_plus_decision_function"], _ = best_of(
        a.repeats, lambda: PyodHBOS(n_bins=10).fit(X_c).decision_function(X_c))
    for order, X in (("c", X_c), ("f", X_f)):
        s[f"hbos_static10_fit_and_score_{order}"], model = best_of(
            a.repeats, lambda: _hbos.DefaultModel.fit(X, "10", 1))
        s[f"hbos_static10_decision_function_{order}"], _ = best_of(
            a.repeats, lambda: model.decision_function(X))
    s["hbos_HBOS_fit_c"], ours = best_of(a.repeats, lambda: hbos.HBOS().fit(X_c))
    s["hbos_pyod_mode_fit_c"], _ = best_of(a.repeats, lambda: hbos.HBOS(mode="pyod").fit(X_c))

    # The GIL: the same scoring twice in a row, then from two threads at once.
    s["hbos_score_twice_sequential"], _ = best_of(
        a.repeats, lambda: (ours.decision_function(X_c), ours.decision_function(X_c)))
    s["hbos_score_twice_two_threads"] = min(
        two_threads(lambda: ours.decision_function(X_c)) for _ in range(a.repeats))

    if not a.no_auto:
        s["hbos_auto_fit_and_score_c"], _ = best_of(
            a.repeats, lambda: _hbos.DefaultModel.fit(X_c, "auto", 1))
        t0 = time.perf_counter()
        PyodHBOS(n_bins="auto").fit(X_c)
        s["pyod_auto_fit"] = time.perf_counter() - t0

    f = r["ratios"] = {}
    for order in ("c", "f"):
        ours_fs = s[f"hbos_static10_fit_and_score_{order}"]
        f[f"pyod_fit_plus_df_over_hbos_fit_and_score_{order}"] = (
            s["pyod_fit_plus_decision_function"] / ours_fs)
        f[f"pyod_fit_over_hbos_fit_and_score_{order}"] = s["pyod_fit"] / ours_fs
        f[f"hbos_fit_and_score_over_stream_{order}"] = ours_fs / s["stream_sum"]
        f[f"pyod_df_over_hbos_df_{order}"] = (
            s["pyod_decision_function"] / s[f"hbos_static10_decision_function_{order}"])
    f["gil_two_threads_over_sequential"] = (
        s["hbos_score_twice_two_threads"] / s["hbos_score_twice_sequential"])
    if not a.no_auto:
        f["pyod_auto_fit_over_hbos_auto"] = s["pyod_auto_fit"] / s["hbos_auto_fit_and_score_c"]

    for k, v in s.items():
        print(f"{k:45s} {v * 1e3:10.2f} ms")
    for k, v in f.items():
        print(f"{k:55s} {v:8.2f}")
    if a.json:
        write_json(a.json, r)


if __name__ == "__main__":
    main()
