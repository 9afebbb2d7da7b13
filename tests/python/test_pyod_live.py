"""`HBOS(mode="pyod")` against PyOD 3.6.5 itself, imported from its source, on generated data.

The bundled vectors (test_hbos.py) fix six real data sets; this test searches the corners that
real data rarely reaches: many ties, constant columns, values on bin edges, scales from 1e-12 to
1e12, one far outlier, one to a thousand rows, more bins than rows, and test rows below, on and
beyond the training range (PyOD's `tol` branches). Every output must be PyOD's bit for bit,
except in `n_bins="auto"`, where PyOD takes numpy's vectorised log2 (docs/pyod_compat.md); a
failure PyOD reports (bad n_bins, too few rows for "auto") must be a ValueError here too.

PyOD's source is found at $HBOS_PYOD_SOURCE, else at ../shared/tools/pyod-3.6.5 beside the
checkout. The test skips itself when the source or PyOD's dependencies (Debian's python3-numba,
python3-scipy, python3-sklearn) are missing: nothing is downloaded.
"""

import os
import pathlib
import sys
import warnings

import pytest

np = pytest.importorskip("numpy")
hbos = pytest.importorskip("hbos")

def _pyod_source():
    if "HBOS_PYOD_SOURCE" in os.environ:
        return pathlib.Path(os.environ["HBOS_PYOD_SOURCE"])
    checkout = pathlib.Path(__file__).resolve().parents[2]  # tests/python/ -> the checkout
    return checkout.parent / "shared" / "tools" / "pyod-3.6.5"


_SOURCE = _pyod_source()
if not (_SOURCE / "pyod" / "models" / "hbos.py").is_file():
    pytest.skip(f"PyOD 3.6.5's source not found at {_SOURCE}", allow_module_level=True)
for _dependency in ("numba", "scipy", "sklearn"):
    pytest.importorskip(_dependency)
sys.path.insert(0, str(_SOURCE))
PyodHBOS = pytest.importorskip("pyod.models.hbos").HBOS

TRIALS_PER_GROUP = 60
GROUPS = 8


def _column(rng, n):
    kind = rng.integers(0, 9)
    if kind == 0:
        return rng.normal(size=n)
    if kind == 1:  # a few distinct values: ties on every edge
        return rng.integers(0, rng.integers(1, 6), size=n).astype(float)
    if kind == 2:  # constant: PyOD's histogram of one value
        return np.full(n, rng.normal())
    if kind == 3:
        return rng.normal(size=n) * 10.0 ** rng.integers(-12, 13)
    if kind == 4:
        return np.round(rng.normal(size=n), rng.integers(0, 3))
    if kind == 5:  # heavy right tail
        return rng.exponential(size=n) ** 3
    if kind == 6:  # one far outlier empties the inner bins
        c = rng.normal(size=n)
        c[rng.integers(0, n)] = 1e6
        return c
    if kind == 7:  # evenly spaced: values on the bin edges
        return np.linspace(0.0, 1.0, n)
    return rng.choice([-1.0, 0.0, 0.1, 0.2, 0.3, 1.0], size=n)


def _trial(rng):
    n = int(rng.choice([1, 3, 4, 5, 10, 37, 100, 100, 1000, 1000]))
    d = int(rng.integers(1, 5))
    X = np.column_stack([_column(rng, n) for _ in range(d)])
    if rng.random() < 0.3:
        X = np.asfortranarray(X)
    # 2 is refused by PyOD (and so here); more than n bins leaves most of them empty.
    n_bins = rng.choice([2, 3, 5, 10, 10, 17, 50, "auto"])
    params = dict(n_bins=n_bins if n_bins == "auto" else int(n_bins),
                  alpha=float(rng.choice([0.1, 0.5, 1e-9, 0.9])),
                  # PyOD takes tol in (0, 1): 1.0 is refused.
                  tol=float(rng.choice([1e-9, 0.1, 0.5, 0.5, 0.999, 1.0])),
                  contamination=float(rng.choice([0.01, 0.1, 0.25, 0.5])))
    head = X[:min(n, 5)]
    # The training rows, the same rows moved out of range, and rows far beyond it.
    X_test = np.vstack([head, head * 2.0 + 1.0, rng.normal(size=(3, d)) * 100.0])
    return X, X_test, params


def _outputs(model, X, X_test):
    clf = model.fit(X)
    return (np.asarray(clf.decision_scores_), float(clf.threshold_), np.asarray(clf.labels_),
            np.asarray(clf.decision_function(X_test)))


@pytest.mark.parametrize("group", range(GROUPS))
def test_pyod_mode_equals_pyod_on_generated_corners(group):
    rng = np.random.default_rng(20261203 + group)
    compared = 0
    for trial in range(TRIALS_PER_GROUP):
        X, X_test, params = _trial(rng)
        where = f"group {group} trial {trial}: {X.shape[0]} x {X.shape[1]}, {params}"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # numpy's divide warnings inside PyOD
            try:
                expected = _outputs(PyodHBOS(**params), X, X_test)
            except ValueError:
                with pytest.raises(ValueError):
                    _outputs(hbos.HBOS(mode="pyod", **params), X, X_test)
                continue
        scores, threshold, labels, test_scores = _outputs(hbos.HBOS(mode="pyod", **params), X,
                                                          X_test)
        if params["n_bins"] == "auto":
            np.testing.assert_allclose(scores, expected[0], rtol=2e-15, atol=1e-14, err_msg=where)
            np.testing.assert_allclose(test_scores, expected[3], rtol=2e-15, atol=1e-14,
                                       err_msg=where)
            assert threshold == pytest.approx(expected[1], rel=2e-15, abs=1e-14), where
        else:
            assert np.array_equal(scores, expected[0]), where
            assert threshold == expected[1], where
            assert np.array_equal(labels, expected[2]), where
            assert np.array_equal(test_scores, expected[3]), where
        compared += 1
    # Most trials must reach the comparison, not PyOD's refusals.
    assert compared >= TRIALS_PER_GROUP // 2
