"""Tests of the Python module (examples/python): PyOD 3.6.5's outputs reproduced through
`HBOS(mode="pyod")` on the bundled vectors (tests/data/hbos_pyod), the default mode's scale
invariance, input layouts, and save/load. Run by ctest (python:pytest) with PYTHONPATH set to
the build tree."""

import json
import os
import pathlib

import pytest

np = pytest.importorskip("numpy")
hbos = pytest.importorskip("hbos")
from hbos import HBOS  # noqa: E402

DATA = pathlib.Path(os.environ.get("HBOS_TEST_DATA_DIR",
                                   pathlib.Path(__file__).parents[1] / "data")) / "hbos_pyod"
SETS = ["cardio", "glass", "lympho", "pima", "vertebral", "wbc"]
TAGS = {"nb10_a0.1_tol0.5": (10, 0.1, 0.5), "nb5_a0.1_tol0.5": (5, 0.1, 0.5),
        "nb20_a0.01_tol0.2": (20, 0.01, 0.2), "nbauto_a0.1_tol0.5": ("auto", 0.1, 0.5)}


def load(name, file):
    return np.loadtxt(DATA / name / file, delimiter=",", ndmin=1)


@pytest.mark.parametrize("name", SETS)
@pytest.mark.parametrize("tag", list(TAGS))
def test_pyod_mode_reproduces_pyod(name, tag):
    n_bins, alpha, tol = TAGS[tag]
    X = load(name, "X.csv")
    clf = HBOS(n_bins=n_bins, alpha=alpha, tol=tol, contamination=0.1, mode="pyod").fit(X)
    scores = load(name, f"scores_{tag}.csv")
    test_scores = load(name, f"test_scores_{tag}.csv")
    threshold = float((DATA / name / f"threshold_{tag}.txt").read_text())
    labels = load(name, f"labels_{tag}.csv").astype(int)
    if n_bins == "auto":
        # PyOD's auto path takes numpy's vectorised log2 (docs/pyod_compat.md): the terms agree
        # to 1.4e-15 relative, a sum of them to a few ulps of its largest term.
        np.testing.assert_allclose(clf.decision_scores_, scores, rtol=2e-15, atol=1e-14)
        np.testing.assert_allclose(clf.decision_function(load(name, "X_test.csv")), test_scores,
                                   rtol=2e-15, atol=1e-14)
        assert clf.threshold_ == pytest.approx(threshold, rel=2e-15)
    else:
        assert np.array_equal(clf.decision_scores_, scores)
        assert np.array_equal(clf.decision_function(load(name, "X_test.csv")), test_scores)
        assert clf.threshold_ == threshold
    assert np.array_equal(clf.labels_, labels)
    edges = json.loads((DATA / name / f"edges_{tag}.json").read_text())
    assert np.array_equal(clf._model.bin_edges(0), np.array(edges[0]))


@pytest.mark.parametrize("mode", ["default", "pyod"])
@pytest.mark.parametrize("contamination", [0.1, 0.37, 0.5, 1e-6])
def test_threshold_and_labels_are_numpys(mode, contamination):
    # threshold_ and labels_ come from the C++ core; they must be numpy's percentile (bit for
    # bit) and (scores > threshold).astype(int), on inputs below and above the size where the
    # selection leaves std::nth_element.
    rng = np.random.default_rng(5)
    for X in (load("cardio", "X.csv"), rng.standard_normal((100_000, 2)),
              np.round(rng.standard_normal((30_000, 3)), 1)):
        clf = HBOS(contamination=contamination, mode=mode).fit(X)
        s = clf.decision_scores_
        expected = float(np.percentile(s, 100.0 * (1.0 - contamination)))
        assert isinstance(clf.threshold_, float)
        assert clf.threshold_ == expected
        assert clf.labels_.dtype == (s > expected).astype(int).dtype
        assert np.array_equal(clf.labels_, (s > expected).astype(int))


def test_default_mode_is_scale_invariant():
    X = load("cardio", "X.csv")
    # Power-of-two units change no rounding, so the scores must be the same bits; other units
    # can move a value that sits exactly on a bin edge (cardio's integer features do) by a bin.
    scaled = X * np.array([1024.0 ** (j % 3 - 1) for j in range(X.shape[1])])
    a = HBOS().fit(X).decision_scores_
    b = HBOS().fit(scaled).decision_scores_
    assert np.array_equal(a, b)
    # PyOD's scores change with the units (its alpha is added to densities).
    pa = HBOS(mode="pyod").fit(X).decision_scores_
    pb = HBOS(mode="pyod").fit(scaled).decision_scores_
    assert not np.allclose(pa, pb, rtol=1e-6)


@pytest.mark.parametrize("mode", ["default", "pyod"])
def test_every_layout_gives_the_same_bits(mode):
    X = load("wbc", "X.csv")
    expected = HBOS(mode=mode).fit(X).decision_scores_
    wide = np.zeros((X.shape[0], 2 * X.shape[1]))
    wide[:, ::2] = X
    for layout in (np.asfortranarray(X), np.ascontiguousarray(X), wide[:, ::2], X[::-1][::-1],
                   X.tolist()):
        clf = HBOS(mode=mode).fit(layout)
        assert np.array_equal(clf.decision_scores_, expected)
        assert np.array_equal(clf.decision_function(layout), expected)


@pytest.mark.parametrize("mode", ["default", "pyod"])
def test_save_and_load(tmp_path, mode):
    X = load("glass", "X.csv")
    X_test = load("glass", "X_test.csv")
    clf = HBOS(mode=mode).fit(X)
    path = tmp_path / "model.hbos"
    clf.save(path)
    loaded = HBOS.load(path)
    assert np.array_equal(loaded.decision_function(X_test), clf.decision_function(X_test))
    if mode == "pyod":
        assert np.array_equal(loaded.decision_scores_, clf.decision_scores_)
        assert loaded.threshold_ == clf.threshold_
        assert np.array_equal(loaded.predict(X_test), clf.predict(X_test))
    assert [p.name for p in tmp_path.iterdir()] == ["model.hbos"]


def test_bad_input_raises_value_error():
    X = load("glass", "X.csv")
    bad = X.copy()
    bad[3, 2] = np.nan
    with pytest.raises(ValueError, match=r"X\(3, 2\)"):
        HBOS().fit(bad)
    with pytest.raises(ValueError, match="n_bins must be > 2"):
        HBOS(n_bins=2, mode="pyod").fit(X)
    clf = HBOS().fit(X)
    with pytest.raises(ValueError, match="9 features"):
        clf.decision_function(X[:, :4])
    with pytest.raises(ValueError, match="not fitted"):
        HBOS().decision_function(X)
