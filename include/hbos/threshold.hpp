#pragma once
/// \file
/// Thresholds on a score vector: each rule turns scores into a cut-off and an inlier mask.
///
/// Convention for every rule (as PyOD's `labels_`): a sample is an **outlier when its score is
/// strictly greater than the threshold**; inliers have `score <= threshold`.
///
/// - AdaptiveRange: `range_alpha * (max - min) + min` (the HBOS-SLAM paper, eq. 6).
/// - Contamination: the `(1 - c)` percentile with numpy's linear interpolation (PyOD's
///   `threshold_`).
/// - MedianMad: `median + k * s * MAD`, `s = 1.4826` when `scale_to_sigma` (robust statistics).
/// - FixedThreshold: `value`.
///
/// Threading: every function here is re-entrant; the scratch buffer is the caller's.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <variant>
#include <vector>

#include "hbos/detail/numpy.hpp"
#include "hbos/detail/scaling.hpp"
#include "hbos/error.hpp"

namespace hbos {

/// The paper's adaptive threshold (eq. 6): `delta = range_alpha * (max - min) + min`.
/// Larger `range_alpha` is looser (fewer rejections). Named `range_alpha`, not `alpha`, so it is
/// never confused with PyOD's `alpha`, which is a density regulariser.
struct AdaptiveRange {
  double range_alpha = 0.7;  ///< fraction of the score range, in (0, 1)
};

/// PyOD's contamination rule: the threshold is the `(1 - contamination)` percentile of the
/// scores, with numpy's default ("linear") interpolation.
struct Contamination {
  double contamination = 0.1;  ///< expected outlier share, in (0, 0.5]
};

/// Robust z-score rule: `median + k * s * MAD`, with MAD the median absolute deviation from the
/// median and `s = 1.4826` (the normal-consistency factor) when `scale_to_sigma` is set.
struct MedianMad {
  double k = 3.0;              ///< number of (scaled) MADs above the median, > 0
  bool scale_to_sigma = true;  ///< multiply MAD by 1.4826 so k counts standard deviations
};

/// A fixed cut-off on the score.
struct FixedThreshold {
  double value = 0.0;  ///< the threshold, finite
};

/// Any of the rules above; switching strategies is one assignment.
using ThresholdRule = std::variant<AdaptiveRange, Contamination, MedianMad, FixedThreshold>;

/// A threshold with the inlier mask it induces (the convenience, allocating API).
template <class Scalar>
struct Thresholded {
  Scalar threshold{};                            ///< outliers have score > threshold
  Eigen::Array<bool, Eigen::Dynamic, 1> inlier;  ///< inlier[i] == (score[i] <= threshold)
  Eigen::Index n_inliers = 0;                    ///< number of true entries in `inlier`
  [[nodiscard]] Eigen::Index n_outliers() const { return inlier.size() - n_inliers; }
};

namespace detail {

inline void validate(const AdaptiveRange& r) {
  require(r.range_alpha > 0.0 && r.range_alpha < 1.0,
          "range_alpha must lie in the open interval (0, 1), got ", r.range_alpha);
}
inline void validate(const Contamination& r) {
  require(r.contamination > 0.0 && r.contamination <= 0.5,
          "contamination must lie in (0, 0.5], got ", r.contamination);
}
inline void validate(const MedianMad& r) {
  require(r.k > 0.0 && std::isfinite(r.k), "MedianMad k must be finite and > 0, got ", r.k);
}
inline void validate(const FixedThreshold& r) {
  require(std::isfinite(r.value), "FixedThreshold value must be finite, got ", r.value);
}

template <class Derived>
void require_finite_scores(const Eigen::DenseBase<Derived>& scores) {
  require(scores.size() > 0, "cannot threshold an empty score vector");
  // s * 0 is 0 for finite s and NaN otherwise: Eigen sums it with packets, so the common case
  // costs a fraction of a scalar check; only a failure scans for the culprit.
  using Scalar = typename Derived::Scalar;
  if ((scores.derived().array() * Scalar(0)).sum() == Scalar(0)) return;
  for (Eigen::Index i = 0; i < scores.size(); ++i) {
    const auto s = scores.derived().coeff(i);
    require(std::isfinite(s), "score ", i, " is not finite (", s, ")");
  }
}

}  // namespace detail

/// Computes the threshold of `rule` on `scores` without allocating once `scratch` has grown to
/// the score count (only Contamination and MedianMad use it).
/// \throws InvalidArgument on an empty vector, a non-finite score or an out-of-range parameter.
template <class Derived>
typename Derived::Scalar compute_threshold(const Eigen::DenseBase<Derived>& scores,
                                           const ThresholdRule& rule,
                                           std::vector<typename Derived::Scalar>& scratch) {
  using Scalar = typename Derived::Scalar;
  std::visit([](const auto& r) { detail::validate(r); }, rule);
  detail::require_finite_scores(scores);
  const Eigen::Index n = scores.size();
  auto copy_to_scratch = [&]() {
    scratch.resize(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i)
      scratch[static_cast<std::size_t>(i)] = scores.derived().coeff(i);
    return scratch.data();
  };
  if (const auto* r = std::get_if<AdaptiveRange>(&rule)) {
    const Scalar lo = scores.minCoeff();
    const Scalar hi = scores.maxCoeff();
    const double range = static_cast<double>(hi - lo);
    if (std::isfinite(range)) {
      return static_cast<Scalar>(r->range_alpha * range + static_cast<double>(lo));
    }
    // A score range beyond Scalar's (-1e308 and 1e308): the same point, as a weighted mean.
    return detail::saturate_cast<Scalar>((1.0 - r->range_alpha) * static_cast<double>(lo) +
                                         r->range_alpha * static_cast<double>(hi));
  }
  if (const auto* r = std::get_if<Contamination>(&rule)) {
    // PyOD: percentile(scores, 100 * (1 - c)); numpy divides by 100 again, which is exact for
    // the q values PyOD produces (q = 0.9 for c = 0.1), so use the same arithmetic.
    const double q = (100.0 * (1.0 - r->contamination)) / 100.0;
    if constexpr (Derived::IsVectorAtCompileTime &&
                  static_cast<bool>(Derived::Flags & Eigen::DirectAccessBit) &&
                  Derived::InnerStrideAtCompileTime == 1) {
      // Contiguous scores are selected from where they are: no copy (scratch is the work area).
      return detail::numpy_percentile_linear(scores.derived().data(), static_cast<std::size_t>(n),
                                             q, scratch);
    } else {
      Scalar* data = copy_to_scratch();
      return detail::numpy_percentile_linear(data, data + n, q);
    }
  }
  if (const auto* r = std::get_if<MedianMad>(&rule)) {
    Scalar* data = copy_to_scratch();
    const Scalar median = detail::median_inplace(data, data + n);
    for (Eigen::Index i = 0; i < n; ++i) data[i] = std::abs(data[i] - median);
    const Scalar mad = detail::median_inplace(data, data + n);
    const double scale = r->scale_to_sigma ? 1.4826 : 1.0;
    // Saturated: a cut-off beyond the largest Scalar (huge k or MAD) keeps every finite score,
    // as the largest Scalar does; converting it would be undefined behaviour.
    // A MAD of 0 adds nothing, even for a k whose product with the scale overflows (inf * 0).
    const double spread = mad == Scalar(0) ? 0.0 : r->k * scale * static_cast<double>(mad);
    return detail::saturate_cast<Scalar>(static_cast<double>(median) + spread);
  }
  return detail::saturate_cast<Scalar>(std::get<FixedThreshold>(rule).value);
}

/// Writes `inlier[i] = scores[i] <= threshold` and returns the inlier count. No allocation.
template <class DerivedScores, class DerivedMask>
Eigen::Index apply_threshold(const Eigen::DenseBase<DerivedScores>& scores,
                             typename DerivedScores::Scalar threshold,
                             Eigen::DenseBase<DerivedMask>& inlier) {
  detail::require(inlier.size() == scores.size(), "inlier mask has ", inlier.size(),
                  " entries but there are ", scores.size(), " scores");
  Eigen::Index count = 0;
  for (Eigen::Index i = 0; i < scores.size(); ++i) {
    const bool keep = scores.derived().coeff(i) <= threshold;
    inlier.derived().coeffRef(i) = keep;
    count += keep ? 1 : 0;
  }
  return count;
}

/// One call: the threshold of `rule` on `scores` and the inlier mask it induces.
template <class Derived>
Thresholded<typename Derived::Scalar> threshold_scores(const Eigen::DenseBase<Derived>& scores,
                                                       const ThresholdRule& rule) {
  using Scalar = typename Derived::Scalar;
  std::vector<Scalar> scratch;
  Thresholded<Scalar> out;
  out.threshold = compute_threshold(scores, rule, scratch);
  out.inlier.resize(scores.size());
  out.n_inliers = apply_threshold(scores, out.threshold, out.inlier);
  return out;
}

}  // namespace hbos
