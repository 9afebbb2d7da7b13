"""hbos.dask (examples/python/hbos/dask.py) on a local distributed cluster the test starts: a
model fitted chunk by chunk is the in-memory model bit for bit (scores, threshold, labels),
whatever the chunking, on worker processes (the model travels pickled), in the default mode and
in mode="pyod" (where it also gives PyOD 3.6.5's reference scores); non-mergeable settings are
refused. Skipped where Debian's python3-dask / python3-distributed are not installed."""

import os

import pytest

np = pytest.importorskip("numpy")
da = pytest.importorskip("dask.array")
distributed = pytest.importorskip("distributed")
import hbos  # noqa: E402
import hbos.dask  # noqa: E402

# distributed 2022.12 on Debian's tornado 6.2 warns on every cluster start; not ours.
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    try:
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=None)
    except Exception as e:  # a machine that cannot start worker processes on loopback
        pytest.skip(f"no local Dask cluster here: {e!r}")
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def mixed(n, seed):
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.normal(100.0, 4.0, n), rng.exponential(2.0, n),
                            rng.integers(0, 7, n).astype(float), rng.uniform(-10, 10, n),
                            np.full(n, 2.5), rng.standard_t(2, n)])


def bits(a):
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


@pytest.mark.parametrize("chunks", [(1000, 6), (777, 6), (20000, 6), (3001, 2)])
@pytest.mark.parametrize("n_bins", [None, 12])
def test_chunked_fit_is_the_in_memory_fit(client, chunks, n_bins):
    X = mixed(20000, 7)
    whole = hbos.HBOS(n_bins=10 if n_bins is None else n_bins, contamination=0.05).fit(X)
    clf = hbos.dask.fit(da.from_array(X, chunks=chunks), n_bins=n_bins, contamination=0.05)
    np.testing.assert_array_equal(bits(clf.decision_scores_.compute()),
                                  bits(whole.decision_scores_))
    assert clf.threshold_ == whole.threshold_
    np.testing.assert_array_equal(clf.labels_.compute(), whole.labels_)
    Q = mixed(3000, 8) * 1.3
    np.testing.assert_array_equal(bits(hbos.dask.score(clf, da.from_array(Q, chunks=500))),
                                  bits(whole.decision_function(Q)))
    np.testing.assert_array_equal(bits(clf.decision_function(Q)), bits(whole.decision_function(Q)))


# A one-row chunk first and last, uneven chunks between; one chunk; split columns.
@pytest.mark.parametrize("chunks", [((1, 1234, 2764, 1), (6,)), (5000, 6), (1500, 4)])
@pytest.mark.parametrize("n_bins,alpha,tol", [(10, 0.1, 0.5), (7, 0.01, 0.2)])
def test_chunked_pyod_fit_is_the_in_memory_pyod_fit(client, chunks, n_bins, alpha, tol):
    X = mixed(4000, 11)  # a constant feature, an integer one with values on interior edges
    whole = hbos.HBOS(n_bins=n_bins, alpha=alpha, tol=tol, contamination=0.05,
                      mode="pyod").fit(X)
    clf = hbos.dask.fit(da.from_array(X, chunks=chunks), n_bins=n_bins, alpha=alpha, tol=tol,
                        contamination=0.05, mode="pyod")
    assert clf.mode == "pyod"
    scores = clf.decision_scores_.compute()
    np.testing.assert_array_equal(bits(scores), bits(whole.decision_scores_))
    assert clf.threshold_ == whole.threshold_
    np.testing.assert_array_equal(clf.labels_.compute(), whole.labels_)
    for j in range(X.shape[1]):
        np.testing.assert_array_equal(bits(clf._model.bin_edges(j)),
                                      bits(whole._model.bin_edges(j)))
        np.testing.assert_array_equal(bits(clf._model.densities(j)),
                                      bits(whole._model.densities(j)))
    Q = mixed(1500, 12) * 1.3 - 0.5  # inside, on and beyond the training range
    np.testing.assert_array_equal(bits(hbos.dask.score(clf, da.from_array(Q, chunks=400))),
                                  bits(whole.decision_function(Q)))
    np.testing.assert_array_equal(clf.predict(Q), whole.predict(Q))
    # The merged histograms with the training scores make the full PyOD model.
    full = clf._model.model(scores)
    assert full.threshold == whole.threshold_
    np.testing.assert_array_equal(bits(full.decision_scores), bits(whole.decision_scores_))


