#pragma once
/// \file
/// numpy's rounding and percentile rules, replicated to the bit: the threshold rules and the
/// PyOD-compatible mode both need `numpy.percentile(..., method="linear")` exactly as numpy
/// computes it.

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hbos::detail {

/// `a * b` rounded to T before the caller uses it. Bit-parity with numpy needs a product and a
/// following addition to round twice; GCC (GNU mode, -ffp-contract=fast) and Clang
/// (-ffp-contract=on) may fuse them into one FMA when the target has FMA (-march=native, -mfma),
/// and GCC ignores
/// `#pragma STDC FP_CONTRACT`. Storing the product through a volatile forces the rounding on
/// every compiler; it costs one store/load, so it is used only where parity depends on it.
template <class T>
[[nodiscard]] inline T mul_rounded(T a, T b) {
  volatile T product = a * b;
  return product;
}

/// numpy's `_lerp(a, b, t)`: a + (b - a) t, evaluated from the upper end, b - (b - a)(1 - t), when
/// t >= 0.5 (so t = 1 gives b exactly).
/// Where b - a overflows (a = -1e308, b = 1e308; numpy returns inf there) the same formula runs
/// on halves, exactly scaled back: the interpolant always lies in [a, b].
[[nodiscard]] inline double numpy_lerp(double a, double b, double t) {
  const double diff = b - a;
  if (!std::isfinite(diff) && std::isfinite(a) && std::isfinite(b)) {
    return 2.0 * numpy_lerp(a * 0.5, b * 0.5, t);
  }
  return t >= 0.5 ? b - mul_rounded(diff, 1.0 - t) : a + mul_rounded(diff, t);
}

/// numpy.percentile(a, 100*q, method="linear") on `values` (reordered in place), bit-identical to
/// numpy: v = (n-1) q, i = floor(v), g = v - i, then numpy's `_lerp` of the i-th and (i+1)-th
/// smallest values.
template <class Scalar>
Scalar numpy_percentile_linear(Scalar* first, Scalar* last, double q) {
  const auto n = static_cast<std::size_t>(last - first);
  const double v = static_cast<double>(n - 1) * q;
  const auto i = static_cast<std::size_t>(std::floor(v));
  if (i + 1 >= n) return *std::max_element(first, last);
  std::nth_element(first, first + static_cast<std::ptrdiff_t>(i), last);
  const Scalar lo = first[i];
  const Scalar hi = *std::min_element(first + static_cast<std::ptrdiff_t>(i) + 1, last);
  const double g = v - static_cast<double>(i);
  return static_cast<Scalar>(numpy_lerp(static_cast<double>(lo), static_cast<double>(hi), g));
}

/// Median of [first, last) (mean of the two middle values for an even count), reordering in place.
template <class Scalar>
Scalar median_inplace(Scalar* first, Scalar* last) {
  return numpy_percentile_linear(first, last, 0.5);
}

}  // namespace hbos::detail
