#pragma once
/// \file
/// Stage 3: the rough pose, under which the residuals are measured. FINDINGS.md point 4: the
/// residual screen can only be as good as this pose, so it is taken from the matches that avoid
/// the mask, by PnP RANSAC with a tight threshold; constant velocity is the fallback (and an
/// option, measured in docs/slam_demo.md).

#include "frontend/config.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>

#include <vector>

namespace hbos::slam {

struct RoughPose {
  Eigen::Isometry3d T_cur_prev = Eigen::Isometry3d::Identity();  ///< previous -> current camera
  bool from_ransac = false;  ///< false: the constant-velocity prediction was used
  int ransac_inliers = 0;
};

class RoughPoseEstimator {
 public:
  /// Throws hbos::InvalidArgument on settings out of range.
  RoughPoseEstimator(const RoughPoseConfig& config, hbos::PinholeCamerad camera);

  /// `points_prev[i]` (previous camera frame [m]) is observed at `observed[i]` (undistorted [px])
  /// in the current frame. `constant_velocity` is the last frame-to-frame motion.
  [[nodiscard]] RoughPose estimate(const std::vector<Eigen::Vector3d>& points_prev,
                                   const std::vector<Eigen::Vector2d>& observed,
                                   const Eigen::Isometry3d& constant_velocity) const;

 private:
  RoughPoseConfig config_;
  hbos::PinholeCamerad camera_;
};

}  // namespace hbos::slam
