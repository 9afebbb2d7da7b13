#pragma once
/// \file
/// The mask neighbourhood's leverage guard: a stage between the screen and the final pose
/// refinement, for every screen. A segmenter's mask misses a person's rim; the matches there
/// move with the person. Where the static matches are all far away (a wall at the depth
/// camera's limit), a small rotation and a sideways translation move them alike, so they leave
/// that direction of the pose nearly free, and a few near matches on the rim decide it alone:
/// the pose follows the person while every static residual stays small. A residual screen
/// cannot see this (after the pull the rim fits too); the pose's information can.
///
/// The guard drops the survivors near the mask when both hold:
/// - along some direction of the pose they carry more information than all other survivors
///   together (hbos::group_leverage's ratio above `max_ratio`), and
/// - the group disagrees with the pose the other survivors give on their own: its residuals
///   under that pose exceed what the noise those survivors show and that pose's own
///   uncertainty explain (hbos::group_consistency's test of the group's mean residual, at
///   `consistency_z`); the offset static neighbours share in this frame counted in
///   (shared_bias.hpp, measured on the others).
/// A decisive group that agrees with the rest (static points along a detector box) is kept, and
/// so is one whose small shared offset only its size would make significant.

#include "frontend/config.hpp"
#include "frontend/pose_refiner.hpp"

#include <hbos/screening/pinhole.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <limits>
#include <vector>

namespace hbos::slam {

/// What the guard found on one frame.
struct GuardOutcome {
  /// hbos::group_leverage's ratio for the survivors near the mask; NaN: not measured (guard
  /// off, no mask distances, or no survivor near the mask)
  double ratio = std::numeric_limits<double>::quiet_NaN();
  /// The group's disagreement with the others' own pose: the chi-square of its mean residual
  /// (hbos::group_consistency's shift, its covariance widened by the shared bias) over its
  /// quantile (> 1: dropped); NaN: not measured (the ratio did not exceed its limit)
  double disagreement = std::numeric_limits<double>::quiet_NaN();
  /// The size of the group's shift: the norm of its mean residual under the others' pose, in
  /// their noise scales; NaN: not measured
  double shift_scales = std::numeric_limits<double>::quiet_NaN();
  /// The offset the others' neighbourhoods share, per axis, in noise scales (shared_bias.hpp),
  /// allowed for in the shift test; NaN: not measured
  double shared_bias = std::numeric_limits<double>::quiet_NaN();
  int dropped = 0;  ///< survivors near the mask set to rejected
};

class LeverageGuard {
 public:
  /// \throws hbos::InvalidArgument for a radius, ratio limit or z that is not finite and > 0.
  explicit LeverageGuard(const LeverageGuardConfig& config);

  /// [px] how far the mask distances must reach for the guard: its radius when it is on and
  /// the frames have masks (`mask_source`), 0 when it has nothing to do.
  [[nodiscard]] double reach_px(MaskSource mask_source) const;

  /// Measures the survivors (`inlier[i] != 0`) within the radius of the mask
  /// (`mask_distance_px[i]`, +inf when no mask pixel is that close) against the other survivors
  /// under `T_cur_prev` (`points[i]` in the frame the pose maps from, as the refiner takes
  /// them, seen at `observed[i]` with scale `sigma[i]`) and, when the two tests above fire, sets
  /// their `inlier` to 0. `refiner` fits the others' own pose (on a copy of `T_cur_prev`). An
  /// empty `mask_distance_px` means the frame has no mask distances: nothing is done.
  /// \throws hbos::InvalidArgument when the vectors' lengths differ.
  GuardOutcome apply(const std::vector<Eigen::Vector3d>& points,
                     const std::vector<Eigen::Vector2d>& observed, const std::vector<double>& sigma,
                     const std::vector<double>& mask_distance_px,
                     const Eigen::Isometry3d& T_cur_prev, const PoseRefiner& refiner,
                     std::vector<std::uint8_t>& inlier) const;

 private:
  LeverageGuardConfig config_;
};

}  // namespace hbos::slam
