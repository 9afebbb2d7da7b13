#pragma once
/// \file
/// Stage 3: the rough pose, under which the residuals are measured. FINDINGS.md point 4: the
/// residual screen can only be as good as this pose, so it is taken from the matches that avoid
/// the mask, by PnP RANSAC with a tight threshold; constant velocity is the fallback (and an
/// option, measured in docs/slam_demo.md).

#include "frontend/config.hpp"
#include "frontend/jump_limit.hpp"
#include "frontend/outlier_share.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace hbos::slam {

/// Which rule the history consensus follows; part of the cached runs' keys (hbos-dynbench's
/// cells, the variant grid's runs), so that a run made under an older rule is not reused.
/// 1: support weighted by 1 - outlier share (stop 26). 2: by static trust, and tracks never
/// screened left out of the second consensus (stop 27).
inline constexpr int kHistoryConsensusRule = 2;

struct RoughPose {
  Eigen::Isometry3d T_cur_prev = Eigen::Isometry3d::Identity();  ///< previous -> current camera
  bool from_ransac = false;  ///< false: the constant-velocity prediction was used
  int ransac_inliers = 0;
  /// the pose came from the second consensus, of the tracks the screen mostly kept
  /// (RoughPoseConfig::history_consensus)
  bool from_remembered_statics = false;
};

class RoughPoseEstimator {
 public:
  /// Throws hbos::InvalidArgument on settings out of range. A consensus further than
  /// `jump_limit` from the prediction is refused for the prediction.
  RoughPoseEstimator(const RoughPoseConfig& config, hbos::PinholeCamerad camera,
                     JumpLimit jump_limit = {});

  /// `points_prev[i]` (previous camera frame [m]) is observed at `observed[i]` (undistorted [px])
  /// in the current frame. `constant_velocity` is the prediction (the last frame-to-frame motion,
  /// or the map tracker's predicted pose, with points in world coordinates).
  /// `memory`, empty or one per match: the screenings of the match's track so far
  /// (frontend/outlier_share.hpp).
  [[nodiscard]] RoughPose estimate(const std::vector<Eigen::Vector3d>& points_prev,
                                   const std::vector<Eigen::Vector2d>& observed,
                                   const Eigen::Isometry3d& constant_velocity,
                                   const std::vector<OutlierShare>& memory = {}) const;

 private:
  /// estimate() without the jump limit: RANSAC's consensus, or the remembered statics'.
  [[nodiscard]] RoughPose best_consensus(const std::vector<Eigen::Vector3d>& points_prev,
                                         const std::vector<Eigen::Vector2d>& observed,
                                         const Eigen::Isometry3d& constant_velocity,
                                         const std::vector<OutlierShare>& memory) const;
  /// PnP RANSAC on the matches with `use[i]` (all when empty); false when it finds no pose with
  /// min_inliers, or (RoughPoseConfig::check_refit) its refit does not hold half of them.
  /// `pose` is written only when true.
  bool consensus(const std::vector<cv::Point3d>& object, const std::vector<cv::Point2d>& image,
                 const std::vector<std::uint8_t>& use, Eigen::Isometry3d& pose,
                 std::vector<int>& inliers) const;
  /// Sum over the matches within the RANSAC threshold under `pose` of their tracks' static
  /// trust (OutlierShare::static_trust).
  [[nodiscard]] double remembered_support(const std::vector<cv::Point3d>& object,
                                          const std::vector<cv::Point2d>& image,
                                          const std::vector<OutlierShare>& memory,
                                          const Eigen::Isometry3d& pose) const;

  RoughPoseConfig config_;
  hbos::PinholeCamerad camera_;
  JumpLimit jump_limit_;
};

}  // namespace hbos::slam
