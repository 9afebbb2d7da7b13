#pragma once
/// \file
/// The robust noise scale of a frame's centred, whitened residual magnitudes.
///
/// If the static matches' centred, whitened residuals are 2-D Gaussian with scale s per axis,
/// their magnitudes m follow a Rayleigh law, F(m) = 1 - exp(-m^2 / (2 s^2)), so the q-quantile
/// of m is s sqrt(-2 ln(1 - q)) and s = m_q / sqrt(-2 ln(1 - q)). Reading a low quantile keeps
/// the estimate on the static matches when a dynamic object holds most of the large residuals
/// (it breaks down only when more than 1 - q of the fit set lies below the static noise).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace hbos::detail {

/// s from the `quantile` of `magnitudes` (reordered in place; at least one value). A scale of
/// exactly 0 (every residual zero) is returned as is.
template <class Scalar>
[[nodiscard]] Scalar rayleigh_scale(std::vector<Scalar>& magnitudes, std::size_t count,
                                    double quantile) {
  const auto k = static_cast<std::size_t>(std::min<double>(
      static_cast<double>(count - 1), std::floor(quantile * static_cast<double>(count))));
  const auto nth = magnitudes.begin() + static_cast<std::ptrdiff_t>(k);
  std::nth_element(magnitudes.begin(), nth,
                   magnitudes.begin() + static_cast<std::ptrdiff_t>(count));
  return static_cast<Scalar>(static_cast<double>(*nth) / std::sqrt(-2.0 * std::log1p(-quantile)));
}

}  // namespace hbos::detail
