#pragma once
/// \file
/// PyOD-compatible HBOS: PyOD 3.6.5's `pyod.models.hbos.HBOS`, number for number, so that a user
/// migrating from PyOD gets the same scores, threshold and labels (docs/pyod_compat.md).
///
/// What PyOD computes, per feature j with n training values (all arithmetic IEEE double):
///  1. Edges, from numpy.histogram: lo = min, hi = max (widened by 0.5 each side for a constant
///     feature), e_k = k * ((hi - lo) / B) + lo with the product rounded before the sum, e_B = hi.
///  2. Counts: N_k = #{e_k <= x < e_{k+1}}, the last bin closed.
///  3. Densities: h_k = (N_k / (e_{k+1} - e_k)) / n.
///  4. Bin count B: the user's integer, or with `auto_bins` PyOD's Birgé–Rozenblac variant,
///     chosen per feature (it may be 1): the first argmax over b = 1 .. floor(sqrt n) - 1 of
///     L(b) = sum_k [N_k ln(b N_k / n + 1) - (b - 1 + ln(b)^2.5)], the penalty inside the sum.
///  5. Per value, with d = numpy.digitize(x, e, right=True) = #{k : e_k < x}:
///     1 <= d <= B uses log2(h_{d-1} + alpha), i.e. the bin (e_{d-1}, e_d];
///     below e_0 it uses bin 0 if e_0 - x <= (e_1 - e_0) tol, above e_B bin B-1 if
///     x - e_B <= (e_B - e_{B-1}) tol, and otherwise min_k log2(h_k + alpha).
///  6. score = -(sum over features, numpy's pairwise order); higher = more anomalous.
///  7. threshold = the (1 - contamination) percentile of the training scores (numpy "linear");
///     label = score > threshold (strict).
///
/// Fitting on row shards (bit-identical to fit on all rows, integer n_bins only):
/// hbos/pyod/merge.hpp.
///
/// Two PyOD defects are reproduced **on purpose** (that is the point of this mode; the default
/// hbos model does not have them):
///  - Edge convention. Counting uses [e_k, e_{k+1}) but look-up uses (e_{k-1}, e_k], so a training
///    value exactly on an interior edge e_k is counted in bin k yet scored with bin k-1's density.
///    Integer-valued features hit this all the time (cardio: 1069 such values at B = 10).
///  - Scale dependence. alpha is added to a *density*, whose unit is 1/feature-unit: rescaling a
///    feature by 1000 divides its densities by 1000, so alpha then swamps them and the feature's
///    weight in the score changes; rankings and ROC-AUC change with the units.
///
/// Parity (tests/unit/test_pyod.cpp, against PyOD's own outputs on six ODDS sets under four
/// parameter sets): bin counts, edges, densities, counts and labels identical; scores and
/// thresholds bit-identical for integer n_bins, within 1.4e-15 relative for auto (PyOD's auto path
/// takes numpy's vectorised log2). Do not compile with -ffast-math (it breaks numpy's rounding
/// order). FMA contraction is guarded in the code (detail::mul_rounded), so -march=native is fine.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "hbos/error.hpp"
#include "hbos/pyod/detail/numpy_replica.hpp"
#include "hbos/threshold.hpp"

