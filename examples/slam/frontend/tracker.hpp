#pragma once
/// \file
/// The front end: frame-to-frame tracking with a reprojection-residual screen, as the HBOS
/// dynamic-SLAM method runs it inside ORB-SLAM2's tracking. `Tracker::track` is the algorithm.

#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/frame.hpp"
#include "frontend/frame_matching.hpp"
#include "frontend/leverage_guard.hpp"
#include "frontend/orb_extraction.hpp"
#include "frontend/outlier_share.hpp"
#include "frontend/pose_refiner.hpp"
#include "frontend/residual_screen.hpp"
#include "frontend/rough_pose.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace hbos::slam {

/// Per-frame statistics. "Person" matches are those with either keypoint on the composited
/// person (the label); all others count as static.
struct FrameStats {
  int index = 0;
  double stamp = 0.0;              ///< [s]
  int features = 0;                ///< ORB keypoints extracted (outside the mask)
  int matches = 0;                 ///< matches screened
  int person_matches = 0;          ///< of them, labelled dynamic
  int survivors = 0;               ///< kept by the screen
  int person_survivors = 0;        ///< labelled dynamic and kept
  int static_dropped = 0;          ///< static and rejected
  bool rough_from_ransac = false;  ///< false: constant velocity (by choice or fallback)
  int ransac_inliers = 0;
  /// the rough pose is the consensus of the tracks the screen mostly kept
  /// (RoughPoseConfig::history_consensus)
  bool rough_from_remembered_statics = false;
  /// The final (refined) pose has >= screen.min_inliers screened matches within the chi-square
  /// gate; else the frame took the constant-velocity prediction.
  bool tracked = false;
  double threshold = std::numeric_limits<double>::quiet_NaN();  ///< the screen's cut; NaN: none
  double screen_us = 0.0;  ///< [us] screening time, refinement excluded
  double refine_us = 0.0;  ///< [us] pose refinement time (between rounds and final)
  double mask_us = 0.0;    ///< [us] time to compute the frame's dynamic-object mask
  /// The leverage guard's ratio (frontend/leverage_guard.hpp); NaN: the guard did not run
  double guard_ratio = std::numeric_limits<double>::quiet_NaN();
  /// its disagreement (> 1: dropped); NaN: not measured (the ratio did not exceed its limit)
  double guard_disagreement = std::numeric_limits<double>::quiet_NaN();
  /// the size of the group's shift in noise scales; NaN: not measured
  double guard_shift = std::numeric_limits<double>::quiet_NaN();
  /// the offset the others' neighbourhoods share [noise scales]; NaN: not measured
  double guard_bias = std::numeric_limits<double>::quiet_NaN();
  int guard_dropped = 0;  ///< survivors near the mask the guard dropped
};

/// One screened match, for figures.
struct MatchRecord {
  Eigen::Vector2d current_px;   ///< keypoint in the current (distorted) image
  Eigen::Vector2d previous_px;  ///< its match in the previous image
  bool on_person = false;
  bool kept = false;
};

struct TrackResult {
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  FrameStats stats;
  ScreenOutcome screen;              ///< empty on the first frame
  std::vector<MatchRecord> matches;  ///< same order as screen's vectors
};

/// Marks each match kept or not from the screen's decisions and counts, against the person
/// label, what the screen kept and dropped (out.stats); both trackers end a frame with it.
void count_match_statistics(TrackResult& out);

/// Whether the frame tracker passes its match chains' outlier shares to the screen: asked for
/// (ScreenStageConfig::track_history) and a screen that reads them (hbos's gated screen with its
/// history evidence on).
[[nodiscard]] bool frame_history_wanted(const Config& config);

/// Whether the frame tracker keeps its match chains' outlier shares at all: for the screen
/// (frame_history_wanted) or for the rough pose (RoughPoseConfig::history_consensus), whatever
/// the screen, once there is one whose decisions can be remembered.
[[nodiscard]] bool frame_history_kept(const Config& config);

/// Not thread-safe; one per sequence.
class Tracker {
 public:
  /// Builds every stage from its own group of `config`; throws hbos::InvalidArgument on invalid
  /// settings.
  Tracker(const Config& config, const CameraModel& camera);

  /// Tracks one frame (frames in time order) and returns its pose in the first frame's
  /// coordinates (the first frame is the identity).
  TrackResult track(const Frame& frame);

 private:
  /// Moves the chains' outlier shares onto the current frame's keypoints (previous_history_).
  void carry_history(const std::vector<FeatureMatch>& pairs,
                     const std::vector<std::uint8_t>& inlier, bool tracked,
                     std::size_t current_size);

  OrbExtractor extractor_;
  FrameMatcher matcher_;
  RoughPoseEstimator rough_pose_;
  ResidualScreen screen_;
  LeverageGuard guard_;
  PoseRefiner refiner_;
  float scale_factor_;
  int min_matches_;
  double mask_reach_px_;      ///< [px] how far from the mask the screen's evidence reaches
  bool pass_mask_distance_;   ///< the screen sees each match's distance to the frame's mask
  double distance_reach_px_;  ///< [px] mask distances measured this far (screen and guard)
  bool keep_history_;         ///< the match chains' outlier shares are kept (frame_history_kept)
  bool pass_history_;         ///< the screen sees each match's chain's outlier share
  double forgetting_;
  JumpLimit jump_limit_;  ///< a motion beyond it is not tracked; a rough pose beyond it not used

  std::optional<Features> previous_;
  /// per keypoint of previous_ (when keep_history_): the outlier share of its match chain
  std::vector<OutlierShare> previous_history_;
  Eigen::Isometry3d T_world_previous_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d velocity_ = Eigen::Isometry3d::Identity();  ///< last T_cur_prev
};

}  // namespace hbos::slam
