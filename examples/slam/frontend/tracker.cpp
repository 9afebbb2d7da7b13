#include "frontend/tracker.hpp"

#include "frontend/mask_distance.hpp"

#include <hbos/error.hpp>
#include <hbos/screening/residual_field.hpp>
#include <hbos/screening/strategies.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace hbos::slam {

bool frame_history_wanted(const Config& config) {
  if (!config.screen.track_history || !config.screen.screen.has_value()) return false;
  const auto* hbos_screen = std::get_if<hbos::HbosScreen>(&config.screen.screen->strategy);
  return hbos_screen != nullptr && hbos_screen->gate.enabled && hbos_screen->history.enabled;
}

bool frame_history_kept(const Config& config) {
  if (!config.screen.track_history || !config.screen.screen.has_value()) return false;
  return frame_history_wanted(config) || (config.rough_pose.history_consensus &&
                                          config.rough_pose.method == RoughPoseMethod::kRansac);
}

Tracker::Tracker(const Config& config, const CameraModel& camera)
    : extractor_(config.extraction, camera),
      matcher_(config.matching),
      rough_pose_(config.rough_pose, camera.pinhole(), config.jump_limit),
      screen_(screen_stage_for(config)),
      guard_(config.guard),
      refiner_(config.refinement, camera.pinhole()),
      scale_factor_(config.extraction.scale_factor),
      min_matches_(static_cast<int>(config.screen.min_inliers)),
      mask_reach_px_(mask_evidence_reach_px(config)),
      pass_mask_distance_(mask_reach_px_ > 0.0),
      distance_reach_px_(std::max(mask_reach_px_, guard_.reach_px(config.mask.source))),
      keep_history_(frame_history_kept(config)),
      pass_history_(frame_history_wanted(config)),
      forgetting_(config.map.history.forgetting),
      jump_limit_(config.jump_limit) {
  if (!(forgetting_ >= 0.0 && forgetting_ <= 1.0))
    throw InvalidArgument("history forgetting must lie in [0, 1], got " +
                          std::to_string(forgetting_));
}

