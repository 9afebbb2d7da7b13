#pragma once
/// \file
/// The map tracker (`hbos-slam --tracker map`): ORB-SLAM2's RGB-D tracking against a local map,
/// with the HBOS method's screen where the paper puts it. `MapTracker::track` is the algorithm:
/// mask -> ORB -> lightweight tracking (constant velocity + last frame by projection; the
/// reference keyframe by descriptor when that fails; relocalisation when lost) -> rough pose ->
/// local map by projection -> reproject -> screen -> optimise on the survivors -> screening
/// history and culling -> keyframe decision. It returns the frame tracker's TrackResult, so the
/// outputs, figures and evaluation are shared.

#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/frame.hpp"
#include "frontend/leverage_guard.hpp"
#include "frontend/map/keyframe_policy.hpp"
#include "frontend/map/map.hpp"
#include "frontend/map/projection_matcher.hpp"
#include "frontend/map/relocaliser.hpp"
#include "frontend/orb_extraction.hpp"
#include "frontend/pose_refiner.hpp"
#include "frontend/residual_screen.hpp"
#include "frontend/rough_pose.hpp"
#include "frontend/tracker.hpp"

#include <Eigen/Geometry>

#include <optional>
#include <unordered_map>
#include <vector>

namespace hbos::slam {

/// How a frame's pose was found.
enum class TrackSource {
  kInitialised,  ///< the first keyframe: the world frame
  kMotion,       ///< constant-velocity prediction, matched into the last frame
  kKeyframe,     ///< descriptor matching against the reference keyframe
  kRelocalised,  ///< PnP RANSAC against a recent keyframe after being lost
  kLost,         ///< no pose: too few matches or inliers, or a jump
};
[[nodiscard]] const char* to_string(TrackSource source);

/// What the map tracker measured on one frame, beyond FrameStats. Times in microseconds.
struct MapFrameReport {
  double extract_us = 0.0;    ///< [us] ORB extraction (with undistortion and depth look-up)
  double tracking_us = 0.0;   ///< [us] lightweight tracking or relocalisation
  double rough_us = 0.0;      ///< [us] rough pose (PnP RANSAC)
  double local_map_us = 0.0;  ///< [us] local-map selection and projection matching
  double screen_us = 0.0;     ///< [us] the screen, refinement rounds excluded
  double refine_us = 0.0;     ///< [us] pose refinement (between rounds and final)
  double map_us = 0.0;        ///< [us] screening history, culling, keyframe insertion
  double bundle_us = 0.0;     ///< [us] of which the local bundle adjustment of a new keyframe
  int bundle_outliers = 0;    ///< observations the adjustment erased; -1: it was discarded
  TrackSource source = TrackSource::kLost;
  int last_frame_matches = 0;  ///< matches from lightweight tracking
  int local_map_matches = 0;   ///< matches added from the local map
  int culled_now = 0;          ///< points culled on this frame
  bool keyframe_inserted = false;
  int keyframes = 0;      ///< in the map after this frame
  int live_points = 0;    ///< map points not culled
  int culled_points = 0;  ///< culled so far
};

/// Not thread-safe; one per sequence.
class MapTracker {
 public:
  /// Builds every stage from its group of `config` (config.map for the map's own stages);
  /// throws hbos::InvalidArgument on invalid settings.
  MapTracker(const Config& config, const CameraModel& camera);

  /// Tracks one frame (in time order). A lost frame has `stats.tracked == false` and a NaN
  /// pose: it has none (the trajectory writer skips it).
  TrackResult track(const Frame& frame);

  [[nodiscard]] const MapFrameReport& last_report() const { return report_; }
  [[nodiscard]] const Map& map() const { return map_; }

 private:
  struct Matched;  // the frame's matches as the screen takes them
  enum class State { kNotInitialised, kTracking, kLost };

  TrackResult initialise(const Frame& frame, Features current, TrackResult out);
  Eigen::Isometry3d lightweight_tracking(const Frame& frame, const Features& current,
                                         const KeypointGrid& grid, std::vector<int>& point_of);
  /// Enough matched points are out of probation (HistoryConfig) for them alone to decide the
  /// pose; the others are then provisional.
  [[nodiscard]] bool enough_proven(const std::vector<int>& point_of) const;
  Eigen::Isometry3d rough_pose(const Features& current, const std::vector<int>& point_of,
                               const Eigen::Isometry3d& guess, FrameStats& stats) const;
  void match_local_map(const Frame& frame, const Features& current, const KeypointGrid& grid,
                       const Eigen::Isometry3d& T_camera_world, std::vector<int>& point_of);
  Matched gather(const Frame& frame, const Features& current, const std::vector<int>& point_of,
                 TrackResult& out) const;
  void refine_on_survivors(const Matched& m, ScreenOutcome& screen, Eigen::Isometry3d& T) const;
  /// The sigmas the final refinement uses: the octave's, widened where a point's own noise
  /// (PointNoiseConfig) stands out from the frame's refined points.
  [[nodiscard]] std::vector<double> refinement_sigma(const Matched& m,
                                                     const std::vector<std::uint8_t>& use) const;
  /// Each match's squared whitened residual under the final pose: a survivor's into its point's
  /// noise (PointNoiseConfig), every screened match's into its screened noise
  /// (NoiseHistoryConfig), as each is enabled.
  void record_point_noise(const Matched& m, const ScreenOutcome& screen,
                          const Eigen::Isometry3d& T_camera_world);
  void update_history(const Matched& m, const ScreenOutcome& screen, std::vector<int>& point_of);
  void finish(const Frame& frame, Features current, const std::vector<int>& point_of,
              const Eigen::Isometry3d& T_camera_world, TrackResult& out);
  void lose(TrackResult& out);
  void insert_keyframe(const Frame& frame, Features current, const std::vector<int>& point_of,
                       const Eigen::Isometry3d& T_camera_world);
  /// Local bundle adjustment around the keyframe just inserted (local_mapping.hpp).
  void adjust_around_new_keyframe();

  Config config_;
  OrbExtractor extractor_;
  RoughPoseEstimator rough_pose_;
  ResidualScreen screen_;
  LeverageGuard guard_;
  PoseRefiner refiner_;
  ProjectionMatcher matcher_;
  Relocaliser relocaliser_;
  Map map_;
  std::optional<ImageBounds> bounds_;  ///< the undistorted image, from the first frame's size
  CameraModel camera_;

  State state_ = State::kNotInitialised;
  MapFrameReport report_;
  int reference_keyframe_ = -1;
  int last_keyframe_frame_ = 0;
  int last_relocalisation_frame_ = -(1 << 20);
  // The last frame: its keypoints, the map points its inliers observe, its pose.
  std::vector<cv::KeyPoint> last_keypoints_;
  std::vector<int> last_point_of_;
  std::unordered_map<int, cv::Point2f> last_pixel_of_point_;  ///< for the match figure
  Eigen::Isometry3d last_T_camera_world_ = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> velocity_;  ///< T_cur_last of the last tracked pair
};

}  // namespace hbos::slam