def test_chunked_pyod_fit_gives_pyod_reference_scores(client, tmp_path):
    data = os.environ.get("HBOS_TEST_DATA_DIR")
    if data is None:
        pytest.skip("HBOS_TEST_DATA_DIR is not set (ctest sets it)")
    d = os.path.join(data, "hbos_pyod", "vertebral")
    X = np.loadtxt(os.path.join(d, "X.csv"), delimiter=",")
    n = X.shape[0]
    clf = hbos.dask.fit(da.from_array(X, chunks=((1, 100, n - 102, 1), (X.shape[1],))), n_bins=20,
                        alpha=0.01, tol=0.2, contamination=0.1, mode="pyod")
    tag = "nb20_a0.01_tol0.2"
    reference = np.loadtxt(os.path.join(d, f"scores_{tag}.csv"))
    np.testing.assert_array_equal(bits(clf.decision_scores_.compute()), bits(reference))
    assert clf.threshold_ == np.loadtxt(os.path.join(d, f"threshold_{tag}.txt"))
    X_test = np.loadtxt(os.path.join(d, "X_test.csv"), delimiter=",")
    np.testing.assert_array_equal(bits(clf.decision_function(X_test)),
                                  bits(np.loadtxt(os.path.join(d, f"test_scores_{tag}.csv"))))
    # Saved (the lazy training scores computed into the file) and loaded: PyOD's model again.
    clf.save(tmp_path / "pyod.hbos")
    again = hbos.HBOS.load(tmp_path / "pyod.hbos")
    assert again.mode == "pyod" and again.threshold_ == clf.threshold_
    np.testing.assert_array_equal(bits(again.decision_scores_), bits(reference))
    np.testing.assert_array_equal(bits(again.decision_function(X_test)),
                                  bits(clf.decision_function(X_test)))


def test_exact_percentile_matches_numpy_on_ties_and_spread(client):
    rng = np.random.default_rng(3)
    # ties (a third of the values equal), a wide spread and more values than one gather holds
    v = np.concatenate([np.full(700000, 1.25), rng.lognormal(0.0, 3.0, 1400000)])
    rng.shuffle(v)
    dv = da.from_array(v, chunks=300000)
    for q in [0.0, 10.0, 33.3, 50.0, 90.0, 99.9, 100.0]:
        assert hbos.dask.percentile(dv, q) == np.percentile(v, q), q


def test_non_mergeable_settings_are_refused(client):
    X = da.from_array(mixed(100, 1), chunks=50)
    with pytest.raises(ValueError, match="Birge-Rozenblac"):
        hbos.dask.fit(X, n_bins="auto")
    with pytest.raises(ValueError, match="auto.*mode='pyod'.*Birge-Rozenblac.*every candidate"):
        hbos.dask.fit(X, n_bins="auto", mode="pyod")
    with pytest.raises(ValueError, match="mode must be"):
        hbos.dask.fit(X, mode="pyod3")
    with pytest.raises(hbos.InvalidArgument, match="n_bins must be > 2"):
        hbos.dask.fit(X, n_bins=2, mode="pyod")
    with pytest.raises(ValueError, match="2-D"):
        hbos.dask.fit(da.zeros(10, chunks=5))
    bad = mixed(100, 1)
    bad[3, 2] = np.nan
    with pytest.raises(hbos.InvalidArgument, match="finite"):
        hbos.dask.fit(da.from_array(bad, chunks=50))