namespace hbos {

/// PyOD's `HBOS(n_bins, alpha, tol, contamination)`. Defaults are PyOD's.
struct PyodParams {
  Eigen::Index n_bins = 10;  ///< bins per feature (PyOD's integer `n_bins`), in [3, kMaxPyodBins]
  bool auto_bins = false;  ///< PyOD's `n_bins="auto"`: Birgé–Rozenblac per feature, needs n > 3
  double alpha = 0.1;      ///< added to each density before log2, in (0, 1) [1/feature-unit]
  double tol = 0.5;        ///< how far outside the range still uses the edge bin, in (0, 1) [bins]
  double contamination = 0.1;  ///< share of training samples labelled outliers, in (0, 0.5]
};

/// The largest PyodParams::n_bins: 2^24 bins (about 1 GB per feature). PyOD has no bound; 2^32
/// would ask for 34 GB.
inline constexpr Eigen::Index kMaxPyodBins = Eigen::Index{1} << 24;

/// The branch PyOD's scorer takes for one value (see PyodHbos, step 5).
enum class PyodBranch {
  InRange,         ///< e_0 < x <= e_B: bin (e_{d-1}, e_d]
  BelowWithinTol,  ///< x <= e_0 and e_0 - x <= (e_1 - e_0) tol: bin 0 (includes x == minimum)
  BelowBeyondTol,  ///< further below: the sparsest bin
  AboveWithinTol,  ///< x > e_B and x - e_B <= (e_B - e_{B-1}) tol: bin B-1
  AboveBeyondTol   ///< further above: the sparsest bin
};

/// How one value of one feature is scored.
struct PyodLookup {
  PyodBranch branch = PyodBranch::InRange;  ///< which rule applied
  Eigen::Index bin = 0;           ///< bin whose density is used (first sparsest bin if beyond tol)
  double log_term = 0.0;          ///< log2(density + alpha); the row score is minus the sum
  bool on_interior_edge = false;  ///< x equals an interior edge: counted in `bin + 1`, scored here
};

namespace detail {

/// A read-only matrix as a pointer and two strides: every Eigen dense object with direct access
/// (Matrix, Array, Map, Ref, Block, either storage order) and raw row-major buffers.
template <class Scalar>
struct StridedView {
  const Scalar* data = nullptr;
  Eigen::Index rows = 0;
  Eigen::Index cols = 0;
  Eigen::Index row_stride = 0;
  Eigen::Index col_stride = 0;
  [[nodiscard]] Scalar operator()(Eigen::Index i, Eigen::Index j) const {
    return data[i * row_stride + j * col_stride];
  }
};

/// Calls f with a view of X: no copy when X has direct access (any storage order, any strides);
/// other expressions are evaluated once into a column-major temporary that outlives the call.
template <class Derived, class F>
decltype(auto) with_strided_view(const Eigen::DenseBase<Derived>& X, F&& f) {
  using Scalar = typename Derived::Scalar;
  if constexpr ((static_cast<unsigned>(Eigen::DenseBase<Derived>::Flags) &
                 Eigen::DirectAccessBit) != 0) {
    const Derived& x = X.derived();
    return std::forward<F>(f)(
        StridedView<Scalar>{x.data(), x.rows(), x.cols(), x.rowStride(), x.colStride()});
  } else {
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> evaluated = X;
    return std::forward<F>(f)(StridedView<Scalar>{evaluated.data(), evaluated.rows(),
                                                  evaluated.cols(), 1, evaluated.rows()});
  }
}

/// PyOD's own parameter checks (`check_parameter`, BaseDetector).
inline void validate(const PyodParams& p) {
  if (!p.auto_bins) {
    require(p.n_bins > 2, "PyodParams::n_bins must be > 2 (PyOD rejects n_bins <= 2), got ",
            p.n_bins);
    require(p.n_bins <= kMaxPyodBins, "PyodParams::n_bins must be <= ", kMaxPyodBins,
            " (2^24), got ", p.n_bins);
  }
  require(p.alpha > 0.0 && p.alpha < 1.0,
          "PyodParams::alpha must lie in the open interval (0, 1), got ", p.alpha);
  require(p.tol > 0.0 && p.tol < 1.0, "PyodParams::tol must lie in the open interval (0, 1), got ",
          p.tol);
  require(p.contamination > 0.0 && p.contamination <= 0.5,
          "PyodParams::contamination must lie in (0, 0.5], got ", p.contamination);
}

/// Calls f(stride) with a compile-time 1 when the stride is 1 (a column of a column-major
/// matrix), so that the hot loops index contiguously; otherwise with the runtime stride.
template <class F>
decltype(auto) with_stride(Eigen::Index stride, F&& f) {
  if (stride == 1) return std::forward<F>(f)(std::integral_constant<Eigen::Index, 1>{});
  return std::forward<F>(f)(stride);
}

/// numpy's histogram range of feature j, which must not overflow a double (numpy's bins of
/// width inf would give NaN and the auto search a negative cell count).
inline OuterEdges pyod_histogram_range(Eigen::Index j, double min_value, double max_value) {
  const OuterEdges range = numpy_outer_edges(min_value, max_value);
  require(std::isfinite(range.hi - range.lo), "feature ", j, ": its range [", range.lo, ", ",
          range.hi, "] overflows a double");
  return range;
}

/// The B + 1 edges numpy.histogram places over a feature whose values span [min_value,
/// max_value]: what PyodHbos::fit uses, and what the sharded fit (hbos/pyod/merge.hpp) fixes
/// from the merged range. Refuses bins narrower than the floating-point resolution.
inline Eigen::VectorXd pyod_bin_edges(Eigen::Index j, Eigen::Index B, double min_value,
                                      double max_value) {
  const OuterEdges range = pyod_histogram_range(j, min_value, max_value);
  Eigen::VectorXd edges(B + 1);
  numpy_histogram_edges(range, B, edges.data());
  for (Eigen::Index k = 0; k < B; ++k) {
    // numpy would divide 0 by a 0 width here and score NaN; refuse instead.
    require(edges[k] < edges[k + 1], "feature ", j, ": ", B,
            " bins are narrower than the floating-point resolution near ", edges[k], " (edges ", k,
            " and ", k + 1, " are equal); rescale or shift the feature");
  }
  return edges;
}

template <class Scalar>
void require_finite_entry(const StridedView<Scalar>& X, const char* what) {
  for (Eigen::Index j = 0; j < X.cols; ++j) {
    for (Eigen::Index i = 0; i < X.rows; ++i) {
      require(std::isfinite(X(i, j)), what, "(", i, ", ", j, ") is not finite: ", X(i, j));
    }
  }
}

}  // namespace detail

template <class Scalar>
class PyodHistograms;  // hbos/pyod/merge.hpp: the histograms of a sharded fit
template <class Scalar>
class PyodFeatureModel;  // one feature on its own (below)

/// HBOS exactly as PyOD 3.6.5 computes it (the maths is in this file's header comment), as an
/// immutable fitted model.
///
/// Invariant: every feature has B_j >= 1 bins with strictly increasing edges, B_j + 1 edges,
/// B_j densities and counts summing to n; decision_scores() == decision_function(training X) bit
/// for bit. Histogram parameters are kept in double whatever Scalar is (as numpy does), so a
/// float model is the double model of the same (float-representable) data; Scalar is the type of
/// the input values and of the scores.
///
/// Inputs: any Eigen dense expression (Matrix, Map, Ref, Block; no copy when it has direct
/// access, in either storage order) or a raw row-major buffer; rows are samples, columns
/// features. Invalid input (empty, NaN/Inf, wrong column count, PyOD's parameter checks) throws
/// InvalidArgument. PyOD yields NaN scores where a bin is narrower than the floating-point
/// resolution of its values (a 0-width bin divides 0 by 0); this class throws instead.
///
/// Threading: a fitted model is immutable; all const members may be called from many threads.
template <class Scalar>
class PyodHbos {
  static_assert(std::is_same_v<Scalar, float> || std::is_same_v<Scalar, double>,
                "PyodHbos is defined for float and double");

 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;        ///< one score per sample
  using Labels = Eigen::VectorXi;                                 ///< 1 = outlier, 0 = inlier
  using Counts = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1>;  ///< samples per bin

  /// Fits on X (n samples x d features); the training scores, threshold and labels are part of
  /// the fit, as in PyOD.
  template <class Derived>
  [[nodiscard]] static PyodHbos fit(const Eigen::DenseBase<Derived>& X,
                                    const PyodParams& params = {}) {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "PyodHbos<Scalar>::fit: X must hold Scalar values (use .template cast<>())");
    return detail::with_strided_view(
        X, [&](const detail::StridedView<Scalar>& view) { return fit_view(view, params); });
  }

  /// Fits on a raw row-major buffer of rows x cols values (sample i, feature j at i * cols + j).
  [[nodiscard]] static PyodHbos fit(const Scalar* data, Eigen::Index rows, Eigen::Index cols,
                                    const PyodParams& params = {}) {
    return fit_view(row_major_view(data, rows, cols), params);
  }

