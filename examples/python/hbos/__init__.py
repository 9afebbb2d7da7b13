"""Histogram-based outlier scores (HBOS) with PyOD's API, on the hbos C++ library.

    from hbos import HBOS
    clf = HBOS(contamination=0.1).fit(X_train)          # default mode: scale-invariant
    clf.decision_scores_, clf.threshold_, clf.labels_   # as PyOD's
    clf.decision_function(X_test); clf.predict(X_test)
    HBOS(mode="pyod")                                  # PyOD 3.6.5's HBOS, bit for bit
    clf.save("model.hbos"); HBOS.load("model.hbos")

Arrays are read in place when they are float64 with positive strides (C or Fortran order, or a
strided view); other dtypes are converted first (one copy). The GIL is released while the C++
code fits and scores. Dask arrays: hbos.dask (fit on chunks, bit-identical to fit in memory).
See docs/data_science.md.
"""

import numpy as np

from . import _hbos

InvalidArgument = _hbos.InvalidArgument

__all__ = ["HBOS", "InvalidArgument"]

_SHIFTS = 5  # the default mode's shifted origins


def _default_bins(n_bins):
    """The default mode's bin setting as the C++ core takes it ("" keeps 5 coarse bins)."""
    return "" if n_bins is None or n_bins == 10 else str(n_bins)


def _as_float64(X):
    X = np.asarray(X, dtype=np.float64)
    if X.ndim == 2 and any(s <= 0 for s in X.strides):
        X = np.ascontiguousarray(X)
    return X


def _as_int(labels):
    """The C++ core's int64 labels as numpy's default int (what ``.astype(int)`` gives)."""
    return labels if labels.dtype == np.dtype(int) else labels.astype(int)


class HBOS:
    """PyOD's ``HBOS(n_bins=10, alpha=0.1, tol=0.5, contamination=0.1)`` plus ``mode``.

    mode="pyod": PyOD 3.6.5's HBOS number for number (n_bins an int > 2 or "auto", alpha, tol).
    mode="default": hbos' scale-invariant HBOS (5 equal-width bins averaged over 5 shifted
    origins; n_bins=None keeps that, an int sets the bins, "auto" picks them by Birge-Rozenblac;
    alpha and tol do not apply). threshold_ is, as in PyOD, the (1 - contamination) percentile
    of decision_scores_ (numpy's linear interpolation), labels_ = decision_scores_ > threshold_.
    """

    def __init__(self, n_bins=10, alpha=0.1, tol=0.5, contamination=0.1, mode="default"):
        if mode not in ("default", "pyod"):
            raise ValueError(f"mode must be 'default' or 'pyod', got {mode!r}")
        if not 0.0 < contamination <= 0.5:
            raise ValueError(f"contamination must lie in (0, 0.5], got {contamination}")
        self.n_bins = n_bins
        self.alpha = alpha
        self.tol = tol
        self.contamination = contamination
        self.mode = mode
        self._model = None

    def fit(self, X, y=None):
        """Fits on X (n_samples x n_features); y is ignored (PyOD's signature)."""
        X = _as_float64(X)
        if self.mode == "pyod":
            auto = isinstance(self.n_bins, str)
            if auto and self.n_bins != "auto":
                raise ValueError(f"n_bins must be an int or 'auto', got {self.n_bins!r}")
            self._model = _hbos.PyodModel.fit(X, 10 if auto else int(self.n_bins), auto,
                                              float(self.alpha), float(self.tol),
                                              float(self.contamination))
            self.decision_scores_ = self._model.decision_scores
        else:
            # The C++ core also takes numpy's percentile (bit for bit) and the labels.
            self._model = _hbos.DefaultModel.fit(X, _default_bins(self.n_bins), _SHIFTS,
                                                 float(self.contamination))
            self.decision_scores_ = self._model.training_scores
        self.threshold_ = self._model.threshold
        self.labels_ = _as_int(self._model.labels)
        return self

    def _fitted(self):
        if self._model is None:
            raise ValueError("this HBOS instance is not fitted yet; call fit(X) first")
        return self._model

    def decision_function(self, X):
        """The outlier score of each row of X (higher = more anomalous)."""
        return self._fitted().decision_function(_as_float64(X))

    def predict(self, X):
        """1 where decision_function(X) > threshold_, else 0."""
        if getattr(self, "threshold_", None) is None:
            raise ValueError("this model has no threshold_ (a default-mode model loaded from a file)")
        return (self.decision_function(X) > self.threshold_).astype(int)

    def save(self, path):
        """Writes the fitted model to a model file (atomically; docs/data_science.md)."""
        model = self._fitted()
        if isinstance(model, _hbos.PyodHistograms):
            # Fitted by hbos.dask in mode="pyod": a PyOD-mode file holds the training scores,
            # so they are computed (np.asarray on the lazy scores) and joined to the histograms.
            model = model.model(np.asarray(self.decision_scores_, dtype=np.float64))
        model.save(str(path))

    @classmethod
    def load(cls, path):
        """A model saved by save(). A PyOD-mode model comes back with decision_scores_,
        threshold_ and labels_; a default-mode file holds the histograms only, so only
        decision_function is available (threshold_ is None)."""
        path = str(path)
        if _hbos.model_kind(path) == "pyod":
            self = cls(mode="pyod")
            self._model = _hbos.PyodModel.load(path)
            self.decision_scores_ = self._model.decision_scores
            self.threshold_ = self._model.threshold
            self.labels_ = _as_int(self._model.labels)
        else:
            self = cls(mode="default")
            self._model = _hbos.DefaultModel.load(path)
            self.threshold_ = None
        return self
