#pragma once
/// \file
/// One feature's histogram: its bins, counts, and the contribution each bin adds to a score.
///
/// Maths. With bin heights h_k = count_k / width_k (a density up to a constant) and
/// h_max = max_k h_k, a value x falling in bin k contributes
///
///     c(x) = log(h_max / h_k)                                   (Goldstein & Dengel 2012, eq. 1)
///
/// which is 0 in the modal bin and grows as the bin gets sparser. Heights are normalised by the
/// feature's own maximum, so every feature weighs the same and shifting or rescaling a feature
/// changes nothing (PyOD's `log2(density + alpha)` lacks both properties; see pyod.hpp).
///
/// Rules that make every score finite and documented:
/// - **Empty bins** score as if they held `empty_bin_count` samples (default 0.5, less than any
///   observed bin): c = log(h_max * width_k / empty_bin_count).
/// - **Outside the fitted range** at scoring time: within `range_tolerance` bin widths of the
///   edge a value scores as the edge bin; beyond it, it gets the feature's **cap**,
///   log(h_max * max_k width_k / empty_bin_count), the largest contribution any value can get.
/// - **Constant feature** (min == max under EqualWidth/EqualFrequency): one bin of width 0; its
///   value contributes 0, any other value the cap log(n / empty_bin_count).
/// - **Tails** (binning.hpp, Tail): Upper zeroes contributions at or below the modal bin and
///   makes them non-decreasing above it; values below the range contribute 0. Lower mirrors it.
/// - **Periodic** features wrap modulo the period; the first and last bins are neighbours and a
///   value never falls out of range.
///
/// Interval convention: bin k holds [e_k, e_{k+1}), the last bin is closed. Counting and lookup
/// call the same `bin_of`, so a training value is always scored from the bin it was counted in.
///
/// Threading: a fitted Histogram is immutable through its const interface; concurrent const
/// calls are safe. `refit` is the (non-const) reuse path of Workspace.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/error.hpp"

namespace hbos {

/// Scoring rules shared by every feature of a model.
struct ScoringOptions {
  double empty_bin_count = 0.5;  ///< an empty bin scores as if it held this many samples, in (0, 1]
  double range_tolerance =
      0.5;  ///< [bins] beyond the fitted range, within this many widths: edge bin
};

namespace detail {
inline void validate(const ScoringOptions& o) {
  require(o.empty_bin_count > 0.0 && o.empty_bin_count <= 1.0,
          "empty_bin_count must lie in (0, 1], got ", o.empty_bin_count);
  require(o.range_tolerance >= 0.0 && std::isfinite(o.range_tolerance),
          "range_tolerance must be finite and >= 0, got ", o.range_tolerance);
}
}  // namespace detail

/// A fitted one-feature histogram. See the file comment for the maths and the rules.
template <class Scalar>
class Histogram {
  static_assert(std::is_floating_point_v<Scalar>, "Histogram needs float or double");

 public:
  using Index = Eigen::Index;

  /// Number of bins, >= 1 once fitted.
  [[nodiscard]] Index bins() const { return static_cast<Index>(counts_.size()); }
  /// bins() + 1 edges, ascending; bin k is [edges[k], edges[k+1]).
  [[nodiscard]] const std::vector<Scalar>& edges() const { return edges_; }
  /// Training samples counted in each bin.
  [[nodiscard]] const std::vector<Index>& counts() const { return counts_; }
  /// The contribution of a value in each bin, after the tail rule (>= 0, 0 in the modal bin).
  [[nodiscard]] const std::vector<Scalar>& bin_contributions() const { return contribution_; }
  /// The largest contribution any value can get (out of range, or an empty bin).
  [[nodiscard]] Scalar cap() const { return cap_; }
  [[nodiscard]] bool periodic() const { return periodic_; }
  [[nodiscard]] Tail tail() const { return tail_; }
  /// The fitted range [lower(), upper()] (the period for a periodic feature).
  [[nodiscard]] Scalar lower() const { return lo_; }
  [[nodiscard]] Scalar upper() const { return hi_; }
  /// Index of the modal (densest) bin; the first one on ties.
  [[nodiscard]] Index mode() const { return mode_; }

