#pragma once
/// \file
/// Stage 5: pose refinement on the matches the screen kept: hbos's Gauss-Newton with a Huber loss
/// on the whitened reprojection error (hbos/screening/pose_refinement.hpp), the cost ORB-SLAM2's
/// PoseOptimization minimises. This file is the front end's only use of that header.
///
/// ORB-SLAM2's width, sqrt(5.991) = 2.447, assumes one pixel of noise per axis at octave 0. With
/// `huber_from_noise` the width follows the noise the refined matches actually have: under the
/// starting pose, their whitened residuals' median norm over sqrt(2 ln 2) (a 2-D Gaussian's
/// median norm is sigma sqrt(2 ln 2)) gives the noise scale s, and the width is 2.447 s, with s
/// clamped to [min_noise_scale, 1]. Matches the noise explains keep their full weight; those
/// beyond 2.447 noise scales lose it as Huber's do beyond 2.447 pixels. Never wider than
/// ORB-SLAM2's.

#include "frontend/config.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>

#include <cstdint>
#include <vector>

namespace hbos::slam {

class PoseRefiner {
 public:
  /// Throws hbos::InvalidArgument on settings out of range.
  PoseRefiner(const RefinementConfig& config, hbos::PinholeCamerad camera);

  /// Refines `T_cur_prev` in place from the matches with `use[i]` set: `points_prev[i]`
  /// (previous camera frame [m]) seen at `observed[i]` [px] with scale sigma `sigma[i]`.
  /// Returns the number of matches used in the last step (fewer than 3: pose unchanged).
  Eigen::Index refine(const std::vector<Eigen::Vector3d>& points_prev,
                      const std::vector<Eigen::Vector2d>& observed,
                      const std::vector<double>& sigma, const std::vector<std::uint8_t>& use,
                      Eigen::Isometry3d& T_cur_prev) const;

  [[nodiscard]] const hbos::PinholeCamerad& camera() const { return camera_; }

  /// The Huber width [px/sigma] that refine() would use for these matches at pose `T_cur_prev`.
  [[nodiscard]] double huber_width(const std::vector<Eigen::Vector3d>& points_prev,
                                   const std::vector<Eigen::Vector2d>& observed,
                                   const std::vector<double>& sigma,
                                   const std::vector<std::uint8_t>& use,
                                   const Eigen::Isometry3d& T_cur_prev) const;

 private:
  RefinementConfig config_;
  hbos::PinholeCamerad camera_;
};

}  // namespace hbos::slam
