#pragma once
/// \file
/// The one configuration of the mini-SLAM front end: plain defaulted fields, grouped by stage in
/// the order the tracker runs them. Each stage is constructed with its own group only.

#include "frontend/jump_limit.hpp"
#include "frontend/map/map_config.hpp"

#include <Eigen/Core>
#include <hbos/screening/strategies.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace hbos::slam {

/// Where the frames come from (a TUM RGB-D folder) and how they are paired.
struct DatasetConfig {
  std::string path;  ///< folder with rgb.txt, depth.txt and optionally groundtruth.txt
  /// A preset (`tum1`, `tum3`) or a `.yaml`/`.yml`/`.json` file with fx, fy, cx, cy [, k1, k2,
  /// p1, p2, k3, depth_factor] (ORB-SLAM2's `Camera.fx` spelling works too).
  std::string camera = "tum1";
  double max_association_difference = 0.02;  ///< [s] rgb/depth pairs need |dt| below this
  int max_frames = 0;                        ///< use only the first N frames; 0 = all
};

/// The labelled dynamic scenario: a real person cut-out composited into every frame.
struct ScenarioConfig {
  bool add_person = false;          ///< composite the person (the "dynamic" scenario)
  std::string person_dir;           ///< folder with rgb.png, mask.png, depth.png of the cut-out
  double depth_m = 0.7;             ///< [m] median depth the person is placed at
  double start_x_px = 40.0;         ///< [px] left edge of the cut-out in the first frame
  double speed_px_per_frame = 5.5;  ///< [px/frame] sideways motion in the image, + = right
  /// Ground-truth object ids per frame (0 = static), the label when no person is composited;
  /// empty: `<dataset>/objects` when that folder exists (frontend/mask_files.hpp).
  std::string objects_dir;
};

/// Which dynamic-object mask the feature extractor avoids.
enum class MaskSource {
  kNone,      ///< no mask: every pixel may give features
  kExact,     ///< the composited person's own mask (an oracle segmentation)
  kDegraded,  ///< the exact mask eroded, its lower body removed, missing every N-th frame
  kDetector,  ///< Yolo-Fastest body boxes, filled as rectangles
  kFiles,     ///< one image per frame from MaskConfig::files_dir (frontend/mask_files.hpp)
};

/// How mask files mark the dynamic pixels.
enum class MaskConvention {
  kDynaSlam,        ///< 0 = dynamic, non-zero = static (DynaSLAM's and the renderer's files)
  kNonzeroDynamic,  ///< non-zero = dynamic
};

struct MaskConfig {
  MaskSource source = MaskSource::kNone;
  int degraded_erosion_px = 6;  ///< [px] erosion radius of the degraded mask
  double degraded_unmasked_lower =
      0.4;                           ///< share of the person's height left unmasked at the bottom
  int degraded_missing_every = 5;    ///< frames 4, 9, 14, ... have no mask at all; 0 = never
  std::string detector_dir;          ///< folder with yolo-fastest-1.1_body.{cfg,weights}
  float detector_confidence = 0.5f;  ///< objectness x class score to accept a box
  float detector_nms = 0.45f;        ///< IoU of non-maximum suppression
  int detector_input_px = 320;       ///< square network input size (the model's own)
  std::string files_dir;             ///< kFiles: folder of masks, matched by file name or stamp
  MaskConvention files_convention = MaskConvention::kDynaSlam;
  double files_max_difference = 0.02;  ///< [s] stamp matching tolerance of the mask files
};

/// ORB as ORB-SLAM2 configures it (TUM yaml files).
struct ExtractionConfig {
  int features = 1000;
  float scale_factor = 1.2f;
  int levels = 8;
  int fast_threshold = 20;     ///< FAST threshold tried first
  int min_fast_threshold = 7;  ///< retried with this when the first gives too few corners
  double min_depth_m = 0.1;    ///< [m] depth below this counts as invalid
  double max_depth_m = 8.0;    ///< [m] depth above this counts as invalid (Kinect noise)
  /// [px] > 0: detect `spread_pool` times the features and keep them spread over cells of this
  /// side, per pyramid level (frontend/keypoint_spread.hpp; ORB-SLAM2 spreads its keypoints
  /// with a quadtree). 0 (the default): cv::ORB's strongest corners of the whole frame.
  float spread_cell_px = 0.f;
  int spread_pool = 3;  ///< >= 1, the pool's size in `features`
};