  /// The bin a value falls in. Periodic features wrap; other values are clamped into
  /// [lower(), upper()] first, so out-of-range values map to the edge bins.
  [[nodiscard]] Index bin_of(Scalar x) const {
    if (periodic_) return uniform_bin(wrap(x));
    return in_range_bin(std::clamp(x, lo_, hi_));
  }

  /// The contribution of value `x` to a sample's score (see the file comment). `x` must be finite.
  [[nodiscard]] Scalar contribution(Scalar x) const {
    if (periodic_) return contribution_[static_cast<std::size_t>(uniform_bin(wrap(x)))];
    if (x < lo_) return x >= tolerance_lo_ ? contribution_.front() : below_;
    if (x > hi_) return x <= tolerance_hi_ ? contribution_.back() : above_;
    return contribution_[static_cast<std::size_t>(in_range_bin(x))];
  }

  /// Pre-grows storage for up to `bins` bins, so refits up to that size do not allocate.
  void reserve(Index bins) {
    edges_.reserve(static_cast<std::size_t>(bins + 1));
    counts_.reserve(static_cast<std::size_t>(bins));
    contribution_.reserve(static_cast<std::size_t>(bins));
  }

  /// Re-fits this histogram to `column` in place, reusing its storage and `scratch`: no heap
  /// allocation once the buffers have grown to the sizes needed. `feature` only labels errors.
  /// The column must be non-empty and finite (the model checks).
  template <class Column>
  void refit(const Column& column, const FeatureSpec& spec, const ScoringOptions& options,
             std::vector<Scalar>& scratch, Index feature = 0);

 private:
  [[nodiscard]] Scalar wrap(Scalar x) const {
    Scalar t = x - lo_;
    if (t < Scalar(0) || t >= period_) t -= period_ * std::floor(t / period_);
    return t;  // in [0, period] (rounding may give exactly period: clamped to the last bin)
  }
  /// Uniform bins: offset t = x - lower() in [0, upper() - lower()].
  [[nodiscard]] Index uniform_bin(Scalar t) const {
    const auto k = static_cast<Index>(t * inv_width_);
    return std::min(k, bins() - 1);
  }
  [[nodiscard]] Index in_range_bin(Scalar x) const {
    if (uniform_) return uniform_bin(x - lo_);
    // Irregular bins: the number of interior edges <= x.
    const auto first = edges_.begin() + 1;
    const auto last = edges_.end() - 1;
    return static_cast<Index>(std::upper_bound(first, last, x) - first);
  }

  template <class Column>
  void place_uniform_edges(const Column& column, const FeatureSpec& spec,
                           std::vector<Scalar>& scratch, Index feature);
  void place_equal_frequency_edges(const Scalar* sorted, Index n, Index k);
  template <class Column>
  void count_and_score(const Column& values, const ScoringOptions& options);
  template <class Column>
  Index rule_bins(const Column& column, const Binning& binning, Scalar lo, Scalar hi,
                  std::vector<Scalar>& scratch) const;