  /// PyOD's `decision_function`: the score of each row of X (higher = more anomalous).
  template <class Derived>
  [[nodiscard]] Vector decision_function(const Eigen::DenseBase<Derived>& X) const {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "PyodHbos<Scalar>::decision_function: X must hold Scalar values");
    return detail::with_strided_view(
        X, [&](const detail::StridedView<Scalar>& view) { return score_view(view); });
  }

  /// decision_function on a raw row-major buffer of rows x cols values.
  [[nodiscard]] Vector decision_function(const Scalar* data, Eigen::Index rows,
                                         Eigen::Index cols) const {
    return score_view(row_major_view(data, rows, cols));
  }

  /// PyOD's `predict`: 1 where decision_function(X) > threshold(), else 0.
  template <class Derived>
  [[nodiscard]] Labels predict(const Eigen::DenseBase<Derived>& X) const {
    return label(decision_function(X));
  }

  /// predict on a raw row-major buffer of rows x cols values.
  [[nodiscard]] Labels predict(const Scalar* data, Eigen::Index rows, Eigen::Index cols) const {
    return label(decision_function(data, rows, cols));
  }

  /// PyOD's `decision_scores_`: the training scores.
  [[nodiscard]] const Vector& decision_scores() const { return scores_; }
  /// PyOD's `threshold_`.
  [[nodiscard]] Scalar threshold() const { return threshold_; }
  /// PyOD's `labels_`: decision_scores() > threshold().
  [[nodiscard]] const Labels& labels() const { return labels_; }

  /// Bin count B_j of feature j (PyOD's `n_bins`, or the `auto` choice).
  [[nodiscard]] Eigen::Index bins(Eigen::Index j) const { return feature(j).edges.size() - 1; }
  /// The B_j + 1 edges of feature j (PyOD's `bin_edges_[:, j]`, or `bin_edges_[j]` for auto).
  [[nodiscard]] const Eigen::VectorXd& bin_edges(Eigen::Index j) const { return feature(j).edges; }
  /// The B_j densities of feature j (PyOD's `hist_[:, j]`, or `hist_[j]` for auto).
  [[nodiscard]] const Eigen::VectorXd& densities(Eigen::Index j) const {
    return feature(j).densities;
  }
  /// The B_j training counts of feature j (numpy.histogram's counts).
  [[nodiscard]] const Counts& counts(Eigen::Index j) const { return feature(j).counts; }

  /// How value x of feature j is scored: branch, bin used and its log2(density + alpha).
  [[nodiscard]] PyodLookup lookup(Eigen::Index j, Scalar x) const {
    const Feature& f = feature(j);
    const double v = static_cast<double>(x);
    const Eigen::Index b = f.digitize(v);
    const Eigen::Index B = f.bins();
    PyodLookup out;
    out.log_term = f.term(v, b);
    if (b >= 1 && b <= B) {
      out.branch = PyodBranch::InRange;
      out.bin = b - 1;
      // digitize counts e_k < x, so x == e_b (b in 1..B-1) is scored with bin b-1.
      out.on_interior_edge = b <= B - 1 && v == f.edges[b];
    } else if (b == 0) {
      const bool within = f.edges[0] - v <= f.tol_below;
      out.branch = within ? PyodBranch::BelowWithinTol : PyodBranch::BelowBeyondTol;
      out.bin = within ? 0 : f.sparsest;
    } else {
      const bool within = v - f.edges[B] <= f.tol_above;
      out.branch = within ? PyodBranch::AboveWithinTol : PyodBranch::AboveBeyondTol;
      out.bin = within ? B - 1 : f.sparsest;
    }
    return out;
  }

  [[nodiscard]] Eigen::Index n_samples() const { return scores_.size(); }
  [[nodiscard]] Eigen::Index n_features() const {
    return static_cast<Eigen::Index>(features_.size());
  }
  [[nodiscard]] const PyodParams& params() const { return params_; }

  /// Assembles a model from its features, each fitted or rebuilt on its own (PyodFeatureModel,
  /// feature j at index j), and the training scores: the model those features and scores came
  /// from, bit for bit. The threshold and labels are recomputed from the scores.
  /// \throws InvalidArgument on a feature out of order, a feature of other parameters, or a
  /// training score that is not finite.
  [[nodiscard]] static PyodHbos from_features(std::vector<PyodFeatureModel<Scalar>> features,
                                              const PyodParams& params, Vector training_scores) {
    detail::validate(params);
    const Eigen::Index n = training_scores.size();
    detail::require(!features.empty() && n >= 1 && (!params.auto_bins || n > 3), "a model of ",
                    features.size(), " features and ", n, " training samples is not one PyOD fits");
    for (Eigen::Index i = 0; i < n; ++i)
      detail::require(std::isfinite(training_scores[i]), "training score ", i, " is not finite (",
                      training_scores[i], ")");
    PyodHbos model;
    model.params_ = params;
    model.features_.reserve(features.size());
    for (std::size_t j = 0; j < features.size(); ++j) {
      PyodFeatureModel<Scalar>& f = features[j];
      detail::require(f.index() == static_cast<Eigen::Index>(j), "feature ", f.index(),
                      " given at index ", j);
      detail::require(params.auto_bins || f.bins() == params.n_bins, "feature ", j, ": ", f.bins(),
                      " bins but n_bins = ", params.n_bins);
      model.features_.push_back(std::move(f.f_));
      // A whole model scores data of any size later: every feature gets its grid.
      add_grid(model.features_.back());
    }
    model.set_training_scores(std::move(training_scores));
    return model;
  }

  /// Assembles a fitted model from what a model file stores (hbos/pyod/model_file.hpp): per
  /// feature its B_j + 1 edges and B_j counts, the parameters and the training scores. Each
  /// feature is refitted on a column holding counts[k] copies of edges[k] with the range
  /// [e_0, e_B] (numpy's edges of that range are the stored ones), so densities and look-up
  /// tables come from the code `fit` uses and the model scores bit for bit like the one the
  /// parts came from; the threshold and labels are recomputed from the training scores.
  /// \throws InvalidArgument naming the feature whose parts are inconsistent.
  [[nodiscard]] static PyodHbos from_parts(const std::vector<Eigen::VectorXd>& edges,
                                           const std::vector<Counts>& counts,
                                           const PyodParams& params, Vector training_scores) {
    detail::validate(params);
    const auto d = static_cast<Eigen::Index>(edges.size());
    const Eigen::Index n = training_scores.size();
    detail::require(d >= 1 && counts.size() == edges.size(), "a model needs edges and counts for ",
                    "each of at least one feature, got ", edges.size(), " and ", counts.size());
    detail::require(n >= 1 && (!params.auto_bins || n > 3), "a model of ", n,
                    " training samples is not one PyOD fits");
    for (Eigen::Index i = 0; i < n; ++i)
      detail::require(std::isfinite(training_scores[i]), "training score ", i, " is not finite (",
                      training_scores[i], ")");
    PyodHbos model;
    model.params_ = params;
    for (Eigen::Index j = 0; j < d; ++j) {
      model.features_.push_back(feature_from_parts(edges[static_cast<std::size_t>(j)],
                                                   counts[static_cast<std::size_t>(j)], n, j,
                                                   params, GridRule::Always));
    }
    model.set_training_scores(std::move(training_scores));
    return model;
  }

 private:
  using View = detail::StridedView<Scalar>;

  /// One cell of a feature's look-up grid (see Feature).
  struct Cell {
    double edge;   // the interior edge inside the cell, +inf if none
    double below;  // log term of values <= edge (all values when there is no edge)
    double above;  // log term of values > edge; NaN (both) when 2+ edges share the cell
  };

  /// One feature's histogram and what scoring needs from it.
  ///
  /// Scoring is exact and mostly one table look-up: [e_0, e_B] is cut into `cells` equal cells
  /// (at least 64 per bin). cell() is monotone, so for a value x in cell c every interior edge in
  /// a cell below c is < x and every one in a cell above is > x: only an edge inside c itself
  /// needs a comparison, and each cell stores that edge with the log terms of both sides. Values
  /// outside [e_0, e_B], and cells holding several edges (past 65536 bins, or edges crowded by
  /// rounding), take the general path: digitize against the edges, then PyOD's branches.
  /// A feature without a grid (cells == 0, see GridRule) takes the general path for every value:
  /// the same bins, found by a search that starts at the right bin give or take one.
  struct Feature {
    Eigen::VectorXd edges;      // B + 1, strictly increasing
    Eigen::VectorXd densities;  // B
    Counts counts;              // B
    Eigen::VectorXd log_terms;  // log2(densities + alpha)
    double lo = 0.0;            // e_0
    double hi = 0.0;            // e_B
    double norm = 0.0;          // B / (e_B - e_0): (x - lo) * norm is about x's bin position
    double log_min = 0.0;       // min_k log_terms, what far out-of-range values get
    Eigen::Index sparsest = 0;  // first k with log_terms[k] == log_min
    double tol_below = 0.0;     // (e_1 - e_0) * tol
    double tol_above = 0.0;     // (e_B - e_{B-1}) * tol
    double cell_scale = 0.0;    // nominal cell count / (e_B - e_0)
    Eigen::Index cells = 0;     // 0: no grid
    std::vector<Cell> grid;

    [[nodiscard]] Eigen::Index bins() const { return edges.size() - 1; }  // set first
    [[nodiscard]] bool has_grid() const { return cells > 0; }

    /// Cell of x in [lo, hi]: in [0, cells), since it is monotone in x and cells = cell(hi) + 1.
    [[nodiscard]] Eigen::Index cell(double x) const {
      return static_cast<Eigen::Index>((x - lo) * cell_scale);
    }

    [[nodiscard]] Eigen::Index digitize(double x) const {
      const Eigen::Index B = bins();
      return detail::digitize_right(x, edges.data(), B, detail::bin_guess(x, lo, norm, B + 1));
    }

    /// log2(h + alpha) of the bin PyOD uses for x, given d = digitize(x).
    [[nodiscard]] double term(double x, Eigen::Index d) const {
      const Eigen::Index B = bins();
      if (d >= 1 && d <= B) return log_terms[d - 1];
      if (d == 0) return edges[0] - x <= tol_below ? log_terms[0] : log_min;
      return x - edges[B] <= tol_above ? log_terms[B - 1] : log_min;
    }

    [[nodiscard]] double term_exact(double x) const { return term(x, digitize(x)); }

    /// The bin x in [lo, hi] is counted in and the bin it is scored with, by search.
    void exact_bins(double x, Eigen::Index& counted, Eigen::Index& scored) const {
      const Eigen::Index B = bins();
      counted = detail::count_bin(x, edges.data(), B, detail::bin_guess(x, lo, norm, B - 1));
      scored = std::max<Eigen::Index>(digitize(x), 1) - 1;
    }
  };

  PyodHbos() = default;

  /// Whether a feature gets its look-up grid. A whole PyodHbos scores data of any size later, so
  /// its features always have one; a feature on its own (PyodFeatureModel) has one only when it
  /// counts at least as many values as the grid has cells, since building the grid costs about
  /// as much as that many searches (a wide file's feature of two values would otherwise spend
  /// nearly all its time on 1024 cells).
  enum class GridRule { Always, IfPays };

  /// The grid's nominal cell count for B bins: 64 cells per bin, at least 1024, at most 65536.
  [[nodiscard]] static Eigen::Index nominal_cells(Eigen::Index B) {
    return std::min<Eigen::Index>(std::max<Eigen::Index>(1024, 64 * B), 65536);
  }

  [[nodiscard]] static bool wants_grid(GridRule rule, Eigen::Index values, Eigen::Index B) {
    return rule == GridRule::Always || values >= nominal_cells(B);
  }

  // The sharded fit (hbos/pyod/merge.hpp) builds models from merged counts.
  template <class>
  friend class PyodHistograms;
  // One feature on its own, for models too wide to hold whole.
  template <class>
  friend class PyodFeatureModel;

  /// The histograms of n samples from each feature's numpy edges (detail::pyod_bin_edges) and
  /// counts, through the code fit uses, with no training outputs yet (set_training_scores).
  [[nodiscard]] static PyodHbos from_counts(const std::vector<Eigen::VectorXd>& edges,
                                            const std::vector<std::vector<Eigen::Index>>& counts,
                                            Eigen::Index n, const PyodParams& params) {
    PyodHbos model;
    model.params_ = params;
    for (std::size_t j = 0; j < edges.size(); ++j) {
      Layout layout;
      Feature f = lay_out(edges[j], layout, true);
      f.counts = Eigen::Map<const Counts>(counts[j].data(), f.bins());
      finish(f, layout, n, static_cast<Eigen::Index>(j), model.params_);
      model.features_.push_back(std::move(f));
    }
    return model;
  }

  /// The training outputs of a model: its scores of the training rows, the threshold PyOD
  /// derives from them and the labels.
  void set_training_scores(Vector training_scores) {
    std::vector<Scalar> percentile_scratch;
    threshold_ = detail::pyod_threshold(training_scores.data(), training_scores.size(),
                                        params_.contamination, percentile_scratch);
    scores_ = std::move(training_scores);
    labels_ = label(scores_);
  }

  [[nodiscard]] static View row_major_view(const Scalar* data, Eigen::Index rows,
                                           Eigen::Index cols) {
    detail::require(rows >= 0 && cols >= 0, "buffer shape must be non-negative, got ", rows, " x ",
                    cols);
    detail::require(data != nullptr || rows * cols == 0, "buffer of ", rows, " x ", cols,
                    " values is a null pointer");
    return View{data, rows, cols, cols, 1};
  }

  [[nodiscard]] const Feature& feature(Eigen::Index j) const {
    detail::require(j >= 0 && j < n_features(), "feature index must lie in [0, ", n_features(),
                    "), got ", j);
    return features_[static_cast<std::size_t>(j)];
  }

  /// Smallest and largest value of a column. With a NaN in the column the result is unspecified
  /// (Eigen's fast reductions): the counting pass checks every value against it.
  [[nodiscard]] static std::pair<double, double> column_range(const Scalar* column,
                                                              Eigen::Index stride, Eigen::Index n) {
    using Column = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    if (stride == 1) {  // contiguous: vectorised reductions
      const Eigen::Map<const Column> x(column, n);
      return {static_cast<double>(x.minCoeff()), static_cast<double>(x.maxCoeff())};
    }
    const Eigen::Map<const Column, 0, Eigen::InnerStride<>> x(column, n,
                                                              Eigen::InnerStride<>(stride));
    return {static_cast<double>(x.minCoeff()), static_cast<double>(x.maxCoeff())};
  }

  [[nodiscard]] static PyodHbos fit_view(const View& X, const PyodParams& params) {
    detail::validate(params);
    detail::require(X.rows >= 1 && X.cols >= 1, "cannot fit on an empty matrix (", X.rows, " x ",
                    X.cols, ")");
    detail::require(!params.auto_bins || X.rows > 3,
                    "n_bins = auto needs more than 3 samples (PyOD searches b = 1 .. sqrt(n) - 1), "
                    "got ",
                    X.rows);
    const Eigen::Index n = X.rows;
    PyodHbos model;
    model.params_ = params;
    model.features_.reserve(static_cast<std::size_t>(X.cols));
    // The bin each training value is scored with, from the counting pass, for the scoring pass
    // (16 bits: beyond 65536 bins the training values are scored like new data instead).
    const std::unique_ptr<std::uint16_t[]> scored_bins(
        new std::uint16_t[static_cast<std::size_t>(n * X.cols)]);  // not zero-filled
    bool bins_stored = true;
    detail::AutoBinsScratch<Scalar> scratch;
    for (Eigen::Index j = 0; j < X.cols; ++j) {
      model.features_.push_back(fit_column(X.data + j * X.col_stride, X.row_stride, n, j, params,
                                           GridRule::Always, scored_bins.get() + j * n, scratch));
      bins_stored = bins_stored && model.features_.back().bins() <= kMaxStoredBins;
    }
    if (!bins_stored) {
      model.scores_ = model.score_view(X);
    } else {
      model.scores_.resize(n);
      model.sum_rows(
          n,
          [&](Eigen::Index j, Eigen::Index first, Eigen::Index m, double* dst, auto add) {
            const double* log_terms = model.features_[static_cast<std::size_t>(j)].log_terms.data();
            const std::uint16_t* bin = scored_bins.get() + j * n + first;
            for (Eigen::Index r = 0; r < m; ++r) {
              if constexpr (decltype(add)::value) {
                dst[r] += log_terms[bin[r]];
              } else {
                dst[r] = log_terms[bin[r]];
              }
            }
          },
          model.scores_.data());
    }
    std::vector<Scalar> percentile_scratch;
    model.threshold_ =
        detail::pyod_threshold(model.scores_.data(), n, params.contamination, percentile_scratch);
    model.labels_ = model.label(model.scores_);
    return model;
  }

  static constexpr Eigen::Index kMaxStoredBins = 65536;

  /// Feature j fitted on its n values (`stride` apart), as fit_view fits column j: its range,
  /// checked finite (a non-finite value named as X(i, j): the columns before j passed, so it is
  /// also the first one of X), its bin count, numpy's histogram. Writes the bins the values are
  /// scored with (see fit_feature).
  [[nodiscard]] static Feature fit_column(const Scalar* column, Eigen::Index stride, Eigen::Index n,
                                          Eigen::Index j, const PyodParams& params, GridRule grid,
                                          std::uint16_t* scored_bins,
                                          detail::AutoBinsScratch<Scalar>& scratch) {
    const auto [lo, hi] = column_range(column, stride, n);
    // An infinity shows in min/max; a NaN is caught by the counting pass, but the auto search
    // must not see one, so it looks first.
    bool finite = std::isfinite(lo) && std::isfinite(hi);
    if (finite && params.auto_bins) {
      Eigen::Index nans = 0;
      for (Eigen::Index i = 0; i < n; ++i) nans += std::isnan(column[i * stride]) ? 1 : 0;
      finite = nans == 0;
    }
    if (!finite) {
      for (Eigen::Index i = 0; i < n; ++i) {
        detail::require(std::isfinite(column[i * stride]), "X(", i, ", ", j,
                        ") is not finite: ", column[i * stride]);
      }
    }
    // Checked before the auto search too, which would bucket an infinite range.
    require_finite_range(j, lo, hi);
    const Eigen::Index B = params.auto_bins
                               ? detail::pyod_optimal_bins(column, stride, n, lo, hi, scratch)
                               : params.n_bins;
    return fit_feature(column, stride, n, j, B, lo, hi, params, grid, scored_bins);
  }

  /// Feature j rebuilt from its stored edges and counts of n samples (see from_parts). The
  /// edges must be numpy's edges of their range, and the counts what fitting would count: a
  /// training value of bin k is at least edges[k], so the smallest Scalar >= edges[k] must be
  /// counted in bin k. The check takes O(B) time and memory, not O(n): a damaged file's
  /// n_samples must not make the loader allocate (one value per sample would).
  [[nodiscard]] static Feature feature_from_parts(const Eigen::VectorXd& e, const Counts& c,
                                                  Eigen::Index n, Eigen::Index j,
                                                  const PyodParams& params, GridRule grid) {
    const Eigen::Index B = c.size();
    detail::require(B >= 1 && e.size() == B + 1, "feature ", j, ": ", e.size(), " edges for ", B,
                    " bins");
    detail::require(params.auto_bins || B == params.n_bins, "feature ", j, ": ", B,
                    " bins but n_bins = ", params.n_bins);
    detail::require(e.allFinite(), "feature ", j, ": an edge is not finite");
    Eigen::Index filled = 0;
    for (Eigen::Index k = 0; k < B; ++k) {
      detail::require(c[k] >= 0 && c[k] <= n - filled, "feature ", j, ": counts[", k, "] = ", c[k],
                      " is negative or exceeds the ", n, " training samples");
      filled += c[k];
    }
    detail::require(filled == n, "feature ", j, ": the counts add up to ", filled, ", not to the ",
                    n, " training samples");
    Layout layout;
    Feature f = lay_out(detail::pyod_bin_edges(j, B, e[0], e[B]), layout, wants_grid(grid, n, B));
    detail::require(f.edges == e, "feature ", j,
                    ": the edges are not numpy's edges of their range [", e[0], ", ", e[B], "]");
    for (Eigen::Index k = 0; k < B; ++k) {
      if (c[k] == 0) continue;
      auto value = static_cast<Scalar>(e[k]);
      if (static_cast<double>(value) < e[k])
        value = std::nextafter(value, std::numeric_limits<Scalar>::infinity());
      const auto x = static_cast<double>(value);
      Eigen::Index counted = -1;
      Eigen::Index scored = -1;
      if (x >= f.lo && x <= f.hi) f.exact_bins(x, counted, scored);
      detail::require(counted == k, "feature ", j,
                      ": the counts do not match the edges (a value placed at edges[", k,
                      "] is not counted in bin ", k, ")");
    }
    f.counts = c;
    finish(f, layout, n, j, params);
    return f;
  }

  /// Writes (kAdd false) or adds (true) to dst[r] the log term of x[r * stride] under feature f,
  /// for r < m (see Feature for the look-up); returns how many of the values are not finite.
  template <bool kAdd>
  static Eigen::Index feature_terms(const Feature& f, const Scalar* x, Eigen::Index stride,
                                    Eigen::Index m, double* dst) {
    // Locals, so that the stores to dst cannot force reloads.
    const double lo = f.lo;
    const double hi = f.hi;
    const double scale = f.cell_scale;
    const Cell* grid = f.grid.data();
    return detail::with_stride(stride, [&](auto step) {
      Eigen::Index bad = 0;
      if (!f.has_grid()) {
        for (Eigen::Index r = 0; r < m; ++r) {
          const double v = static_cast<double>(x[r * step]);
          bad += std::isfinite(v) ? 0 : 1;
          const double t = f.term_exact(v);
          if constexpr (kAdd) {
            dst[r] += t;
          } else {
            dst[r] = t;
          }
        }
        return bad;
      }
      for (Eigen::Index r = 0; r < m; ++r) {
        const double v = static_cast<double>(x[r * step]);
        double t;
        if (v >= lo && v <= hi) {
          const Cell& cell = grid[static_cast<Eigen::Index>((v - lo) * scale)];
          t = v <= cell.edge ? cell.below : cell.above;
          if (std::isnan(t)) t = f.term_exact(v);
        } else {
          bad += std::isfinite(v) ? 0 : 1;
          t = f.term_exact(v);
        }
        if constexpr (kAdd) {
          dst[r] += t;
        } else {
          dst[r] = t;
        }
      }
      return bad;
    });
  }

  /// detail::pyod_histogram_range (numpy's range of feature j, refused if it overflows).
  static detail::OuterEdges require_finite_range(Eigen::Index j, double min_value,
                                                 double max_value) {
    return detail::pyod_histogram_range(j, min_value, max_value);
  }

  /// Per grid cell: the interior edge inside it (+inf if none) and the bin of a value below
  /// that edge (= #{interior edges in cells below}); first_bin = -1 marks a cell holding several.
  struct CellBins {
    double edge = std::numeric_limits<double>::infinity();
    Eigen::Index first_bin = 0;
  };
  /// What counting and the look-up grid need to know of a feature's edges, cell by cell (empty
  /// for a feature without a grid).
  struct Layout {
    std::vector<Eigen::Index> edges_in;  // interior edges per cell
    std::vector<CellBins> cell_bins;
  };

  /// numpy.histogram(column, B, density=True) plus the scoring tables. Writes the bin each value
  /// is scored with (which differs from the bin it is counted in for values on interior edges),
  /// truncated to 16 bits: meaningful only when B <= kMaxStoredBins.
  [[nodiscard]] static Feature fit_feature(const Scalar* column, Eigen::Index stride,
                                           Eigen::Index n, Eigen::Index j, Eigen::Index B,
                                           double min_value, double max_value,
                                           const PyodParams& params, GridRule grid,
                                           std::uint16_t* scored_bins) {
    Layout layout;
    Feature f =
        lay_out(detail::pyod_bin_edges(j, B, min_value, max_value), layout, wants_grid(grid, n, B));
    const std::vector<CellBins>& cell_bins = layout.cell_bins;

    // Count (bin c: e_c <= x < e_{c+1}, last closed) and record the scored bin (PyOD's look-up:
    // e_{s} < x <= e_{s+1}, the minimum in bin 0). Four count arrays, used in turn, break the
    // chains of increments of one counter.
    std::vector<Eigen::Index> counts(static_cast<std::size_t>(4 * B), 0);
    Eigen::Index non_finite = 0;
    auto count_one = [&](double x, Eigen::Index* count, std::uint16_t* scored_bin, auto on_grid) {
      // Outside [lo, hi] only with a NaN in the column: then Eigen's fast min/max may even have
      // skipped the true extremes. The column is rescanned for the NaN below.
      if (!(x >= f.lo && x <= f.hi)) {
        ++non_finite;
        return;
      }
      Eigen::Index counted = 0;
      Eigen::Index scored = 0;
      if constexpr (decltype(on_grid)::value) {
        const CellBins cell = cell_bins[static_cast<std::size_t>(f.cell(x))];
        counted = cell.first_bin + (cell.edge <= x ? 1 : 0);
        scored = cell.first_bin + (cell.edge < x ? 1 : 0);
        if (cell.first_bin < 0) f.exact_bins(x, counted, scored);
      } else {
        f.exact_bins(x, counted, scored);
      }
      ++count[counted];
      *scored_bin = static_cast<std::uint16_t>(scored);  // truncated when B > kMaxStoredBins
    };
    auto count_all = [&](auto on_grid) {
      detail::with_stride(stride, [&](auto step) {
        Eigen::Index* c0 = counts.data();
        Eigen::Index* c1 = c0 + B;
        Eigen::Index* c2 = c1 + B;
        Eigen::Index* c3 = c2 + B;
        auto at = [&](Eigen::Index i) { return static_cast<double>(column[i * step]); };
        Eigen::Index i = 0;
        for (; i + 4 <= n; i += 4) {
          count_one(at(i), c0, scored_bins + i, on_grid);
          count_one(at(i + 1), c1, scored_bins + i + 1, on_grid);
          count_one(at(i + 2), c2, scored_bins + i + 2, on_grid);
          count_one(at(i + 3), c3, scored_bins + i + 3, on_grid);
        }
        for (; i < n; ++i) count_one(at(i), c0, scored_bins + i, on_grid);
      });
    };
    if (f.has_grid()) {
      count_all(std::true_type{});
    } else {
      count_all(std::false_type{});
    }
    for (Eigen::Index i = 0; non_finite > 0 && i < n; ++i) {
      detail::require(std::isfinite(column[i * stride]), "X(", i, ", ", j,
                      ") is not finite: ", column[i * stride]);
    }
    f.counts.resize(B);
    for (Eigen::Index k = 0; k < B; ++k) {
      f.counts[k] = counts[static_cast<std::size_t>(k)] + counts[static_cast<std::size_t>(B + k)] +
                    counts[static_cast<std::size_t>(2 * B + k)] +
                    counts[static_cast<std::size_t>(3 * B + k)];
    }
    finish(f, layout, n, j, params);
    return f;
  }

  /// A feature's edges (detail::pyod_bin_edges), laid out on its look-up grid if `grid`.
  [[nodiscard]] static Feature lay_out(const Eigen::VectorXd& edges, Layout& layout, bool grid) {
    Feature f;
    f.edges = edges;  // B + 1 values, once per feature
    const Eigen::Index B = f.bins();
    f.lo = f.edges[0];
    f.hi = f.edges[B];
    f.norm = static_cast<double>(B) / (f.hi - f.lo);
    if (grid) {
      lay_out_grid(f, layout);
    } else {
      layout.edges_in.clear();
      layout.cell_bins.clear();
    }
    return f;
  }

  /// The cells of f's grid and which edges fall in each (f's edges set, see lay_out).
  static void lay_out_grid(Feature& f, Layout& layout) {
    const Eigen::Index B = f.bins();
    // The nominal cells, plus the cell of e_B itself, which rounding may put one past them.
    f.cell_scale = static_cast<double>(nominal_cells(B)) / (f.hi - f.lo);
    if (!std::isfinite(f.cell_scale)) f.cell_scale = 0.0;  // a range of denormals: one cell
    f.cells = f.cell(f.hi) + 1;
    std::vector<Eigen::Index>& edges_in = layout.edges_in;
    edges_in.assign(static_cast<std::size_t>(f.cells), 0);
    for (Eigen::Index k = 1; k < B; ++k) ++edges_in[static_cast<std::size_t>(f.cell(f.edges[k]))];
    layout.cell_bins.assign(static_cast<std::size_t>(f.cells), CellBins{});
    for (Eigen::Index c = 0, below = 0; c < f.cells; ++c) {
      const Eigen::Index inside = edges_in[static_cast<std::size_t>(c)];
      CellBins& cell = layout.cell_bins[static_cast<std::size_t>(c)];
      cell.first_bin = inside > 1 ? -1 : below;
      if (inside == 1) cell.edge = f.edges[below + 1];
      below += inside;
    }
  }

  /// Gives a finished feature without a grid the grid it would have been fitted with.
  static void add_grid(Feature& f) {
    if (f.has_grid()) return;
    Layout layout;
    lay_out_grid(f, layout);
    fill_grid(f, layout);
  }

  /// Densities, log terms and (if laid out) the look-up grid of a laid-out feature from its
  /// counts (f.counts, n samples in all): the same code for fit and for counts merged from shards.
  static void finish(Feature& f, const Layout& layout, Eigen::Index n, Eigen::Index j,
                     const PyodParams& params) {
    const Eigen::Index B = f.bins();
    f.densities.resize(B);
    f.log_terms.resize(B);
    const double n_double = static_cast<double>(n);
    for (Eigen::Index k = 0; k < B; ++k) {
      // numpy's n / db / n.sum(): each bin's own width first (widths differ by ULPs), then n.
      f.densities[k] = static_cast<double>(f.counts[k]) / (f.edges[k + 1] - f.edges[k]) / n_double;
      f.log_terms[k] = std::log2(f.densities[k] + params.alpha);
      // Bins of subnormal width: the density overflows and PyOD would score -inf; refuse.
      detail::require(std::isfinite(f.densities[k]), "feature ", j, ": bin ", k, " of width ",
                      f.edges[k + 1] - f.edges[k], " holds ", f.counts[k],
                      " samples, a density that overflows a double (PyOD would score -inf); "
                      "rescale the feature");
    }
    f.log_min = f.log_terms.minCoeff(&f.sparsest);
    f.tol_below = (f.edges[1] - f.edges[0]) * params.tol;
    f.tol_above = (f.edges[B] - f.edges[B - 1]) * params.tol;
    if (f.has_grid()) fill_grid(f, layout);
  }

  /// The look-up grid of a laid-out feature whose log terms are set.
  static void fill_grid(Feature& f, const Layout& layout) {
    const std::vector<Eigen::Index>& edges_in = layout.edges_in;
    const std::vector<CellBins>& cell_bins = layout.cell_bins;
    f.grid.resize(static_cast<std::size_t>(f.cells));
    constexpr double kInf = std::numeric_limits<double>::infinity();
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    for (Eigen::Index c = 0; c < f.cells; ++c) {
      const auto uc = static_cast<std::size_t>(c);
      const Eigen::Index bin = cell_bins[uc].first_bin;
      Cell& cell = f.grid[uc];
      if (bin < 0) {
        cell = {kInf, kNaN, kNaN};
      } else if (edges_in[uc] == 0) {
        cell = {kInf, f.log_terms[bin], f.log_terms[bin]};
      } else {
        cell = {cell_bins[uc].edge, f.log_terms[bin], f.log_terms[bin + 1]};
      }
    }
  }

  /// out[i] = -(numpy's pairwise sum over features of the row's log terms), a block of rows at a
  /// time. `terms(j, first, m, dst, add)` writes (add: std::false_type) or adds (std::true_type)
  /// the terms of feature j for rows first .. first + m - 1 to dst[0 .. m-1]. With fewer than 8
  /// features numpy's sum is the plain loop from 0, so terms are accumulated feature by feature;
  /// otherwise the block keeps every term and each row is summed in numpy's pairwise order.
  template <class Terms>
  void sum_rows(Eigen::Index n, const Terms& terms, Scalar* out) const {
    constexpr Eigen::Index kBlock = 256;
    const Eigen::Index d = n_features();
    std::vector<double> buffer(static_cast<std::size_t>(d < 8 ? kBlock : kBlock * d));
    double* block = buffer.data();
    for (Eigen::Index first = 0; first < n; first += kBlock) {
      const Eigen::Index m = std::min(kBlock, n - first);
      if (d < 8) {
        std::fill_n(block, m, 0.0);
        for (Eigen::Index j = 0; j < d; ++j) terms(j, first, m, block, std::true_type{});
        for (Eigen::Index r = 0; r < m; ++r) out[first + r] = static_cast<Scalar>(-block[r]);
      } else {
        for (Eigen::Index j = 0; j < d; ++j) {
          terms(j, first, m, block + j * kBlock, std::false_type{});
        }
        for (Eigen::Index r = 0; r < m; ++r) {
          out[first + r] = static_cast<Scalar>(-detail::numpy_pairwise_sum(block + r, d, kBlock));
        }
      }
    }
  }

  /// Scores every row of X (see Feature for the look-up).
  [[nodiscard]] Vector score_view(const View& X) const {
    detail::require(X.rows >= 1 && X.cols >= 1, "cannot score an empty matrix (", X.rows, " x ",
                    X.cols, ")");
    detail::require(X.cols == n_features(), "X has ", X.cols,
                    " columns but the model was fitted on ", n_features(), " features");
    Vector scores(X.rows);
    Eigen::Index non_finite = 0;
    sum_rows(
        X.rows,
        [&](Eigen::Index j, Eigen::Index first, Eigen::Index m, double* dst, auto add) {
          const Feature& f = features_[static_cast<std::size_t>(j)];
          const Scalar* x = X.data + first * X.row_stride + j * X.col_stride;
          non_finite += feature_terms<decltype(add)::value>(f, x, X.row_stride, m, dst);
        },
        scores.data());
    if (non_finite > 0) detail::require_finite_entry(X, "X");
    return scores;
  }

  [[nodiscard]] Labels label(const Vector& scores) const {
    Labels labels(scores.size());
    const Scalar threshold = threshold_;
    const Scalar* score = scores.data();
    int* label = labels.data();
    for (Eigen::Index i = 0; i < scores.size(); ++i) label[i] = score[i] > threshold ? 1 : 0;
    return labels;
  }

  std::vector<Feature> features_;
  PyodParams params_;
  Vector scores_;
  Scalar threshold_{};
  Labels labels_;
};

