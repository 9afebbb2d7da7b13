#pragma once
/// \file
/// Fitting on shards: histograms are sums, so a model can be fitted on data split into row
/// shards (files, chunks of a Dask array, machines) and come out **bit-identical** to the model
/// fitted on all rows at once.
///
/// Equal-width bins span the global [min, max] and fixed-width bins are snapped to the grid
/// around it, so the edges need the whole data before any shard can be counted. The plan has
/// two passes over the shards, each reducing small summaries that merge in any order:
///
///  1. `summarize_range(shard)` per shard (per feature min and max, and the row count; checks
///     finiteness), reduced with `merge` (min, max, +).
///  2. `ShardedFit plan(range, params)` fixes every feature's edges from the global summary —
///     exactly the edges `Hbos::fit` places on the whole data, through the same code — then
///     `plan.count(shard)` per shard (integer counts per bin), reduced with `merge` (+).
///  3. `plan.model(total)` derives the contributions from the total counts (the code `fit` uses)
///     and returns the Hbos: same bits as `Hbos::fit(all rows, params)`.
///
/// Mergeable specs: EqualWidth or FixedWidth binning, periodic or not, any shifts and tail, with
/// the bin-count rules Fixed, Sqrt and Sturges (which need only n). Rules that need more of the
/// data than its range and size (Scott's variance, Freedman–Diaconis' quartiles,
/// Birgé–Rozenblac's likelihood search) and EqualFrequency bins (quantiles) are refused with an
/// InvalidArgument naming the feature: `mergeable(params, d)` tells beforehand.
///
/// `fit_sharded(shards, params)` runs the whole plan over a list of in-memory shards.
///
/// The PyOD mode (`PyodHbos`) has the same plan in hbos/pyod/merge.hpp, with these summaries:
/// mergeable for an integer n_bins (PyOD's numpy.histogram needs only the range and n, then the
/// counts); n_bins = auto is refused (PyOD's Birgé–Rozenblac search histograms the whole data
/// for every candidate bin count).
///
/// Threading: summaries are plain values; a ShardedFit is immutable after construction, and
/// `count` may run on many shards in parallel.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/model.hpp"

