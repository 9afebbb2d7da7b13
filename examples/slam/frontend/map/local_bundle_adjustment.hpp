#pragma once
/// \file
/// Local bundle adjustment of the RGB-D keyframe map: the poses of the keyframes not held fixed
/// and the positions of the points they see, refined together on the whitened reprojection
/// error, as ORB-SLAM2's Optimizer::LocalBundleAdjustment does with g2o. Written on Eigen alone
/// so that the example needs no solver library.
///
/// Observation of point X by keyframe (R, t), with p = R X + t = (x, y, z) in the camera frame
/// and d the depth measured at the keypoint:
///
///     e = ((u - fx x/z - cx) / sigma,  (v - fy y/z - cy) / sigma  [, (bf/d - bf/z) / sigma_d])
///
/// The third row is the depth as a disparity, bf/d, as ORB-SLAM2's RGB-D edge has it, whose
/// noise an RGB-D sensor keeps roughly constant: its standard deviation sigma_d is the sensor's
/// (`disparity_sigma_px`) or else the keypoint's sigma. ORB-SLAM2 compares the virtual right
/// coordinate u - bf/d instead, which also carries the first row's pixel error; at the keypoint's
/// sigma that makes little difference, at a sensor's tenth of a pixel it would tie the point to
/// its pixel as tightly as to its depth. Used only when depth is enabled and measured. Cost: sum
/// of Huber(|e|^2), the width depending on the row count.
///
/// Levenberg-Marquardt, each free pose moved on the left (T <- exp(delta) T, delta = (rotation,
/// translation)) and each point additively. The points are eliminated from the normal equations
/// (Schur complement), leaving one dense 6F x 6F system for the F free keyframes; a local map has
/// tens of keyframes and thousands of points, so that system is the small one.
///
/// A point whose own 3x3 block is singular (a single observation without depth fixes a ray, not
/// a point) keeps its position; its observations still constrain the poses.
///
/// Threading: re-entrant; no shared state.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>

#include <cstdint>
#include <vector>

namespace hbos::slam {

struct BundleKeyframe {
  Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();  ///< world -> camera
  bool fixed = false;  ///< held constant: fixes the gauge (ORB-SLAM2's fixed covisible keyframes)
};

struct BundlePoint {
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();  ///< [m]
};

struct BundleObservation {
  int keyframe = 0;                                 ///< index into the keyframes
  int point = 0;                                    ///< index into the points
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  ///< undistorted keypoint [px]
  double sigma = 1.0;                               ///< [px] keypoint std dev, 1.2^octave
  double depth_m = 0.0;                             ///< measured depth [m]; 0 = none
};

struct BundleAdjustmentConfig {
  /// Levenberg-Marquardt iterations per pass, >= 1 (ORB-SLAM2: 5, then 10 without outliers).
  int iterations = 10;
  double huber_mono = 2.447;   ///< sqrt(5.991): Huber width of a 2-row whitened residual, >= 0
  double huber_depth = 2.796;  ///< sqrt(7.815): that of a 3-row one; 0 = plain least squares
  /// [px m] focal length times the virtual stereo baseline (ORB-SLAM2's Camera.bf) that turns a
  /// depth into the disparity bf/depth: the further the point, the less its depth counts, as an
  /// RGB-D sensor's disparity-like noise suggests.
  double baseline_fx = 40.0;
  /// [px] the disparity's standard deviation: the sensor's noise, which does not grow with the
  /// keypoint's pyramid level. 0: the keypoint's sigma, as ORB-SLAM2 does, which for a Kinect
  /// weighs depth about a hundred times less than the sensor measures it.
  double disparity_sigma_px = 0.0;
  bool use_depth = true;  ///< false: every observation has two rows
  /// After a first pass, drop the observations above the chi2 gates (5.991 for 2 rows, 7.815 for
  /// 3) or behind their camera and optimise again without them (ORB-SLAM2's second round).
  bool reject_outliers = true;
};

struct BundleAdjustmentResult {
  int iterations = 0;         ///< Levenberg-Marquardt iterations over both passes
  double initial_cost = 0.0;  ///< Huber cost at the start, over every observation [whitened]
  double final_cost = 0.0;    ///< at the end, over the observations the last pass used
  /// Per observation, 1 = outlier: behind its camera or above the chi2 gate at the end. Reported
  /// whether or not reject_outliers is set; an observation dropped after the first pass that
  /// fits the final estimate is not marked (as ORB-SLAM2 checks every edge again).
  std::vector<std::uint8_t> outlier;
  /// The last pass stopped because the cost no longer fell (relative decrease below 1e-6, or no
  /// damped step lowered it), not because it ran out of iterations.
  bool converged = false;
};

/// Optimises, in place, the poses of the keyframes not fixed and the position of every point
/// (also those only fixed keyframes see). Fixed keyframes are never written to.
/// \throws hbos::InvalidArgument, naming the field and the value, on an index out of range, a
/// sigma not finite and > 0, a non-finite pixel, depth, pose or point, a rotation that is not
/// orthonormal, settings out of range, invalid intrinsics, or no fixed keyframe while there are
/// observations (the map's position and orientation would be free).
[[nodiscard]] BundleAdjustmentResult adjust_bundle(
    std::vector<BundleKeyframe>& keyframes, std::vector<BundlePoint>& points,
    const std::vector<BundleObservation>& observations, const hbos::PinholeCamerad& camera,
    const BundleAdjustmentConfig& config = {});

}  // namespace hbos::slam