  std::vector<Scalar> edges_;
  std::vector<Index> counts_;
  std::vector<Scalar> contribution_;
  Scalar lo_ = 0, hi_ = 0;
  Scalar inv_width_ = 0;  // uniform bins only (0 for a constant feature)
  Scalar period_ = 0;     // periodic only
  Scalar tolerance_lo_ = 0, tolerance_hi_ = 0;
  Scalar below_ = 0, above_ = 0;  // contributions beyond the tolerance band
  Scalar cap_ = 0;
  Index mode_ = 0;
  Index shifts_ = 1;  // averaged shifted histograms: fine bins per coarse bin
  Tail tail_ = Tail::Both;
  bool periodic_ = false;
  bool uniform_ = true;
};

// ---------------------------------------------------------------------------------------------
// Implementation
// ---------------------------------------------------------------------------------------------

template <class Scalar>
template <class Column>
Eigen::Index Histogram<Scalar>::rule_bins(const Column& column, const Binning& binning, Scalar lo,
                                          Scalar hi, std::vector<Scalar>& scratch) const {
  const Index n = column.size();
  const double range = static_cast<double>(hi) - static_cast<double>(lo);
  const double dn = static_cast<double>(n);
  switch (binning.rule) {
    case BinCountRule::Fixed:
      return binning.bins;
    case BinCountRule::Sqrt:
      return detail::clamp_bins(std::ceil(std::sqrt(dn)), binning.max_bins);
    case BinCountRule::Sturges:
      return detail::clamp_bins(static_cast<double>(detail::sturges_bins(n)), binning.max_bins);
    case BinCountRule::Scott: {
      double mean = 0.0;
      for (Index i = 0; i < n; ++i)
        mean += static_cast<double>(scratch[static_cast<std::size_t>(i)]);
      mean /= dn;
      double ss = 0.0;
      for (Index i = 0; i < n; ++i) {
        const double d = static_cast<double>(scratch[static_cast<std::size_t>(i)]) - mean;
        ss += d * d;
      }
      const double h =
          std::cbrt(24.0 * std::sqrt(3.14159265358979323846) / dn) * std::sqrt(ss / dn);
      return detail::bins_from_width(range, h, n, binning.max_bins);
    }
    case BinCountRule::FreedmanDiaconis: {
      Scalar* v = scratch.data();  // sorted by the caller
      auto quantile = [&](double q) {
        const double pos = q * (dn - 1.0);
        const auto i = static_cast<std::size_t>(std::floor(pos));
        const double g = pos - static_cast<double>(i);
        const double a = static_cast<double>(v[i]);
        const double b = i + 1 < static_cast<std::size_t>(n) ? static_cast<double>(v[i + 1]) : a;
        return a + (b - a) * g;
      };
      const double iqr = quantile(0.75) - quantile(0.25);
      return detail::bins_from_width(range, 2.0 * iqr / std::cbrt(dn), n, binning.max_bins);
    }
    case BinCountRule::BirgeRozenblac:
      return detail::birge_rozenblac_bins(scratch.data(), n, binning.max_bins);
  }
  return binning.bins;
}

template <class Scalar>
template <class Column>
void Histogram<Scalar>::place_uniform_edges(const Column& column, const FeatureSpec& spec,
                                            std::vector<Scalar>& scratch, Index feature) {
  const Binning& binning = spec.binning;
  Index k = 1;
  Scalar width = 0;
  if (spec.periodic) {
    lo_ = static_cast<Scalar>(spec.period_start);
    period_ = static_cast<Scalar>(spec.period);
    hi_ = lo_ + period_;
    if (binning.method == BinningMethod::FixedWidth) {
      // The period must hold a whole number of bins: the width is rounded to the nearest divisor.
      k = detail::clamp_bins(std::round(spec.period / binning.width), binning.max_bins);
    } else {
      k = rule_bins(column, binning, lo_, hi_, scratch);
    }
    width = period_ / static_cast<Scalar>(k);
  } else if (binning.method == BinningMethod::FixedWidth) {
    const Scalar lo = column.minCoeff();
    const Scalar hi = column.maxCoeff();
    const double first = std::floor((static_cast<double>(lo) - binning.origin) / binning.width);
    const double last =
        std::floor((static_cast<double>(hi) - binning.origin) / binning.width) + 1.0;
    detail::require(
        last - first <= static_cast<double>(binning.max_bins) / static_cast<double>(shifts_),
        "feature ", feature, ": fixed bin width ", binning.width, " over the range [", lo, ", ", hi,
        "] needs ", last - first, " bins, more than max_bins = ", binning.max_bins);
    k = static_cast<Index>(last - first);
    width = static_cast<Scalar>(binning.width);
    lo_ = static_cast<Scalar>(binning.origin + first * binning.width);
    hi_ = static_cast<Scalar>(binning.origin + last * binning.width);
  } else {
    lo_ = column.minCoeff();
    hi_ = column.maxCoeff();
    if (hi_ > lo_) {
      k = rule_bins(column, binning, lo_, hi_, scratch);
      width = (hi_ - lo_) / static_cast<Scalar>(k);
    }
  }
  // Averaged shifted histograms count on a grid m times finer than the coarse bins.
  if (width > Scalar(0) && shifts_ > 1) {
    detail::require(k * shifts_ <= binning.max_bins, "feature ", feature, ": ", k, " bins x ",
                    shifts_, " shifts exceed max_bins = ", binning.max_bins);
    k *= shifts_;
    width /= static_cast<Scalar>(shifts_);
  }
  inv_width_ = width > Scalar(0) ? Scalar(1) / width : Scalar(0);
  edges_.resize(static_cast<std::size_t>(k + 1));
  for (Index j = 0; j < k; ++j)
    edges_[static_cast<std::size_t>(j)] = lo_ + static_cast<Scalar>(j) * width;
  edges_.back() = hi_;
}

template <class Scalar>
void Histogram<Scalar>::place_equal_frequency_edges(const Scalar* sorted, Index n, Index k) {
  // Goldstein & Dengel's dynamic bins: about n/k sorted values per bin; a boundary never splits
  // a run of equal values, so ties may merge bins. Edges sit midway between the last value of a
  // bin and the first of the next, so every bin has positive width when values differ.
  lo_ = sorted[0];
  hi_ = sorted[n - 1];
  edges_.clear();
  edges_.push_back(lo_);
  Index previous = 0;
  for (Index b = 1; b < k; ++b) {
    auto p = static_cast<Index>(
        std::llround(static_cast<double>(b) * static_cast<double>(n) / static_cast<double>(k)));
    if (p <= previous) continue;
    while (p < n && sorted[p] == sorted[p - 1]) ++p;
    if (p >= n) break;
    edges_.push_back(sorted[p - 1] + (sorted[p] - sorted[p - 1]) / Scalar(2));
    previous = p;
  }
  edges_.push_back(hi_);
}

template <class Scalar>
template <class Column>
void Histogram<Scalar>::count_and_score(const Column& values, const ScoringOptions& options) {
  const Index n = values.size();
  const auto k = static_cast<std::size_t>(edges_.size() - 1);
  counts_.assign(k, 0);
  // Periodic values arrive as offsets wrap(x) into the period: exactly what lookup computes.
  if (periodic_) {
    for (Index i = 0; i < n; ++i) ++counts_[static_cast<std::size_t>(uniform_bin(values.coeff(i)))];
  } else {
    for (Index i = 0; i < n; ++i)
      ++counts_[static_cast<std::size_t>(in_range_bin(values.coeff(i)))];
  }

  contribution_.resize(k);
  const bool constant = !periodic_ && !(hi_ > lo_);
  if (constant) {
    contribution_[0] = 0;
    cap_ = static_cast<Scalar>(std::log(static_cast<double>(n) / options.empty_bin_count));
    mode_ = 0;
  } else {
    // Smoothed mass around each bin (averaged shifted histograms, Scott 1985): with m shifts the
    // fine bins are 1/m of a coarse bin and m_i = sum_{|d|<m} (1 - |d|/m) count_{i+d}, i.e. the
    // average of the m coarse histograms whose origins are shifted by one fine bin each. m = 1 is
    // the plain histogram. Periodic features wrap around. Stored in contribution_ for now.
    const auto m = static_cast<std::ptrdiff_t>(shifts_);
    const auto kk = static_cast<std::ptrdiff_t>(k);
    for (std::ptrdiff_t i = 0; i < kk; ++i) {
      double mass = static_cast<double>(counts_[static_cast<std::size_t>(i)]);
      for (std::ptrdiff_t d = 1; d < m; ++d) {
        const double weight = 1.0 - static_cast<double>(d) / static_cast<double>(m);
        std::ptrdiff_t left = i - d, right = i + d;
        if (periodic_) {
          left = (left % kk + kk) % kk;
          right = right % kk;
        }
        if (left >= 0)
          mass += weight * static_cast<double>(counts_[static_cast<std::size_t>(left)]);
        if (right < kk)
          mass += weight * static_cast<double>(counts_[static_cast<std::size_t>(right)]);
      }
      contribution_[static_cast<std::size_t>(i)] = static_cast<Scalar>(mass);
    }
    // Heights h_i = mass_i / width_i, in double; only ratios to h_max matter. An empty
    // neighbourhood counts as `empty_bin_count` samples.
    // Uniform bins share one nominal width: using it (not edge differences, which carry the
    // rounding of lo + j * width) keeps heights exactly proportional to mass, and scores exactly
    // invariant under affine maps of the feature.
    auto width_of = [&](std::size_t i) {
      return uniform_ ? 1.0 : static_cast<double>(edges_[i + 1]) - static_cast<double>(edges_[i]);
    };
    auto height = [&](std::size_t i, bool regularise) {
      const double w = width_of(i);
      const double mass = static_cast<double>(contribution_[i]);
      return (regularise && !(mass > 0.0) ? options.empty_bin_count : mass) / w;
    };
    double h_max = 0.0;
    double w_max = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
      const double h = height(i, false);
      if (h > h_max) {
        h_max = h;
        mode_ = static_cast<Index>(i);
      }
      w_max = std::max(w_max, width_of(i));
    }
    for (std::size_t i = 0; i < k; ++i)
      contribution_[i] = static_cast<Scalar>(std::max(0.0, std::log(h_max / height(i, true))));
    // The cap is at least every bin's contribution (with shifts, a bin's smoothed mass can be
    // below empty_bin_count).
    cap_ = static_cast<Scalar>(std::log(h_max * w_max / options.empty_bin_count));
    for (std::size_t i = 0; i < k; ++i) cap_ = std::max(cap_, contribution_[i]);
  }