namespace hbos {

/// Pass 1's summary of some rows: per feature their min and max, and how many rows.
template <class Scalar>
struct RangeSummary {
  std::vector<Scalar> lo;  ///< [feature units] per feature: the smallest value
  std::vector<Scalar> hi;  ///< [feature units] per feature: the largest value
  Eigen::Index rows = 0;   ///< rows summarised
};

/// Pass 2's summary of some rows: per feature the samples counted in each bin of the plan.
struct CountSummary {
  std::vector<std::vector<Eigen::Index>> counts;  ///< [feature][bin]
  Eigen::Index rows = 0;                          ///< rows counted
};

namespace detail {

/// Pass 3's check that the merged counts are those of the rows and features a plan was built
/// for. \throws InvalidArgument naming the mismatch.
inline void require_counts_cover(const CountSummary& total, Eigen::Index rows,
                                 Eigen::Index features) {
  require(total.rows == rows, "the counts cover ", total.rows, " rows but the range summary ", rows,
          " (a shard missing or counted twice?)");
  require(static_cast<Eigen::Index>(total.counts.size()) == features, "the counts have ",
          total.counts.size(), " features, the plan ", features);
}

/// Why feature j's spec cannot be fitted by shards, or empty when it can.
inline std::string not_mergeable_reason(const FeatureSpec& spec) {
  const Binning& b = spec.binning;
  if (b.method == BinningMethod::EqualFrequency)
    return "EqualFrequency bins need the quantiles of the whole data";
  if (b.method == BinningMethod::FixedWidth) return {};
  switch (b.rule) {
    case BinCountRule::Fixed:
    case BinCountRule::Sqrt:
    case BinCountRule::Sturges:
      return {};
    case BinCountRule::Scott:
      return "the Scott rule needs the variance of the whole data in its summation order";
    case BinCountRule::FreedmanDiaconis:
      return "the Freedman-Diaconis rule needs the quartiles of the whole data";
    case BinCountRule::BirgeRozenblac:
      return "the Birge-Rozenblac rule searches bin counts on the whole data";
  }
  return "unknown bin-count rule";
}

}  // namespace detail

/// Whether every feature's spec under `params` can be fitted by shards (see the file comment).
[[nodiscard]] inline bool mergeable(const HbosParams& params, Eigen::Index n_features) {
  for (Eigen::Index j = 0; j < n_features; ++j)
    if (!detail::not_mergeable_reason(params.spec(j)).empty()) return false;
  return true;
}

/// Pass 1 on one shard (rows = samples; any Eigen dense expression).
/// \throws InvalidArgument on an empty shard or a non-finite value (naming X(i, j) of the shard).
template <class Derived>
[[nodiscard]] RangeSummary<typename Derived::Scalar> summarize_range(
    const Eigen::DenseBase<Derived>& shard) {
  using Scalar = typename Derived::Scalar;
  detail::require(shard.rows() > 0 && shard.cols() > 0, "cannot summarise an empty shard (",
                  shard.rows(), " x ", shard.cols(), ")");
  RangeSummary<Scalar> s;
  s.rows = shard.rows();
  std::vector<Scalar> storage;
  for (Eigen::Index j = 0; j < shard.cols(); ++j) {
    const auto [lo, hi] =
        detail::finite_min_max(detail::view_of(shard.derived().col(j), storage), j);
    s.lo.push_back(lo);
    s.hi.push_back(hi);
  }
  return s;
}

/// Pass 1's reduction: the summary of both sets of rows.
template <class Scalar>
[[nodiscard]] RangeSummary<Scalar> merge(const RangeSummary<Scalar>& a,
                                         const RangeSummary<Scalar>& b) {
  if (a.rows == 0) return b;
  if (b.rows == 0) return a;
  detail::require(a.lo.size() == b.lo.size(), "cannot merge range summaries of ", a.lo.size(),
                  " and ", b.lo.size(), " features");
  RangeSummary<Scalar> s = a;
  for (std::size_t j = 0; j < a.lo.size(); ++j) {
    s.lo[j] = std::min(a.lo[j], b.lo[j]);
    s.hi[j] = std::max(a.hi[j], b.hi[j]);
  }
  s.rows = a.rows + b.rows;
  return s;
}

/// Pass 2's reduction: the counts of both sets of rows.
[[nodiscard]] inline CountSummary merge(const CountSummary& a, const CountSummary& b) {
  if (a.rows == 0) return b;
  if (b.rows == 0) return a;
  detail::require(a.counts.size() == b.counts.size(), "cannot merge count summaries of ",
                  a.counts.size(), " and ", b.counts.size(), " features");
  CountSummary s = a;
  for (std::size_t j = 0; j < a.counts.size(); ++j) {
    detail::require(a.counts[j].size() == b.counts[j].size(), "feature ", j,
                    ": cannot merge counts of ", a.counts[j].size(), " and ", b.counts[j].size(),
                    " bins (counted by different plans?)");
    for (std::size_t k = 0; k < a.counts[j].size(); ++k) s.counts[j][k] += b.counts[j][k];
  }
  s.rows = a.rows + b.rows;
  return s;
}

/// Passes 2 and 3: the bins fixed from the global range, counting shards, the final model.
template <class Scalar>
class ShardedFit {
 public:
  /// Places every feature's edges as `Hbos::fit` would on all the rows `range` summarises.
  /// \throws InvalidArgument for invalid or non-mergeable params (naming the feature and why).
  ShardedFit(const RangeSummary<Scalar>& range, const HbosParams& params = {})
      : params_(params), rows_(range.rows) {
    const auto d = static_cast<Eigen::Index>(range.lo.size());
    detail::require(range.rows > 0 && d > 0, "the range summary is empty (", range.rows, " rows, ",
                    d, " features)");
    detail::require(range.hi.size() == range.lo.size(), "the range summary has ", range.lo.size(),
                    " minima but ", range.hi.size(), " maxima");
    detail::validate(params, d);
    for (Eigen::Index j = 0; j < d; ++j) {
      const FeatureSpec& spec = params.spec(j);
      const std::string why = detail::not_mergeable_reason(spec);
      detail::require(why.empty(), "feature ", j, " cannot be fitted by shards: ", why);
      const auto uj = static_cast<std::size_t>(j);
      detail::require(range.lo[uj] <= range.hi[uj] && std::isfinite(range.lo[uj]) &&
                          std::isfinite(range.hi[uj]),
                      "feature ", j, ": the summarised range [", range.lo[uj], ", ", range.hi[uj],
                      "] is not a finite interval");
      // The bin count rules that need n see the global n; the edges are then placed, by the
      // code fit uses, for a column holding just the global min and max (which is all that
      // equal- and fixed-width placement reads of the data).
      FeatureSpec fixed = spec;
      if (spec.binning.method == BinningMethod::EqualWidth &&
          spec.binning.rule != BinCountRule::Fixed) {
        const std::array<Scalar, 1> dummy{range.lo[uj]};
        const detail::ColumnView<Scalar> sized{dummy.data(), range.rows, 0};
        std::vector<Scalar> scratch;
        detail::RuleScratch rule_scratch;
        fixed.binning.bins = detail::rule_bins(sized, spec.binning, range.lo[uj], range.hi[uj],
                                               scratch, rule_scratch);
        fixed.binning.rule = BinCountRule::Fixed;
      }
      const std::array<Scalar, 2> extremes{range.lo[uj], range.hi[uj]};
      std::vector<Scalar> scratch;
      detail::RuleScratch rule_scratch;
      detail::EdgeLayout<Scalar> layout;
      detail::place_uniform_edges(detail::ColumnView<Scalar>{extremes.data(), 2, 1}, fixed,
                                  spec.binning.shifts, scratch, rule_scratch, j, layout);
      HistogramParts<Scalar> parts;
      parts.edges = layout.edges;
      parts.counts.assign(layout.edges.size() - 1, 0);
      parts.counts[0] = 1;  // a placeholder sample: this histogram only serves bin_of
      parts.lo = layout.lo;
      parts.hi = layout.hi;
      parts.inv_width = layout.inv_width;
      parts.period = spec.periodic ? layout.period : Scalar(0);
      parts.scale = layout.scale;
      parts.base = layout.base;
      parts.fine = layout.fine;
      parts.shifts = spec.binning.shifts;
      parts.tail = spec.tail;
      parts.periodic = spec.periodic;
      parts.uniform = true;
      binners_.push_back(
          Histogram<Scalar>::from_parts(parts, params.scoring, detail::concat("feature ", j)));
    }
  }

