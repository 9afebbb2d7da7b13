#pragma once
/// \file
/// Fitting the PyOD mode on shards: hbos/merge.hpp's plan for `PyodHbos`. A model fitted on
/// data split into row shards (files, chunks of a Dask array, machines) comes out
/// **bit-identical** to `PyodHbos::fit` on all rows: the same edges, counts and densities, so
/// decision_function of new data gives the same bits, and the same training scores, threshold
/// and labels.
///
/// For an integer n_bins PyOD's fit reads only each feature's range and size (numpy.histogram
/// over [min, max]) and then the counts, so the plan is hbos/merge.hpp's, with the same
/// summaries and reductions:
///
///  1. `summarize_range(shard)` per shard (hbos/merge.hpp: per feature min and max, the row
///     count; checks finiteness), reduced with `merge` (min, max, +).
///  2. `PyodShardedFit plan(range, params)` fixes every feature's numpy edges from the global
///     range — through `detail::pyod_bin_edges`, the code `PyodHbos::fit` places its edges with
///     (a constant feature widened by 0.5 each side, as numpy does) — then `plan.count(shard)`
///     per shard (numpy's integer counts, e_k <= x < e_{k+1}, the last bin closed), reduced with
///     `merge` (+).
///  3. `plan.histograms(total)` derives the densities and look-up tables from the total counts
///     (the code `fit` uses): a `PyodHistograms`, which scores new data as the whole fit does.
///  4. Unlike the default model, a PyodHbos carries PyOD's training outputs, which need every
///     row's score: a scoring pass `histograms.decision_function(shard)` per shard, then
///     `histograms.model(training_scores)` (scores in row order) sets decision_scores, threshold
///     (numpy's percentile, the code `fit` uses) and labels.
///
/// `fit_sharded(shards, pyod_params)` runs the whole plan over a list of in-memory shards.
///
/// Refused: `n_bins = auto` (`mergeable(params)` is false). PyOD's Birgé–Rozenblac search
/// histograms the whole column once for every candidate b = 1 .. floor(sqrt(n)) - 1 and takes
/// the first argmax of a likelihood of those counts, so the bin count needs the counts of all
/// rows under about sqrt(n) different sets of edges, not a summary of the range.
///
/// Threading: summaries are plain values; a PyodShardedFit and a PyodHistograms are immutable,
/// and `count` and `decision_function` may run on many shards in parallel.

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hbos/error.hpp"
#include "hbos/merge.hpp"
#include "hbos/pyod/detail/numpy_replica.hpp"
#include "hbos/pyod/model.hpp"

namespace hbos {

namespace detail {

inline constexpr const char* kPyodAutoNotMergeable =
    "n_bins = auto cannot be fitted by shards: PyOD's Birge-Rozenblac search histograms the "
    "whole data once for every candidate bin count b = 1 .. sqrt(n) - 1, which a range summary "
    "cannot give; pass an integer n_bins";

}  // namespace detail

/// Whether `params` can be fitted by shards: any integer n_bins, not `auto` (see the file
/// comment).
[[nodiscard]] inline bool mergeable(const PyodParams& params) { return !params.auto_bins; }

/// Pass 3's result: the histograms of all rows, which score new data bit for bit as
/// `PyodHbos::fit` on all rows does; `model(training_scores)` completes the model.
template <class Scalar>
class PyodHistograms {
 public:
  using Vector = typename PyodHbos<Scalar>::Vector;  ///< one score per sample
  using Counts = typename PyodHbos<Scalar>::Counts;  ///< samples per bin

  /// PyOD's `decision_function`: the score of each row of X (higher = more anomalous).
  template <class Derived>
  [[nodiscard]] Vector decision_function(const Eigen::DenseBase<Derived>& X) const {
    return histograms_.decision_function(X);
  }
  /// decision_function on a raw row-major buffer of rows x cols values.
  [[nodiscard]] Vector decision_function(const Scalar* data, Eigen::Index rows,
                                         Eigen::Index cols) const {
    return histograms_.decision_function(data, rows, cols);
  }

