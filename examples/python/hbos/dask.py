"""HBOS on Dask arrays: the default mode fitted chunk by chunk, bit-identical to ``HBOS().fit``.

    import dask.array as da, hbos.dask
    X = da.from_zarr(...)                      # n_samples x n_features, chunked along rows
    clf = hbos.dask.fit(X, contamination=0.1)  # an hbos.HBOS, as if fitted on X in memory
    scores = hbos.dask.score(clf, X_new)       # a lazy dask array (map_blocks)

The fit is the library's sharded fit (hbos/merge.hpp), two passes over the chunks: per-chunk
(min, max, rows) reduced to the global range, which fixes every bin edge; then per-chunk bin
counts, reduced by addition. Both summaries are small (a few numbers per feature), and both
reductions are exact (min, max and integer sums), so the model is the in-memory model bit for
bit whatever the chunking. threshold_ is exact too: the (1 - contamination) percentile of the
training scores with numpy's linear interpolation, found by narrowing histograms over the score
chunks (a few passes, memory bounded by one chunk plus 2^20 values), not by dask's approximate
percentile. The model pickles as its model-file text, so it travels to workers exactly.

Only the default mode with a bin count known from the range and size is mergeable: n_bins None
(5 coarse bins), an int, not "auto" (Birge-Rozenblac needs all the data) and not mode="pyod".
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


def fit(X, n_bins=None, contamination=0.1):
    """Fits the default-mode HBOS on a 2-D dask array (or anything dask.array.asarray takes).

    Returns an hbos.HBOS with decision_scores_ (a lazy dask array), threshold_ and labels_
    (lazy), whose model scores bit for bit as ``HBOS(n_bins, contamination=...).fit(X)``."""
    if isinstance(n_bins, str):
        raise ValueError(f"n_bins={n_bins!r} cannot be fitted by chunks (the Birge-Rozenblac rule "
                         "needs all the data); pass None or an int")
    clf = HBOS(n_bins=10 if n_bins is None else n_bins, contamination=contamination)
    X = _rows_only(X)
    bins = _default_bins(n_bins)
    blocks = X.to_delayed().ravel()
    lo, hi, rows = dask.compute(_tree([dask.delayed(_range)(b) for b in blocks],
                                      _merge_ranges))[0]
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