/// Frame-to-frame descriptor matching.
struct MatchingConfig {
  int max_hamming = 50;     ///< ORB-SLAM2's TH_LOW: descriptors further apart never match
  bool cross_check = true;  ///< keep only mutual nearest neighbours
  double ratio = 0.0;       ///< Lowe ratio best/second (e.g. 0.8); 0 = off
};

/// How the rough pose (the one the residuals are measured under) is found.
enum class RoughPoseMethod {
  kRansac,            ///< cv::solvePnPRansac on the matches (which avoid the mask)
  kConstantVelocity,  ///< the previous frame-to-frame motion repeated
};

struct RoughPoseConfig {
  RoughPoseMethod method = RoughPoseMethod::kRansac;
  /// [px] inlier threshold of the consensus: tight (near the 0.6 px level-0 keypoint noise) so
  /// that a moving person cannot join it (FINDINGS.md point 4; measured in docs/slam_demo.md)
  double ransac_threshold_px = 1.0;
  int ransac_iterations = 300;
  double ransac_confidence = 0.999;
  int min_inliers = 12;  ///< fewer RANSAC inliers: fall back to constant velocity
  /// With the tracks' outlier memory (the frame tracker's --track-history): when RANSAC's
  /// consensus holds matches whose tracks the screen mostly rejected before, RANSAC runs again
  /// on the matches whose tracks it screened and mostly kept, and the pose with the larger
  /// remembered support (each inlier over all matches weighted by its track's static trust,
  /// OutlierShare::static_trust) is taken. A person holding a fifth of the matches can otherwise
  /// win the consensus (docs/results.md, stops 26 and 27).
  bool history_consensus = true;
  /// [0, 1] a track is "mostly rejected" above this outlier share
  double history_rejected_share = 0.5;
  /// the second RANSAC runs only when at least this share of the consensus is mostly rejected
  double history_trigger_share = 0.1;
  /// cv::solvePnPRansac returns its inliers' refit; with this, a refit that no longer holds half
  /// of those inliers within the threshold is no consensus and the fallback is taken
  /// (docs/results.md, "A frame-to-frame pose that jumped 5 m").
  bool check_refit = true;
};

