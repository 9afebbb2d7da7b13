#pragma once
/// \file
/// Stage 5: pose refinement on the matches the screen kept: hbos's Gauss-Newton with a Huber loss
/// on the whitened reprojection error (hbos/screening/pose_refinement.hpp), the cost ORB-SLAM2's
/// PoseOptimization minimises. This file is the front end's only use of that header.

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

 private:
  RefinementConfig config_;
  hbos::PinholeCamerad camera_;
};

}  // namespace hbos::slam