  /// Pass 4: the model, with `training_scores` (decision_function of every training row, in the
  /// order its decision_scores() should have) as its decision_scores, the threshold numpy's
  /// percentile of them and labels = scores > threshold, as `PyodHbos::fit` sets them.
  /// \throws InvalidArgument unless there is one finite score per row the histograms count.
  [[nodiscard]] PyodHbos<Scalar> model(Vector training_scores) const {
    detail::require(training_scores.size() == rows_, "the histograms count ", rows_, " rows but ",
                    training_scores.size(), " training scores were given");
    for (Eigen::Index i = 0; i < training_scores.size(); ++i)
      detail::require(std::isfinite(training_scores[i]), "training score ", i, " is not finite (",
                      training_scores[i], ")");
    PyodHbos<Scalar> out = histograms_;
    out.set_training_scores(std::move(training_scores));
    return out;
  }

  /// The rows counted (PyOD's n).
  [[nodiscard]] Eigen::Index rows() const { return rows_; }
  [[nodiscard]] Eigen::Index n_features() const { return histograms_.n_features(); }
  /// Bin count of feature j (n_bins).
  [[nodiscard]] Eigen::Index bins(Eigen::Index j) const { return histograms_.bins(j); }
  /// PyOD's `bin_edges_[:, j]`.
  [[nodiscard]] const Eigen::VectorXd& bin_edges(Eigen::Index j) const {
    return histograms_.bin_edges(j);
  }
  /// PyOD's `hist_[:, j]`.
  [[nodiscard]] const Eigen::VectorXd& densities(Eigen::Index j) const {
    return histograms_.densities(j);
  }
  /// numpy.histogram's counts of feature j over all rows.
  [[nodiscard]] const Counts& counts(Eigen::Index j) const { return histograms_.counts(j); }
  [[nodiscard]] const PyodParams& params() const { return histograms_.params(); }

 private:
  template <class>
  friend class PyodShardedFit;

  PyodHistograms(const std::vector<Eigen::VectorXd>& edges,
                 const std::vector<std::vector<Eigen::Index>>& counts, Eigen::Index rows,
                 const PyodParams& params)
      : histograms_(PyodHbos<Scalar>::from_counts(edges, counts, rows, params)), rows_(rows) {}

  PyodHbos<Scalar> histograms_;  // no training outputs
  Eigen::Index rows_ = 0;
};

/// Passes 2 and 3 for the PyOD mode: numpy's edges fixed from the global range, counting shards,
/// the histograms of all rows.
template <class Scalar>
class PyodShardedFit {
  static_assert(std::is_same_v<Scalar, float> || std::is_same_v<Scalar, double>,
                "PyodShardedFit is defined for float and double");

 public:
  /// Places every feature's edges as `PyodHbos::fit` would on all the rows `range` summarises.
  /// \throws InvalidArgument for invalid params (PyOD's checks), n_bins = auto (naming why), or
  /// a range that is empty, not finite or overflows a double (naming the feature).
  PyodShardedFit(const RangeSummary<Scalar>& range, const PyodParams& params = {})
      : params_(params), rows_(range.rows) {
    detail::validate(params);
    detail::require(mergeable(params), detail::kPyodAutoNotMergeable);
    const auto d = static_cast<Eigen::Index>(range.lo.size());
    detail::require(range.rows > 0 && d > 0, "the range summary is empty (", range.rows, " rows, ",
                    d, " features)");
    detail::require(range.hi.size() == range.lo.size(), "the range summary has ", range.lo.size(),
                    " minima but ", range.hi.size(), " maxima");
    for (Eigen::Index j = 0; j < d; ++j) {
      const auto uj = static_cast<std::size_t>(j);
      const auto lo = static_cast<double>(range.lo[uj]);
      const auto hi = static_cast<double>(range.hi[uj]);
      detail::require(lo <= hi && std::isfinite(lo) && std::isfinite(hi), "feature ", j,
                      ": the summarised range [", lo, ", ", hi, "] is not a finite interval");
      lo_.push_back(lo);
      hi_.push_back(hi);
      edges_.push_back(detail::pyod_bin_edges(j, params.n_bins, lo, hi));
    }
  }

  [[nodiscard]] Eigen::Index n_features() const { return static_cast<Eigen::Index>(edges_.size()); }
  /// The rows the range summary covers (PyOD's n).
  [[nodiscard]] Eigen::Index rows() const { return rows_; }
  /// The n_bins + 1 edges of feature j: PyOD's `bin_edges_[:, j]` on all rows.
  [[nodiscard]] const Eigen::VectorXd& bin_edges(Eigen::Index j) const {
    detail::require(j >= 0 && j < n_features(), "feature index must lie in [0, ", n_features(),
                    "), got ", j);
    return edges_[static_cast<std::size_t>(j)];
  }
  [[nodiscard]] const PyodParams& params() const { return params_; }

