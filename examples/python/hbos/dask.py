"""HBOS on Dask arrays: either mode fitted chunk by chunk, bit-identical to ``HBOS(...).fit``.

    import dask.array as da, hbos.dask
    X = da.from_zarr(...)                      # n_samples x n_features, chunked along rows
    clf = hbos.dask.fit(X, contamination=0.1)  # an hbos.HBOS, as if fitted on X in memory
    pyod = hbos.dask.fit(X, n_bins=10, mode="pyod")  # PyOD 3.6.5's HBOS, as if fitted in memory
    scores = hbos.dask.score(clf, X_new)       # a lazy dask array (map_blocks)

The fit is the library's sharded fit (hbos/merge.hpp), two passes over the chunks: per-chunk
(min, max, rows) reduced to the global range, which fixes every bin edge; then per-chunk bin
counts, reduced by addition. Both summaries are small (a few numbers per feature), and both
reductions are exact (min, max and integer sums), so the model is the in-memory model bit for
bit whatever the chunking. threshold_ is exact too: the (1 - contamination) percentile of the
training scores with numpy's linear interpolation, found by narrowing histograms over the score
chunks (a few passes, memory bounded by one chunk plus 2^20 values), not by dask's approximate
percentile. The model pickles as its model-file text, so it travels to workers exactly.

mode="pyod" (PyOD 3.6.5's HBOS, hbos/pyod/merge.hpp) is the same plan: numpy's edges of the
global range, per-chunk numpy counts added up, then a scoring pass for decision_scores_ and the
exact percentile for threshold_, so the model, scores, threshold and labels are
``HBOS(mode="pyod", ...).fit(X)``'s bit for bit. Its merged histograms pickle as the range,
parameters and counts (a few numbers per bin), rebuilt on the worker by the same code.

Mergeable: an integer n_bins (None: the default mode's 5 coarse bins, PyOD's 10 in mode="pyod").
Refused: n_bins="auto" in either mode (the Birge-Rozenblac search histograms all the data for
every candidate bin count; a range summary cannot stand in for it).
"""

import numpy as np

import dask
import dask.array as da

from . import HBOS, _as_float64, _default_bins, _hbos, _SHIFTS

__all__ = ["fit", "score"]

_GATHER_LIMIT = 1 << 20  # values gathered at most when selecting an order statistic
_SELECT_BINS = 1024


def _rows_only(X):
    """X as a 2-D float64 dask array chunked along rows only."""
    X = da.asarray(X)
    if X.ndim != 2:
        raise ValueError(f"X must be a 2-D array, got {X.ndim} dimensions")
    if X.shape[0] == 0 or X.shape[1] == 0:
        raise ValueError(f"X must have rows and columns, got shape {X.shape}")
    return X.astype(np.float64).rechunk({1: -1})


def _range(block):
    return _hbos.summarize_range(_as_float64(block))


def _count(block, lo, hi, rows, bins):
    return _hbos.count_shard(_as_float64(block), lo, hi, rows, bins, _SHIFTS)


def _merge_ranges(parts):
    parts = list(parts)
    lo = np.minimum.reduce([p[0] for p in parts])
    hi = np.maximum.reduce([p[1] for p in parts])
    return lo, hi, sum(int(p[2]) for p in parts)


def _add_counts(parts):
    parts = list(parts)
    return [np.sum([p[j] for p in parts], axis=0, dtype=np.int64) for j in range(len(parts[0]))]


def _tree(items, combine, width=8):
    """Reduces delayed items `width` at a time (a tree, so no task holds every summary)."""
    items = list(items)
    while len(items) > 1:
        items = [dask.delayed(combine)(items[k:k + width]) for k in range(0, len(items), width)]
    return items[0] if len(items) == 1 else dask.delayed(combine)(items)


def _pyod_count(block, lo, hi, rows, params):
    return _hbos.pyod_count_shard(_as_float64(block), lo, hi, rows, *params)