/// The residual screen (hbos's reprojection screen or a baseline).
struct ScreenStageConfig {
  /// hbos's screen: a strategy with its settings (hbos/screening/strategies.hpp); nullopt = no
  /// screen (the pose is refined on every match). Set by name with select().
  std::optional<hbos::ScreenConfig> screen = hbos::ScreenConfig{};
  std::string name = "default";   ///< the name it was selected by, for tables and logs
  int rounds = 4;                 ///< screen -> refine -> re-screen rounds (ORB-SLAM2 runs 4)
  Eigen::Index min_inliers = 10;  ///< stop re-fitting below this many survivors
  /// pass each match's distance to the frame's dynamic-object mask to the screen (the mask's
  /// neighbourhood evidence of hbos's default; the baselines ignore it); only with a mask.
  /// On: it lowered the default's ATE with leaky masks and changed nothing elsewhere
  /// (docs/slam_demo.md, "The mask's neighbourhood").
  bool mask_evidence = true;
  /// The frame tracker follows each keypoint along its chain of frame-to-frame matches and
  /// passes the chain's outlier share (frontend/outlier_share.hpp) to the screen: the default's
  /// persistence evidence. The map tracker keeps its own per map point (MapConfig::history);
  /// both forget at MapConfig::history.forgetting.
  /// On: it lowered the default's ATE on the semi-real paths without a mask or with a leaky one
  /// and in the rendered benchmark, at 1-3 points of statics (docs/slam_demo.md, "The match
  /// chains' memory").
  bool track_history = true;
  /// The map tracker passes its new points on probation as flagged matches (kept out of the
  /// screen's fit). With this, a flagged match's coherence is taken over its flagged neighbours
  /// too (hbos::CoherenceEvidence::flagged_consensus): a group of new points on a person, each
  /// inside the noise gate, is caught by moving together. The frame tracker flags nothing.
  /// On: measured in docs/results.md ("New points vouch for each other", stop 35).
  bool provisional_consensus = true;
  /// [px/sigma] the default screen's noise-gate floor (hbos::NoiseGate::floor) in the rounds
  /// after the first; 0 = the screen's own floor in every round; unset = the tracker's own
  /// (later_rounds_gate_floor(const Config&)). The first round judges the matches under the
  /// rough pose, whose error the residual field may not absorb: there the floor stays at
  /// chi^2's 2.447, so a static match is lost no more often than chi^2 loses it. The later
  /// rounds judge them under a pose refined on that round's survivors, where the gate can follow
  /// the noise the frame has (3 noise scales) down to this floor. Only strategies with a noise
  /// gate use it.
  std::optional<double> later_rounds_gate_floor;
  /// The default screen refits its residual field as the pixel shift of a small rigid motion
  /// (hbos::RefitModel::Rigid, with the tracker's camera and the points' depths) in the rounds
  /// after the first, instead of an affine field; unset = on, for both trackers
  /// (later_rounds_rigid_field(const Config&)). After a refinement on the survivors, an affine
  /// field on real frames fits structure no pose error gives, and centring it away keeps the
  /// matches the rigid refinement cannot agree with.
  std::optional<bool> later_rounds_rigid_field;

  /// Selects a strategy of hbos::named_strategies() by name, or "none".
  /// \throws hbos::InvalidArgument naming the value and the choices.
  void select(const std::string& strategy_name);
};

/// The mask neighbourhood's leverage guard (frontend/leverage_guard.hpp), run on the screen's
/// survivors before the final refinement, with any screen. When every static match is far away,
/// a rotation and a translation move them alike; a few near matches just outside the mask (a
/// person's rim the segmenter missed) then decide the pose alone. Such matches are dropped when
/// the other survivors, left to themselves, put them off. Measured in docs/results.md ("The mask
/// neighbourhood's leverage").
struct LeverageGuardConfig {
  bool enabled = true;
  /// [px] matches within this distance of the frame's dynamic-object mask form the group (the
  /// default screen's mask-neighbourhood radius)
  double radius_px = 10.0;
  /// The group is dropped when, along some direction of the pose, its Gauss-Newton information
  /// exceeds this multiple of all other survivors' (hbos::group_leverage's ratio). 1: the group
  /// alone outweighs everything else there.
  double max_ratio = 1.0;
  /// ... and only when the group disagrees with the pose the other survivors give alone
  /// (hbos::group_consistency's shift_chi2 for the group's mean residual, at the noise those
  /// survivors show, above its quantile at this one-sided normal z): a decisive group that agrees
  /// with them (static points along the mask's edge) is kept. 3.09: a static group is dropped in
  /// about 1 of 1000 frames where it is decisive.
  double consistency_z = 3.09;
  /// [px] cells in which the offset static neighbours share is measured on the other
  /// survivors, per frame (frontend/shared_bias.hpp), and added to the noise the shift test
  /// expects. Real frames have one (depth and timing errors move neighbours alike); without it a
  /// large enough static group makes any shared offset significant. Rendered frames have none,
  /// so a fixed allowance would blunt the guard there. Measured in docs/results.md ("A static
  /// group's shared offset"). 0: assume independent noise.
  double bias_cell_px = 80.0;
};

/// Gauss-Newton pose refinement on the survivors (hbos/screening/pose_refinement.hpp).
struct RefinementConfig {
  int max_iterations = 10;     ///< per call (ORB-SLAM2: 10 per round)
  double huber_delta = 2.447;  ///< [px/sigma] sqrt(5.991), ORB-SLAM2's Huber width
  /// Scale the Huber width by the noise the refined matches have (frontend/pose_refiner.hpp):
  /// huber_delta times their noise scale, clamped to [min_noise_scale, 1].
  bool huber_from_noise = false;
  /// [px/sigma] the narrowest noise scale: two keypoints rounded to the pixel grid differ by
  /// 1/sqrt(6) per axis, the screen's own floor for the same reason
  double min_noise_scale = hbos::NoiseGate{}.min_scale;
};