  /// Pass 2 on one shard: numpy.histogram's counts in the fixed edges (e_k <= x < e_{k+1}, the
  /// last bin closed). Every value must lie in the range the plan was built from (true for the
  /// rows pass 1 summarised).
  /// \throws InvalidArgument on a wrong column count, a non-finite or out-of-range value.
  template <class Derived>
  [[nodiscard]] CountSummary count(const Eigen::DenseBase<Derived>& shard) const {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "the shard's scalar type must match the plan's");
    detail::require(shard.cols() == n_features(), "the plan has ", n_features(),
                    " features but the shard has ", shard.cols(), " columns");
    return detail::with_strided_view(shard, [&](const detail::StridedView<Scalar>& x) {
      CountSummary s;
      s.rows = x.rows;
      for (Eigen::Index j = 0; j < x.cols; ++j) {
        const auto uj = static_cast<std::size_t>(j);
        const Eigen::VectorXd& e = edges_[uj];
        const Eigen::Index B = e.size() - 1;
        const double norm = static_cast<double>(B) / (e[B] - e[0]);
        std::vector<Eigen::Index> counts(static_cast<std::size_t>(B), 0);
        for (Eigen::Index i = 0; i < x.rows; ++i) {
          const auto v = static_cast<double>(x(i, j));
          detail::require(std::isfinite(v), "X(", i, ", ", j, ") is not finite (", v, ")");
          detail::require(v >= lo_[uj] && v <= hi_[uj], "X(", i, ", ", j, ") = ", v,
                          " lies outside the range [", lo_[uj], ", ", hi_[uj],
                          "] the plan was built from");
          const Eigen::Index k =
              detail::count_bin(v, e.data(), B, detail::bin_guess(v, e[0], norm, B - 1));
          ++counts[static_cast<std::size_t>(k)];
        }
        s.counts.push_back(std::move(counts));
      }
      return s;
    });
  }

  /// Pass 3: the histograms of all rows from the total counts (every shard's counts merged).
  /// \throws InvalidArgument when the counts do not cover the rows the plan was built from.
  [[nodiscard]] PyodHistograms<Scalar> histograms(const CountSummary& total) const {
    detail::require_counts_cover(total, rows_, n_features());
    for (Eigen::Index j = 0; j < n_features(); ++j) {
      const auto& c = total.counts[static_cast<std::size_t>(j)];
      const Eigen::Index B = edges_[static_cast<std::size_t>(j)].size() - 1;
      detail::require(static_cast<Eigen::Index>(c.size()) == B, "feature ", j, ": ", c.size(),
                      " counts for a plan of ", B, " bins");
      Eigen::Index sum = 0;
      for (const Eigen::Index k : c) {
        detail::require(k >= 0, "feature ", j, ": a negative count (", k, ")");
        sum += k;
      }
      detail::require(sum == rows_, "feature ", j, ": the counts add up to ", sum, ", not to the ",
                      rows_, " rows");
    }
    return PyodHistograms<Scalar>(edges_, total.counts, rows_, params_);
  }

 private:
  std::vector<Eigen::VectorXd> edges_;  // numpy's edges per feature
  std::vector<double> lo_;              // the summarised range per feature
  std::vector<double> hi_;
  PyodParams params_;
  Eigen::Index rows_ = 0;
};

/// The whole plan over in-memory shards (any Eigen dense objects of one scalar type, the same
/// column count): bit-identical to `PyodHbos::fit` on their rows stacked in shard order.
template <class Shard>
[[nodiscard]] PyodHbos<typename Shard::Scalar> fit_sharded(const std::vector<Shard>& shards,
                                                           const PyodParams& params) {
  using Scalar = typename Shard::Scalar;
  detail::require(!shards.empty(), "fit_sharded needs at least one shard");
  RangeSummary<Scalar> range;
  for (const Shard& s : shards) range = merge(range, summarize_range(s));
  const PyodShardedFit<Scalar> plan(range, params);
  CountSummary total;
  for (const Shard& s : shards) total = merge(total, plan.count(s));
  const PyodHistograms<Scalar> histograms = plan.histograms(total);
  typename PyodHistograms<Scalar>::Vector scores(total.rows);
  Eigen::Index first = 0;
  for (const Shard& s : shards) {
    scores.segment(first, s.rows()) = histograms.decision_function(s);
    first += s.rows();
  }
  return histograms.model(std::move(scores));
}

}  // namespace hbos
