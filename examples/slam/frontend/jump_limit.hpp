#pragma once
/// \file
/// The most a camera moves from one frame to the next. A pose step beyond it is a failed
/// estimate, not motion: both trackers then keep their prediction (docs/results.md, "A
/// frame-to-frame pose that jumped 5 m").

#include <Eigen/Geometry>

namespace hbos::slam {

struct JumpLimit {
  /// [m] per frame: 9 m/s at 30 frames/s, far beyond any hand-held or robot-mounted camera
  double max_m = 0.3;
  /// [deg] per frame: 900 deg/s at 30 frames/s, likewise
  double max_deg = 30.0;

  /// True when `step` (a relative pose: one frame's motion, or a pose's distance from its
  /// prediction) moves further than the limit.
  [[nodiscard]] bool exceeded_by(const Eigen::Isometry3d& step) const {
    const double degrees =
        Eigen::AngleAxisd(step.linear()).angle() * 180.0 / 3.14159265358979323846;
    return step.translation().norm() > max_m || degrees > max_deg;
  }
};

}  // namespace hbos::slam