  [[nodiscard]] Eigen::Index n_features() const {
    return static_cast<Eigen::Index>(binners_.size());
  }

  /// Pass 2 on one shard: its counts in the fixed bins. Every value must lie in the range the
  /// plan was built from (true for the rows pass 1 summarised).
  /// \throws InvalidArgument on a wrong column count, a non-finite or out-of-range value.
  template <class Derived>
  [[nodiscard]] CountSummary count(const Eigen::DenseBase<Derived>& shard) const {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "the shard's scalar type must match the plan's");
    detail::require(shard.cols() == n_features(), "the plan has ", n_features(),
                    " features but the shard has ", shard.cols(), " columns");
    CountSummary s;
    s.rows = shard.rows();
    std::vector<Scalar> storage;
    for (Eigen::Index j = 0; j < shard.cols(); ++j) {
      const Histogram<Scalar>& h = binners_[static_cast<std::size_t>(j)];
      std::vector<Eigen::Index> counts(static_cast<std::size_t>(h.bins()), 0);
      const detail::ColumnView<Scalar> x = detail::view_of(shard.derived().col(j), storage);
      for (Eigen::Index i = 0; i < x.size; ++i) {
        const Scalar v = x[i];
        detail::require(std::isfinite(v), "X(", i, ", ", j, ") is not finite (", v, ")");
        detail::require(h.periodic() || (v >= h.lower() && v <= h.upper()), "X(", i, ", ", j,
                        ") = ", v, " lies outside the range [", h.lower(), ", ", h.upper(),
                        "] the plan was built from");
        ++counts[static_cast<std::size_t>(h.bin_of(v))];
      }
      s.counts.push_back(std::move(counts));
    }
    return s;
  }

  /// Pass 3: the model of all rows from the total counts (every shard's counts merged).
  /// \throws InvalidArgument when the counts do not cover the rows the plan was built from.
  [[nodiscard]] Hbos<Scalar> model(const CountSummary& total) const {
    detail::require_counts_cover(total, rows_, n_features());
    std::vector<Histogram<Scalar>> histograms;
    for (Eigen::Index j = 0; j < n_features(); ++j) {
      HistogramParts<Scalar> parts = binners_[static_cast<std::size_t>(j)].parts();
      parts.counts = total.counts[static_cast<std::size_t>(j)];
      detail::require(parts.counts.size() == parts.edges.size() - 1, "feature ", j, ": ",
                      parts.counts.size(), " counts for a plan of ", parts.edges.size() - 1,
                      " bins");
      histograms.push_back(Histogram<Scalar>::from_parts(std::move(parts), params_.scoring,
                                                         detail::concat("feature ", j)));
    }
    return Hbos<Scalar>::from_histograms(std::move(histograms), params_, rows_);
  }

  [[nodiscard]] const HbosParams& params() const { return params_; }

 private:
  std::vector<Histogram<Scalar>> binners_;  // the plan's edges, with placeholder counts
  HbosParams params_;
  Eigen::Index rows_ = 0;
};

/// The whole plan over in-memory shards (any Eigen dense objects of one scalar type, the same
/// column count): bit-identical to `Hbos::fit` on their rows stacked in any order.
template <class Shard>
[[nodiscard]] Hbos<typename Shard::Scalar> fit_sharded(const std::vector<Shard>& shards,
                                                       const HbosParams& params = {}) {
  using Scalar = typename Shard::Scalar;
  detail::require(!shards.empty(), "fit_sharded needs at least one shard");
  RangeSummary<Scalar> range;
  for (const Shard& s : shards) range = merge(range, summarize_range(s));
  const ShardedFit<Scalar> plan(range, params);
  CountSummary total;
  for (const Shard& s : shards) total = merge(total, plan.count(s));
  return plan.model(total);
}

}  // namespace hbos