/// One feature of a PyOD-mode model on its own, for models too wide to hold whole (a PyodHbos
/// keeps a look-up grid of at least 1024 cells, 24 KB, per feature): what PyodModelFileWriter
/// fits and writes per feature and PyodModelFileReader gives back (hbos/pyod/model_file.hpp).
///
/// Its edges, counts and densities are those PyodHbos::fit gives feature j of the same data, and
/// log_terms() gives per value the term decision_function adds up (negated) for feature j, in
/// double, before numpy's sum over features (PyodFeatureScores adds them in that order).
///
/// Threading: immutable once built; const members may be called from many threads.
template <class Scalar>
class PyodFeatureModel {
 public:
  using Counts = typename PyodHbos<Scalar>::Counts;  ///< samples per bin

  /// Fits feature `j` on its `n` training values, `stride` apart, as PyodHbos::fit fits column j
  /// (errors name X(i, j)). Writes to `terms` the n training values' log terms (what
  /// decision_scores() adds up for feature j).
  /// \throws InvalidArgument for invalid params or data, as PyodHbos::fit.
  [[nodiscard]] static PyodFeatureModel fit(const Scalar* column, Eigen::Index stride,
                                            Eigen::Index n, Eigen::Index j,
                                            const PyodParams& params, double* terms) {
    detail::validate(params);
    detail::require(n >= 1, "cannot fit on an empty matrix (", n, " x 1)");
    detail::require(!params.auto_bins || n > 3,
                    "n_bins = auto needs more than 3 samples (PyOD searches b = 1 .. sqrt(n) - 1), "
                    "got ",
                    n);
    std::vector<std::uint16_t> scored_bins(static_cast<std::size_t>(n));
    detail::AutoBinsScratch<Scalar> scratch;
    PyodFeatureModel out;
    out.j_ = j;
    out.f_ = Model::fit_column(column, stride, n, j, params, Model::GridRule::IfPays,
                               scored_bins.data(), scratch);
    // As PyodHbos::fit: the scored bins of the counting pass, or beyond 65536 bins the values
    // scored like new data (the same terms, by the model's invariant).
    if (out.f_.bins() <= Model::kMaxStoredBins) {
      const double* log_terms = out.f_.log_terms.data();
      for (Eigen::Index i = 0; i < n; ++i)
        terms[i] = log_terms[scored_bins[static_cast<std::size_t>(i)]];
    } else {
      out.log_terms(column, stride, n, terms);
    }
    return out;
  }

