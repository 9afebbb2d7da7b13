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
  /// [m] how far a RANSAC consensus may put the camera from the constant-velocity prediction.
  /// A real camera's change of velocity in a frame is far smaller than its motion, but the
  /// prediction is the tracker's own last step and carries its drift: a tighter bound refused
  /// the map tracker's recoveries from drift as often as it stopped a crowd's consensus
  /// (docs/results.md, stop 42), so by default it is as wide as the bound on motion.
  double max_from_prediction_m = 0.3;
  /// [deg] likewise for the orientation.
  double max_from_prediction_deg = 30.0;

  /// True when `step` (a relative pose: one frame's motion) moves further than the limit.
  [[nodiscard]] bool exceeded_by(const Eigen::Isometry3d& step) const {
    return beyond(step, max_m, max_deg);
  }
  /// True when `deviation` (a pose's distance from its constant-velocity prediction) is further
  /// than a camera's velocity changes in a frame.
  [[nodiscard]] bool departs_from_prediction(const Eigen::Isometry3d& deviation) const {
    return beyond(deviation, max_from_prediction_m, max_from_prediction_deg);
  }

 private:
  static bool beyond(const Eigen::Isometry3d& step, double metres, double degrees_max) {
    const double degrees =
        Eigen::AngleAxisd(step.linear()).angle() * 180.0 / 3.14159265358979323846;
    return step.translation().norm() > metres || degrees > degrees_max;
  }
};

}  // namespace hbos::slam