  // One-sided tails: zero on the good side of the mode, a running maximum on the anomalous side.
  const auto mode = static_cast<std::size_t>(mode_);
  if (tail_ == Tail::Upper) {
    std::fill(contribution_.begin(), contribution_.begin() + static_cast<std::ptrdiff_t>(mode) + 1,
              Scalar(0));
    for (std::size_t b = mode + 1; b < k; ++b)
      contribution_[b] = std::max(contribution_[b], contribution_[b - 1]);
  } else if (tail_ == Tail::Lower) {
    std::fill(contribution_.begin() + static_cast<std::ptrdiff_t>(mode), contribution_.end(),
              Scalar(0));
    for (std::size_t b = mode; b-- > 0;)
      contribution_[b] = std::max(contribution_[b], contribution_[b + 1]);
  }
  below_ = tail_ == Tail::Upper ? Scalar(0) : cap_;
  above_ = tail_ == Tail::Lower ? Scalar(0) : cap_;

  // The tolerance counts coarse bins (m fine bins each).
  const auto tol = static_cast<Scalar>(options.range_tolerance * static_cast<double>(shifts_));
  tolerance_lo_ = lo_ - tol * (edges_[1] - edges_[0]);
  tolerance_hi_ = hi_ + tol * (edges_[k] - edges_[k - 1]);
}

