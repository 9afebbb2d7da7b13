#pragma once
/// \file
/// A square grid of image cells over a set of pixels, for the screens' per-cell statistics
/// (cell balancing of the residual field, the coherence neighbourhoods). The grid is bounded
/// whatever the input: when the pixels span more than `max_side` cells of the requested size,
/// the cells grow. Offsets are taken at half scale in double, so the span of any two finite
/// pixels stays finite (pixels 1e308 apart would overflow a double span to inf, then inf / inf
/// cells).

#include <algorithm>
#include <cstddef>

namespace hbos::detail {

class PixelGrid {
 public:
  /// The grid over pixels in [u_lo, u_hi] x [v_lo, v_hi] (finite, lo <= hi) with cells of
  /// `cell_px` (> 0) or larger, at most `max_side` (>= 2) a side.
  PixelGrid(double u_lo, double u_hi, double v_lo, double v_hi, double cell_px, double max_side)
      : hu0_(0.5 * u_lo), hv0_(0.5 * v_lo) {
    const double half_span_u = 0.5 * u_hi - hu0_;
    const double half_span_v = 0.5 * v_hi - hv0_;
    half_cell_ = std::max(
        {0.5 * cell_px, half_span_u / (max_side - 1.0), half_span_v / (max_side - 1.0), 0.5e-9});
    nx_ = static_cast<std::size_t>(half_span_u / half_cell_) + 1;
    ny_ = static_cast<std::size_t>(half_span_v / half_cell_) + 1;
  }

  [[nodiscard]] std::size_t nx() const { return nx_; }
  [[nodiscard]] std::size_t ny() const { return ny_; }
  /// The column and row of a pixel inside the grid's range.
  [[nodiscard]] std::size_t column(double u) const {
    return std::min(static_cast<std::size_t>((0.5 * u - hu0_) / half_cell_), nx_ - 1);
  }
  [[nodiscard]] std::size_t row(double v) const {
    return std::min(static_cast<std::size_t>((0.5 * v - hv0_) / half_cell_), ny_ - 1);
  }
  /// Row-major cell index.
  [[nodiscard]] std::size_t cell(double u, double v) const { return row(v) * nx_ + column(u); }

 private:
  double hu0_, hv0_;
  double half_cell_ = 1.0;
  std::size_t nx_ = 1, ny_ = 1;
};

}  // namespace hbos::detail