  /// Feature `j` of a model fitted on `n` samples, from its stored B + 1 edges and B counts,
  /// checked and rebuilt as PyodHbos::from_parts does.
  /// \throws InvalidArgument naming the feature when the parts are inconsistent.
  [[nodiscard]] static PyodFeatureModel from_parts(const Eigen::VectorXd& edges,
                                                   const Counts& counts, Eigen::Index n,
                                                   Eigen::Index j, const PyodParams& params) {
    detail::validate(params);
    detail::require(n >= 1 && (!params.auto_bins || n > 3), "a model of ", n,
                    " training samples is not one PyOD fits");
    PyodFeatureModel out;
    out.j_ = j;
    out.f_ = Model::feature_from_parts(edges, counts, n, j, params, Model::GridRule::IfPays);
    return out;
  }

  /// The feature's index j in its model.
  [[nodiscard]] Eigen::Index index() const { return j_; }
  /// Bin count B.
  [[nodiscard]] Eigen::Index bins() const { return f_.bins(); }
  /// PyOD's `bin_edges_[:, j]` (B + 1 values).
  [[nodiscard]] const Eigen::VectorXd& bin_edges() const { return f_.edges; }
  /// numpy.histogram's B training counts.
  [[nodiscard]] const Counts& counts() const { return f_.counts; }
  /// PyOD's `hist_[:, j]` (B densities).
  [[nodiscard]] const Eigen::VectorXd& densities() const { return f_.densities; }

