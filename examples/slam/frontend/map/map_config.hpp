#pragma once
/// \file
/// Settings of the map tracker (`hbos-slam --tracker map`), one group per stage, with
/// ORB-SLAM2's values (Tracking.cc, ORBmatcher.cc, MapPoint.cc) as defaults where it has one.
/// The stages shared with the frame tracker (ORB, rough pose, screen, refinement) keep their own
/// groups in frontend/config.hpp.

#include "frontend/map/noise_history.hpp"
#include "frontend/map/point_noise.hpp"

#include <limits>

namespace hbos::slam {

/// Projection matching (ORBmatcher::SearchByProjection).
struct ProjectionMatchConfig {
  int max_hamming = 100;            ///< [bits] ORB-SLAM2's TH_HIGH for projection searches
  int max_hamming_descriptor = 50;  ///< [bits] TH_LOW, for descriptor-only (keyframe) matching
  float ratio = 0.8f;               ///< best / second best, when both lie on the same level
  /// [px at level 0] last-frame search radius, times 1.2^octave (ORB-SLAM2 RGB-D: 15)
  float last_frame_radius_px = 15.f;
  /// [px at level 0] local-map search radius, times 1.2^predicted octave and the viewing-angle
  /// factor (2.5 head-on, else 4; ORB-SLAM2: th = 1, 5 right after relocalisation)
  float local_map_radius_px = 1.f;
  float relocalised_radius_px = 5.f;
  bool check_orientation = true;    ///< rotation-consistency histogram (30 bins, top 3 kept)
  int min_last_frame_matches = 20;  ///< below: retry with twice the radius, then the keyframe
  int min_reference_matches = 15;   ///< below: the reference keyframe cannot track either
};

/// The local map (Tracking::UpdateLocalKeyFrames).
struct LocalMapConfig {
  int max_keyframes = 20;  ///< [keyframes] cap (ORB-SLAM2: 80); the most sharing come first
  int neighbours = 5;      ///< [keyframes] best covisible neighbours added per local keyframe
  float viewing_cos_limit = 0.5f;  ///< a point seen more than 60 deg off its mean view is skipped
};

/// Keyframe insertion (Tracking::NeedNewKeyFrame, RGB-D branch).
struct KeyframeConfig {
  int max_frames = 30;            ///< [frames] insert at the latest after this many (fps)
  int min_frames = 0;             ///< [frames] insert at the earliest after this many
  float reference_ratio = 0.75f;  ///< tracked below this share of the reference's points: insert
  int min_tracked = 15;           ///< never insert with this few tracked points or fewer
  float close_depth_m = 3.0f;     ///< [m] "close" points (ORB-SLAM2: bf * ThDepth / fx = 3.0 m)
  int tracked_close_min = 100;    ///< fewer tracked close points than this, and
  int untracked_close_min = 70;   ///< more close points without a map point: insert
  int min_new_points = 100;       ///< new points: all closer than close_depth_m, at least this many
  /// New points beyond close_depth_m besides the near ones, nearest first; default: all of them.
  /// ORB-SLAM2 makes none here and gets the room's far points later, when its local mapping
  /// thread triangulates them between keyframes; this tracker has no such thread, so depth is
  /// their only source. Without them a person the mask misses, nearer than the room, made every
  /// new point, and the pose rested on near points alone, which pin rotation and sideways motion
  /// poorly (docs/results.md, "A missed person and the map tracker's new points" and "The room's
  /// far points").
  int max_far_points = std::numeric_limits<int>::max();
  int init_min_features = 500;  ///< the first keyframe needs this many keypoints (ORB-SLAM2: 500)
};

/// Tracking success and relocalisation (Tracking::Relocalization).
struct RelocalisationConfig {
  int min_inliers = 30;                ///< tracked when this many survive (ORB-SLAM2: 30)
  int min_inliers_relocalised = 50;    ///< ... in the frames right after relocalisation (50)
  int recent_keyframes = 8;            ///< candidates: the most recent keyframes
  int min_matches = 15;                ///< descriptor matches a candidate needs for PnP
  float ratio = 0.75f;                 ///< Lowe ratio of those matches (ORB-SLAM2: 0.75)
  double ransac_threshold_px = 2.447;  ///< [px at level 0] sqrt(5.991), ORB-SLAM2's PnP gate
  int ransac_iterations = 300;
  int min_pnp_inliers = 20;  ///< PnP inliers to try the pose against the local map
  /// A RANSAC pose whose refit no longer holds half of its inliers within the threshold is
  /// refused, as the rough pose's (RoughPoseConfig::check_refit; frontend/pnp_pose.hpp).
  bool check_refit = true;
};

/// The screen's memory per map point (see screening_history.hpp).
struct HistoryConfig {
  double forgetting = 0.8;      ///< weight of the past per screening (half-life ~3 screenings)
  int cull_consecutive = 3;     ///< culled after this many rejections in a row
  double cull_share = 0.75;     ///< or with this forgotten outlier share ...
  int cull_min_screenings = 4;  ///< ... after at least this many screenings
  /// points with a larger share (screened at least twice) are kept out of the rough pose
  double rough_pose_max_share = 0.5;
  /// A new point decides the pose (rough pose, refinement) only once the screen has kept it
  /// this many times; until then it is screened against the pose its elders give. 0: at once
  /// (ORB-SLAM2). Measured in docs/results.md ("A missed person and the map tracker's new points").
  int probation_kept = 2;
  /// Fewer matched points out of probation than this, and every match decides: a view the map
  /// has just reached would otherwise have no pose (ORB-SLAM2's 30 inliers to be tracked).
  int min_proven_matches = 30;
};

/// Local bundle adjustment after each new keyframe (LocalMapping::Run's
/// Optimizer::LocalBundleAdjustment, run in the tracking thread here; local_mapping.hpp).
struct LocalBundleConfig {
  /// Off by default: on 60 rendered runs it lowered the ATE on 31 and raised it on 24, two of
  /// them to 3-5 cm (docs/map_tracking.md, "Local bundle adjustment").
  bool enabled = false;
  /// [keyframes] the new keyframe and its most covisible neighbours that move (ORB-SLAM2: every
  /// covisible keyframe); the others observing their points are held fixed
  int max_keyframes = 10;
  int iterations = 10;  ///< Levenberg-Marquardt iterations per pass (ORB-SLAM2: 5, then 10)
  /// [px m] the virtual stereo baseline times fx that turns depth into disparity (ORB-SLAM2's
  /// Camera.bf for the TUM Kinects: 40)
  double baseline_fx = 40.0;
  /// [px] the disparity's noise: a Kinect's is about a tenth of a pixel whatever the keypoint's
  /// level (with bf = 40, sigma_z = z^2 / 400: 2.5 mm at 1 m, 2.3 cm at 3 m, near Nguyen et al.
  /// 2012's measurement). ORB-SLAM2 uses the keypoint's sigma, 1.2^octave px, which trusts depth
  /// ten times less in standard deviation, and multi-view pixels then outweigh it: points were
  /// moved off their depth and tracking got worse (docs/map_tracking.md). 0: ORB-SLAM2's.
  double disparity_sigma_px = 0.1;
  /// [m], [deg] an adjustment that would move a keyframe further is discarded (the tracker
  /// placed it within millimetres; a larger move is a different minimum, not a better map)
  double max_shift_m = 0.02;
  double max_shift_deg = 1.0;
};

struct MapConfig {
  /// PnP RANSAC iterations of the map tracker's rough pose (the frame tracker's rough_pose group
  /// gives every other setting): the matches come from a constant-velocity search, so a smaller
  /// budget suffices, and when it fails the prediction is the rough pose (measured in
  /// docs/benchmarks.md)
  int rough_pose_iterations = 100;
  ProjectionMatchConfig projection;
  LocalMapConfig local_map;
  KeyframeConfig keyframes;
  RelocalisationConfig relocalisation;
  HistoryConfig history;
  LocalBundleConfig local_bundle;
  PointNoiseConfig point_noise;
  NoiseHistoryConfig noise_history;
};

}  // namespace hbos::slam
