#pragma once
/// \file
/// Arithmetic at the edges of the floating-point range: casts that saturate instead of invoking
/// undefined behaviour, and the power-of-two scale that lets a range which overflows (-1e308 to
/// 1e308) or underflows (subnormal values) be binned exactly as an ordinary one.
///
/// Multiplying by a power of two is exact unless the result leaves the normal range, so a
/// column binned as x * s gives the very bins of x wherever x itself could be binned; the
/// scale is 1 (and the arithmetic bit for bit the unscaled one) on every ordinary column.

#include <algorithm>
#include <cmath>
#include <limits>

namespace hbos::detail {

/// `value` converted to To, clamped to To's finite range (NaN stays NaN). A double beyond
/// FLT_MAX converted to float is undefined behaviour in C++; this is not.
template <class To>
[[nodiscard]] To saturate_cast(double value) {
  using Limits = std::numeric_limits<To>;
  if (value > static_cast<double>(Limits::max())) return Limits::max();
  if (value < static_cast<double>(Limits::lowest())) return Limits::lowest();
  return static_cast<To>(value);
}

/// A power of two s with max(|lo|, |hi|) * s in [1, 2) (as far as s stays representable): the
/// scale that puts a column's values near 1.
template <class Scalar>
[[nodiscard]] Scalar unit_scale(Scalar lo, Scalar hi) {
  const Scalar m = std::max(std::abs(lo), std::abs(hi));
  if (!(m > Scalar(0)) || !std::isfinite(m)) return Scalar(1);
  constexpr int top = std::numeric_limits<Scalar>::max_exponent - 1;  // 2^top is the largest
  const int e = std::clamp(-static_cast<int>(std::ilogb(m)), -top, top);
  return std::ldexp(Scalar(1), e);
}

/// The scale for the bin-count rules (which compute in double): 1 while the values' squares and
/// sums stay comfortably inside double's range (|v| <= 2^480, range 0 or >= 2^-480), else
/// unit_scale. Every rule's bin count is invariant under a power-of-two scale.
[[nodiscard]] inline double rule_scale(double lo, double hi) {
  const double m = std::max(std::abs(lo), std::abs(hi));
  const double range = hi - lo;
  constexpr double big = 0x1p480;
  constexpr double small = 0x1p-480;
  if (m <= big && (range == 0.0 || range >= small)) return 1.0;
  return unit_scale(lo, hi);
}

/// (b - a) / w for b >= a, w > 0, without the overflow of b - a (a = -1e308, b = 1e308).
[[nodiscard]] inline double span_over(double a, double b, double w) {
  const double span = b - a;
  if (std::isfinite(span)) return span / w;
  return (b * 0.5 - a * 0.5) / w * 2.0;
}

/// ln(b - a) for b > a, without the overflow of b - a; a zero span counts as the smallest
/// positive double.
[[nodiscard]] inline double log_span(double a, double b) {
  const double span = b - a;
  if (std::isfinite(span)) {
    return std::log(span > 0.0 ? span : std::numeric_limits<double>::denorm_min());
  }
  return std::log(b * 0.5 - a * 0.5) + std::log(2.0);
}

}  // namespace hbos::detail