  /// Whether log_terms() looks values up on a grid (built when the feature was fitted on, or
  /// rebuilt from, at least grid_min_samples(bins()) samples) or finds each value's bin by
  /// search. Both give the same bits; the grid is faster per value but costs its cells to build.
  [[nodiscard]] bool has_lookup_grid() const { return f_.has_grid(); }
  /// The fewest training samples for which a feature of `bins` bins builds its look-up grid.
  [[nodiscard]] static Eigen::Index grid_min_samples(Eigen::Index bins) {
    return Model::nominal_cells(bins);
  }

  /// out[i] = the log term of x[i * stride] (i < m): log2(density + alpha) of the bin PyOD scores
  /// it with. \throws InvalidArgument naming X(i, j) for a value that is not finite.
  void log_terms(const Scalar* x, Eigen::Index stride, Eigen::Index m, double* out) const {
    if (Model::template feature_terms<false>(f_, x, stride, m, out) > 0) {
      for (Eigen::Index i = 0; i < m; ++i)
        detail::require(std::isfinite(x[i * stride]), "X(", i, ", ", j_,
                        ") is not finite: ", x[i * stride]);
    }
  }

 private:
  using Model = PyodHbos<Scalar>;
  friend class PyodHbos<Scalar>;  // from_features takes the feature
  PyodFeatureModel() = default;

