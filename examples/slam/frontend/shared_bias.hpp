#pragma once
/// \file
/// How much of a frame's residual static neighbours share. Real static matches are not
/// independent: depth and timing errors move neighbours alike, so a neighbourhood's mean
/// residual does not shrink to zero as it grows. The leverage guard (leverage_guard.hpp) allows
/// for that offset when it asks whether a group of matches moved; without it, any large enough
/// static group would look as if it had.

#include <Eigen/Core>

#include <vector>

namespace hbos::slam {

/// The offset b that neighbouring matches share, per axis, in units of the noise scale s: with
/// the matches binned into square cells of `cell_px` by their pixel, a cell of n matches has a
/// mean residual m ~ N(0, s^2 (b^2 + 1/n) I) if each cell shares an offset ~ N(0, b^2 s^2 I) on
/// top of independent noise, so |m|^2 / (s^2 (b^2 + 1/n)) is chi-square with 2 degrees of
/// freedom. b is the value that puts that statistic's median over the cells at chi-square's
/// median, 2 ln 2 (0 when it is below it already): a median, so a few cells that hold
/// something moving do not inflate it.
///
/// `pixel[i]` [px] and `residual[i]` [sigma units] are match i's; `noise` is s [sigma units].
/// Cells with fewer than `min_matches` matches are not used; with fewer than `min_cells` used
/// cells there is no evidence of a shared offset and the result is 0.
/// \throws hbos::InvalidArgument when the lengths differ or cell_px, noise are not finite and > 0.
[[nodiscard]] double shared_bias_scales(const std::vector<Eigen::Vector2d>& pixel,
                                        const std::vector<Eigen::Vector2d>& residual, double noise,
                                        double cell_px, int min_matches = 8, int min_cells = 4);

}  // namespace hbos::slam