TrackResult Tracker::track(const Frame& frame) {
  TrackResult out;
  FrameStats& stats = out.stats;
  stats.index = frame.index;
  stats.stamp = frame.stamp;
  stats.mask_us = frame.mask_us;

  // 1. ORB features outside the dynamic-object mask.
  Features current = extractor_.extract(frame);
  stats.features = static_cast<int>(current.size());
  if (!previous_) {
    if (keep_history_) previous_history_.assign(current.size(), OutlierShare{});
    previous_ = std::move(current);
    stats.tracked = true;
    out.T_world_camera = T_world_previous_;
    return out;
  }
  const Features& previous = *previous_;

  // 2. Match against the previous frame's features that have depth.
  const std::vector<FeatureMatch> pairs = matcher_.match(previous, current);

  // 3. Each match: the previous keypoint back-projected to 3D, the current keypoint observing it.
  const hbos::PinholeCamerad camera = refiner_.camera();
  // One distance per match serves the screen's evidence and the guard: beyond the evidence's
  // own radius its value is 0 whatever the distance, so a longer reach changes nothing there.
  const MaskDistance to_mask(distance_reach_px_ > 0.0 ? frame.mask : cv::Mat(), distance_reach_px_);
  std::vector<double> mask_distance_px;
  MatchEvidence evidence;
  std::vector<Eigen::Vector3d> points_prev;
  std::vector<Eigen::Vector2d> observed;
  std::vector<double> sigma;
  std::vector<OutlierShare> memory;  // per match, its chain's screenings (when keep_history_)
  for (const FeatureMatch& m : pairs) {
    const auto p = static_cast<std::size_t>(m.previous), c = static_cast<std::size_t>(m.current);
    points_prev.push_back(camera.back_project(previous.undistorted[p], previous.depth_m[p]));
    observed.push_back(current.undistorted[c]);
    // ORB-SLAM's noise model: a keypoint at octave o is 1.2^o times less precise.
    sigma.push_back(hbos::sigma_from_octave(current.keypoints[c].octave, scale_factor_));
    if (distance_reach_px_ > 0.0) mask_distance_px.push_back(to_mask.at(current.keypoints[c].pt));
    if (keep_history_) memory.push_back(previous_history_[p]);
    out.matches.push_back({{current.keypoints[c].pt.x, current.keypoints[c].pt.y},
                           {previous.keypoints[p].pt.x, previous.keypoints[p].pt.y},
                           previous.on_person[p] != 0 || current.on_person[c] != 0,
                           false});
  }
  stats.matches = static_cast<int>(pairs.size());
  if (pass_mask_distance_) evidence.mask_distance_px = mask_distance_px;
  if (pass_history_) {
    evidence.outlier_history.reserve(memory.size());
    for (const OutlierShare& chain : memory) evidence.outlier_history.push_back(chain.share());
  }

  // "Tracked" is decided on the final pose, after RANSAC, the screen and the refinement: a
  // frame is tracked when at least min_matches_ screened matches reproject within ORB-SLAM2's
  // chi-square gate under the refined pose, and the motion stays within the jump limit.
  // Otherwise (too few matches, a black or featureless frame, a pose no inlier set supports, a
  // jump) the frame keeps the constant-velocity prediction:
  // its pose continues the last tracked motion, never a jump made up from noise.
  Eigen::Isometry3d T_cur_prev = velocity_;
  bool supported = false;
  if (stats.matches >= min_matches_) {
    // 4. Rough pose from the matches (PnP RANSAC; constant velocity as fallback).
    const RoughPose rough = rough_pose_.estimate(points_prev, observed, velocity_, memory);
    Eigen::Isometry3d T_candidate = rough.T_cur_prev;
    stats.rough_from_ransac = rough.from_ransac;
    stats.ransac_inliers = rough.ransac_inliers;
    stats.rough_from_remembered_statics = rough.from_remembered_statics;

    // 5. Screen the reprojection residuals under the rough pose; between rounds the pose is
    //    refined on the survivors and the residuals measured again.
    out.screen = screen_.screen(points_prev, observed, sigma, T_candidate, refiner_, evidence);
    const GuardOutcome guard = guard_.apply(points_prev, observed, sigma, mask_distance_px,
                                            T_candidate, refiner_, out.screen.inlier);
    stats.guard_ratio = guard.ratio;
    stats.guard_disagreement = guard.disagreement;
    stats.guard_shift = guard.shift_scales;
    stats.guard_bias = guard.shared_bias;
    stats.guard_dropped = guard.dropped;

    // 6. Refine the pose on the final survivors, less those near the mask when they alone would
    //    decide a direction of the pose (frontend/leverage_guard.hpp).
    Eigen::Index survivors = 0;
    for (const std::uint8_t k : out.screen.inlier) survivors += k;
    if (survivors >= min_matches_) {
      const auto start = std::chrono::steady_clock::now();
      refiner_.refine(points_prev, observed, sigma, out.screen.inlier, T_candidate);
      out.screen.refine_us +=
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
              .count();
      // The final pose's support: survivors within the gate under the refined pose.
      constexpr double kChi2Gate = 5.991;  // 95 % of chi-square with 2 dof, as ORB-SLAM2
      Eigen::Index support = 0;
      for (std::size_t i = 0; i < out.screen.inlier.size(); ++i) {
        if (out.screen.inlier[i] == 0) continue;
        const Eigen::Vector3d p = T_candidate * points_prev[i];
        if (!(p.z() > 0.0)) continue;
        const double r2 = (camera.project(p) - observed[i]).squaredNorm() / (sigma[i] * sigma[i]);
        support += r2 <= kChi2Gate ? 1 : 0;
      }
      // The rounds start from the rough pose but are not bound to it (each re-screens on what the
      // last pose kept): a motion no camera makes in a frame is not tracked, whatever it
      // reprojects.
      supported = support >= min_matches_ && T_candidate.matrix().allFinite() &&
                  !jump_limit_.exceeded_by(T_candidate);
    }
    if (supported) T_cur_prev = T_candidate;
  }
  stats.tracked = supported;

  // 7. Chain the motion onto the trajectory and keep it as the next constant-velocity guess
  //    (an untracked frame repeats the last motion, so the velocity stays as it was).
  T_world_previous_ = T_world_previous_ * T_cur_prev.inverse();
  velocity_ = T_cur_prev;
  out.T_world_camera = T_world_previous_;
  if (keep_history_) carry_history(pairs, out.screen.inlier, supported, current.size());
  previous_ = std::move(current);

  // 8. Statistics against the person label.
  count_match_statistics(out);
  return out;
}

void Tracker::carry_history(const std::vector<FeatureMatch>& pairs,
                            const std::vector<std::uint8_t>& inlier, bool tracked,
                            std::size_t current_size) {
  // Each matched keypoint continues its predecessor's chain; an unmatched one starts afresh.
  // The decision is recorded only when the frame was tracked: an untracked frame's screen
  // judged residuals under a pose nothing supports.
  std::vector<OutlierShare> current(current_size);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    OutlierShare& chain = current[static_cast<std::size_t>(pairs[i].current)];
    chain = previous_history_[static_cast<std::size_t>(pairs[i].previous)];
    if (tracked && i < inlier.size()) chain.record(inlier[i] == 0, forgetting_);
  }
  previous_history_ = std::move(current);
}

void count_match_statistics(TrackResult& out) {
  FrameStats& stats = out.stats;
  stats.threshold = out.screen.threshold;
  stats.screen_us = out.screen.screen_us;
  stats.refine_us = out.screen.refine_us;
  for (std::size_t i = 0; i < out.matches.size(); ++i) {
    MatchRecord& m = out.matches[i];
    m.kept = i < out.screen.inlier.size() && out.screen.inlier[i] != 0;
    stats.person_matches += m.on_person ? 1 : 0;
    stats.survivors += m.kept ? 1 : 0;
    stats.person_survivors += (m.on_person && m.kept) ? 1 : 0;
    stats.static_dropped += (!m.on_person && !m.kept) ? 1 : 0;
  }
}

}  // namespace hbos::slam