/// What is written, and where.
struct OutputConfig {
  std::string dir = "out/slam";
  int figure_frame = -1;  ///< frame drawn in the figures; -1 = the one with most person matches
  bool progress = true;   ///< a progress line per frame on stderr
};

/// Which tracker runs (`--tracker`).
enum class TrackerKind {
  kFrame,  ///< frame-to-frame odometry (frontend/tracker.hpp)
  kMap,    ///< tracking against a local map of keyframes (frontend/map/map_tracker.hpp)
};

/// Everything the front end needs, one group per stage.
struct Config {
  TrackerKind tracker = TrackerKind::kFrame;
  DatasetConfig dataset;
  ScenarioConfig scenario;
  MaskConfig mask;
  ExtractionConfig extraction;
  MatchingConfig matching;
  RoughPoseConfig rough_pose;
  ScreenStageConfig screen;
  LeverageGuardConfig guard;
  RefinementConfig refinement;
  JumpLimit jump_limit;  ///< both trackers: a pose step beyond it is a failure, not motion
  MapConfig map;         ///< the map tracker's own stages (frontend/map/map_config.hpp)
  OutputConfig output;
};

/// The noise gate's floor [px/sigma] in the screening rounds after the first: the one set
/// (ScreenStageConfig::later_rounds_gate_floor), or the tracker's own. The frame tracker's is
/// 3 x the default NoiseGate::min_scale, the least 3 noise scales can be: no floor of its own.
/// The map tracker's is 0, chi^2's floor in every round: a lower floor after the first round
/// lowered its ATE on most rendered runs but let the pose follow an unmasked person filling most
/// of the view (docs/results.md, "The noise gate after the first refinement", has the
/// measurements).
[[nodiscard]] double later_rounds_gate_floor(const Config& config);
/// Whether the default screen refits a rigid field in the rounds after the first: the setting
/// (ScreenStageConfig::later_rounds_rigid_field), or on. Measured through both trackers in
/// docs/results.md ("A field only a camera motion can give"); each adopted by a rule written
/// before its held-out run.
[[nodiscard]] bool later_rounds_rigid_field(const Config& config);
/// config.screen with later_rounds_gate_floor and later_rounds_rigid_field set to the values
/// above: what a tracker screens with.
[[nodiscard]] ScreenStageConfig screen_stage_for(const Config& config);

/// `none`, `exact`, `degraded`, `detector`.
[[nodiscard]] const char* to_string(MaskSource source);
/// Inverse of to_string; throws hbos::InvalidArgument naming the value and the choices.
[[nodiscard]] MaskSource parse_mask_source(const std::string& name);
/// The guard's settings as one object (run summaries and cache keys), or `false` when off.
[[nodiscard]] nlohmann::json to_json(const LeverageGuardConfig& guard);
/// The limit as one object (run summaries and cache keys).
[[nodiscard]] nlohmann::json to_json(const JumpLimit& limit);
/// The map tracker's per-point noise as one object (run summaries and cache keys), or `false`
/// when off.
[[nodiscard]] nlohmann::json to_json(const PointNoiseConfig& noise);
/// The map tracker's residual history as screen evidence, or `false` when off.
[[nodiscard]] nlohmann::json to_json(const NoiseHistoryConfig& history);
/// `ransac`, `constant-velocity`.
[[nodiscard]] const char* to_string(RoughPoseMethod method);
[[nodiscard]] RoughPoseMethod parse_rough_pose_method(const std::string& name);
/// `frame`, `map`.
[[nodiscard]] inline const char* to_string(TrackerKind kind) {
  return kind == TrackerKind::kMap ? "map" : "frame";
}

}  // namespace hbos::slam