template <class Scalar>
template <class Column>
void Histogram<Scalar>::refit(const Column& column, const FeatureSpec& spec,
                              const ScoringOptions& options, std::vector<Scalar>& scratch,
                              Index feature) {
  const Index n = column.size();
  detail::require(n > 0, "feature ", feature, ": cannot fit a histogram to no samples");
  periodic_ = spec.periodic;
  tail_ = spec.tail;
  period_ = 0;
  shifts_ = spec.binning.method == BinningMethod::EqualFrequency ? 1 : spec.binning.shifts;

  const BinCountRule rule = spec.binning.rule;
  const bool equal_frequency = spec.binning.method == BinningMethod::EqualFrequency;
  const bool needs_sorted =
      equal_frequency ||
      (spec.binning.method == BinningMethod::EqualWidth &&
       (rule == BinCountRule::FreedmanDiaconis || rule == BinCountRule::BirgeRozenblac));
  const bool needs_copy =
      periodic_ || needs_sorted ||
      (spec.binning.method == BinningMethod::EqualWidth && rule == BinCountRule::Scott);
  if (!needs_copy) {
    // The common case (equal or fixed width, a rule that needs only n): two passes over the
    // caller's column, no copy.
    uniform_ = true;
    place_uniform_edges(column, spec, scratch, feature);
    count_and_score(column, options);
    return;
  }

  // Otherwise the values, wrapped for periodic features, go to scratch: moments, quantiles,
  // sorting and the counting pass read them from there.
  scratch.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) scratch[static_cast<std::size_t>(i)] = column.coeff(i);
  if (periodic_) {
    lo_ = static_cast<Scalar>(spec.period_start);
    period_ = static_cast<Scalar>(spec.period);
    for (auto& v : scratch) v = wrap(v);  // offsets into the period; every rule is shift-invariant
  }
  if (needs_sorted) std::sort(scratch.begin(), scratch.end());

  const Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> values(scratch.data(), n);
  if (equal_frequency) {
    uniform_ = false;
    inv_width_ = 0;
    const Index k = scratch.front() < scratch.back()
                        ? rule_bins(values, spec.binning, scratch.front(), scratch.back(), scratch)
                        : 1;
    place_equal_frequency_edges(scratch.data(), n, k);
  } else {
    uniform_ = true;
    place_uniform_edges(values, spec, scratch, feature);
  }
  count_and_score(values, options);
}

}  // namespace hbos