  typename Model::Feature f_;
  Eigen::Index j_ = 0;
};

/// PyodHbos::decision_function built one feature at a time: each feature's log terms for every
/// row are added in feature order with numpy's pairwise summation (detail::PairwiseRowSums), so
/// scores() is bit for bit what the whole model gives, holding about 10 doubles per row and
/// nothing per feature.
template <class Scalar>
class PyodFeatureScores {
 public:
  using Vector = typename PyodHbos<Scalar>::Vector;

  /// Scores of `rows` rows (>= 1) under a model of `n_features` features.
  PyodFeatureScores(Eigen::Index n_features, Eigen::Index rows)
      : sums_(checked(n_features, rows), rows), terms_(static_cast<std::size_t>(rows)) {}

  [[nodiscard]] Eigen::Index rows() const { return sums_.rows(); }
  /// Features added so far.
  [[nodiscard]] Eigen::Index features_added() const { return sums_.added(); }

  /// Adds the next feature, scoring its column of rows() values, `stride` apart.
  /// \throws InvalidArgument naming X(i, j) for a value that is not finite.
  void add(const PyodFeatureModel<Scalar>& feature, const Scalar* column, Eigen::Index stride) {
    detail::require(feature.index() == features_added(), "feature ", feature.index(),
                    " added where feature ", features_added(), " was due");
    feature.log_terms(column, stride, rows(), terms_.data());
    sums_.add(terms_.data());
  }

  /// Adds the next feature's log terms, rows() values (PyodFeatureModel::fit's training terms).
  void add_terms(const double* terms) { sums_.add(terms); }

  /// The scores, once every feature has been added: decision_function's bits.
  /// \throws InvalidArgument when features are missing.
  [[nodiscard]] Vector scores() const {
    Vector out(rows());
    for (Eigen::Index i = 0; i < rows(); ++i) out[i] = static_cast<Scalar>(-sums_.sum(i));
    return out;
  }

 private:
  static Eigen::Index checked(Eigen::Index n_features, Eigen::Index rows) {
    detail::require(n_features >= 1 && rows >= 1, "cannot score ", rows, " rows of ", n_features,
                    " features");
    return n_features;
  }

  detail::PairwiseRowSums sums_;
  std::vector<double> terms_;
};

using PyodHbosd = PyodHbos<double>;  ///< the double model (PyOD parity is defined for double)
using PyodHbosf = PyodHbos<float>;   ///< the float model: same histograms, float inputs and scores

}  // namespace hbos