def fit(X, n_bins=None, contamination=0.1, mode="default", alpha=0.1, tol=0.5):
    """Fits HBOS on a 2-D dask array (or anything dask.array.asarray takes).

    Returns an hbos.HBOS with decision_scores_ (a lazy dask array), threshold_ and labels_
    (lazy), whose model scores bit for bit as ``HBOS(n_bins, alpha, tol, contamination,
    mode).fit(X)`` (alpha and tol apply to mode="pyod" only)."""
    if mode not in ("default", "pyod"):
        raise ValueError(f"mode must be 'default' or 'pyod', got {mode!r}")
    if isinstance(n_bins, str):
        why = ("PyOD's Birge-Rozenblac search histograms all the data for every candidate bin "
               "count" if mode == "pyod" else "the Birge-Rozenblac rule needs all the data")
        raise ValueError(f"n_bins={n_bins!r} cannot be fitted by chunks in mode={mode!r} ({why}); "
                         "pass " + ("an int" if mode == "pyod" else "None or an int"))
    if mode == "pyod":
        clf = HBOS(n_bins=10 if n_bins is None else int(n_bins), alpha=alpha, tol=tol,
                   contamination=contamination, mode="pyod")
        params = (clf.n_bins, float(alpha), float(tol), float(contamination))
        _hbos.pyod_check_params(*params)  # PyOD's checks, before any pass
    else:
        clf = HBOS(n_bins=10 if n_bins is None else n_bins, contamination=contamination)
        bins = _default_bins(n_bins)
    X = _rows_only(X)
    blocks = X.to_delayed().ravel()
    lo, hi, rows = dask.compute(_tree([dask.delayed(_range)(b) for b in blocks],
                                      _merge_ranges))[0]
    if mode == "pyod":
        counts = [dask.delayed(_pyod_count)(b, lo, hi, rows, params) for b in blocks]
        total = dask.compute(_tree(counts, _add_counts))[0]
        clf._model = _hbos.PyodHistograms.from_counts(lo, hi, rows, *params, total)
    else:
        counts = [dask.delayed(_count)(b, lo, hi, rows, bins) for b in blocks]
        total = dask.compute(_tree(counts, _add_counts))[0]
        clf._model = _hbos.DefaultModel.from_counts(lo, hi, rows, bins, _SHIFTS, total)
    clf.decision_scores_ = score(clf, X)
    clf.threshold_ = percentile(clf.decision_scores_, 100.0 * (1.0 - contamination))
    clf.labels_ = (clf.decision_scores_ > clf.threshold_).astype(int)
    return clf


def score(clf, X):
    """decision_function of a fitted hbos.HBOS on a 2-D dask array: a lazy 1-D dask array."""
    model = clf._fitted()
    X = _rows_only(X)
    if X.shape[1] != model.n_features:
        raise ValueError(f"X has {X.shape[1]} features, the model {model.n_features}")
    return X.map_blocks(lambda b: model.decision_function(_as_float64(b)), drop_axis=1,
                        dtype=np.float64)


def _counts_in(block, lo, hi, edges):
    """Per block: values < lo, then one slot per [edges[k], edges[k+1]) and one for == hi."""
    inside = block[(block >= lo) & (block <= hi)]
    slots = np.searchsorted(edges, inside, side="right")  # 1..len(edges)
    return (np.count_nonzero(block < lo),
            np.bincount(slots, minlength=len(edges) + 1)[1:])


def _order_statistic(values, rank):
    """The value of 0-based `rank` in the ascending order of the 1-D dask array `values`,
    exactly: histograms narrow the window holding it until it is small enough to gather."""
    blocks = values.to_delayed().ravel()
    lo, hi = (float(v) for v in dask.compute(values.min(), values.max()))
    while True:
        if lo == hi:
            return lo
        edges = np.unique(np.linspace(lo, hi, _SELECT_BINS + 1))
        parts = dask.compute(*[dask.delayed(_counts_in)(b, lo, hi, edges) for b in blocks])
        below = sum(p[0] for p in parts)
        counts = np.sum([p[1] for p in parts], axis=0)
        if counts.sum() <= _GATHER_LIMIT:
            window = np.concatenate(dask.compute(*[
                dask.delayed(lambda b: b[(b >= lo) & (b <= hi)])(b) for b in blocks]))
            return float(np.partition(window, rank - below)[rank - below])
        cum = below + np.cumsum(counts)
        slot = int(np.searchsorted(cum, rank, side="right"))  # first slot with cum > rank
        if slot == len(edges) - 1:  # the values equal to hi
            return hi
        lo, hi = float(edges[slot]), float(np.nextafter(edges[slot + 1], -np.inf))


def percentile(values, q):
    """numpy.percentile(values, q) (linear interpolation) of a 1-D dask array, bit for bit."""
    n = int(values.shape[0])
    if n == 0:
        raise ValueError("percentile of an empty array")
    virtual = (n - 1) * np.true_divide(q, 100)  # numpy's linear method, in its operation order
    previous = int(np.floor(virtual))
    if previous >= n - 1:
        return _order_statistic(values, n - 1)
    if previous < 0:
        return _order_statistic(values, 0)
    a = _order_statistic(values, previous)
    b = _order_statistic(values, previous + 1)
    gamma = virtual - previous
    diff = b - a
    return float(b - diff * (1 - gamma)) if gamma >= 0.5 else float(a + diff * gamma)
