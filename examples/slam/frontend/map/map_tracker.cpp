#include "frontend/map/map_tracker.hpp"

#include "frontend/map/local_mapping.hpp"
#include "frontend/map/noise_history.hpp"
#include "frontend/mask_distance.hpp"

#include <hbos/screening/residual_field.hpp>
#include "common/index.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace hbos::slam {

namespace {

using examples::at;

using Clock = std::chrono::steady_clock;

/// Time since the last lap [us].
class Stopwatch {
 public:
  double lap() {
    const Clock::time_point now = Clock::now();
    const double us = std::chrono::duration<double, std::micro>(now - start_).count();
    start_ = now;
    return us;
  }

 private:
  Clock::time_point start_ = Clock::now();
};

// ORB-SLAM2's ComputeImageBounds: the undistorted image's extent from its corners.
ImageBounds undistorted_bounds(const CameraModel& camera, int cols, int rows) {
  const auto w = static_cast<float>(cols), h = static_cast<float>(rows);
  const std::vector<cv::Point2f> corners =
      undistort_pixels(camera, {{0.f, 0.f}, {w, 0.f}, {0.f, h}, {w, h}});
  ImageBounds b;
  b.min_x = std::min(corners[0].x, corners[2].x);
  b.max_x = std::max(corners[1].x, corners[3].x);
  b.min_y = std::min(corners[0].y, corners[1].y);
  b.max_y = std::max(corners[2].y, corners[3].y);
  return b;
}

Eigen::Isometry3d no_pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.matrix().setConstant(std::numeric_limits<double>::quiet_NaN());
  return T;
}

RoughPoseConfig map_rough_pose(const Config& config) {
  RoughPoseConfig c = config.rough_pose;
  c.ransac_iterations = config.map.rough_pose_iterations;
  return c;
}

}  // namespace

const char* to_string(TrackSource source) {
  switch (source) {
    case TrackSource::kInitialised:
      return "initialised";
    case TrackSource::kMotion:
      return "motion";
    case TrackSource::kKeyframe:
      return "keyframe";
    case TrackSource::kRelocalised:
      return "relocalised";
    case TrackSource::kLost:
      return "lost";
  }
  return "?";
}

struct MapTracker::Matched {
  std::vector<int> keypoint;  ///< current keypoint of match i
  std::vector<int> point;     ///< map point of match i
  std::vector<Eigen::Vector3d> points_world;
  std::vector<Eigen::Vector2d> observed;
  std::vector<double> sigma;
  MatchEvidence evidence;
  std::vector<double> mask_distance_px;  ///< for the leverage guard; empty: not measured
};

MapTracker::MapTracker(const Config& config, const CameraModel& camera)
    : config_(config),
      extractor_(config.extraction, camera),
      rough_pose_(map_rough_pose(config), camera.pinhole(), config.jump_limit),
      screen_(screen_stage_for(config)),
      guard_(config.guard),
      refiner_(config.refinement, camera.pinhole()),
      matcher_(config.map.projection, camera.pinhole(), config.extraction.scale_factor,
               config.extraction.levels),
      relocaliser_(config.map.relocalisation, camera.pinhole()),
      map_(config.extraction.scale_factor, config.extraction.levels),
      camera_(camera) {}

TrackResult MapTracker::track(const Frame& frame) {
  TrackResult out;
  out.stats.index = frame.index;
  out.stats.stamp = frame.stamp;
  out.stats.mask_us = frame.mask_us;
  report_ = MapFrameReport{};
  Stopwatch clock;
  if (!bounds_) bounds_ = undistorted_bounds(camera_, frame.bgr.cols, frame.bgr.rows);

  // 1. Mask: the frame source computed frame.mask (timed in mask_us); ORB avoids it.
  // 2. ORB features outside the mask.
  Features current = extractor_.extract(frame);
  out.stats.features = static_cast<int>(current.size());
  report_.extract_us = clock.lap();
  if (state_ == State::kNotInitialised) return initialise(frame, std::move(current), out);
  const KeypointGrid grid(current, *bounds_);
  std::vector<int> point_of(current.size(), -1);  // current keypoint -> map point

  // 3. Lightweight tracking: constant velocity + the last frame by projection; the reference
  //    keyframe by descriptor when that fails; relocalisation against recent keyframes when lost.
  Eigen::Isometry3d T_camera_world = lightweight_tracking(frame, current, grid, point_of);
  report_.tracking_us = clock.lap();
  if (report_.source == TrackSource::kLost) {
    lose(out);
    return out;
  }
  // 4. Rough pose: PnP RANSAC on those matches, without the points the screen distrusts, and
  //    without new points still on probation while enough others are out of it.
  T_camera_world = rough_pose(current, point_of, T_camera_world, out.stats);
  report_.rough_us = clock.lap();

  // 5. Local map: the keyframes sharing points with this frame and their neighbours; their
  //    points matched by projection under the rough pose.
  match_local_map(frame, current, grid, T_camera_world, point_of);
  report_.local_map_us = clock.lap();

  // 6. Reproject every match under the rough pose and screen the residuals (the rounds refine
  //    the pose on the survivors out of probation), with each point's screening history as
  //    evidence.
  const Matched m = gather(frame, current, point_of, out);
  out.screen =
      screen_.screen(m.points_world, m.observed, m.sigma, T_camera_world, refiner_, m.evidence);
  // 7. Optimise the pose on the survivors out of probation (Huber), less those near the mask
  //    when they alone would decide a direction of the pose (frontend/leverage_guard.hpp).
  const GuardOutcome guard = guard_.apply(m.points_world, m.observed, m.sigma, m.mask_distance_px,
                                          T_camera_world, refiner_, out.screen.inlier);
  out.stats.guard_ratio = guard.ratio;
  out.stats.guard_disagreement = guard.disagreement;
  out.stats.guard_shift = guard.shift_scales;
  out.stats.guard_bias = guard.shared_bias;
  out.stats.guard_dropped = guard.dropped;
  refine_on_survivors(m, out.screen, T_camera_world);
  report_.screen_us = out.screen.screen_us;
  report_.refine_us = out.screen.refine_us;
  clock.lap();

  // 8. Screening history: every screened point remembers the verdict; points screened out
  //    again and again are culled.
  if (config_.map.point_noise.enabled || config_.map.noise_history.enabled)
    record_point_noise(m, out.screen, T_camera_world);
  update_history(m, out.screen, point_of);

  // 9. Tracked or lost, the keyframe decision, and this frame as the next one's last frame.
  finish(frame, std::move(current), point_of, T_camera_world, out);
  report_.map_us = clock.lap();
  return out;
}

TrackResult MapTracker::initialise(const Frame& frame, Features current, TrackResult out) {
  int with_depth = 0;
  for (const float d : current.depth_m) with_depth += d > 0.f ? 1 : 0;
  if (with_depth < config_.map.keyframes.init_min_features) {
    lose(out);  // not enough structure for a first keyframe: no pose yet
    return out;
  }
  Stopwatch clock;
  insert_keyframe(frame, std::move(current), {}, Eigen::Isometry3d::Identity());
  state_ = State::kTracking;
  report_.source = TrackSource::kInitialised;
  out.stats.tracked = true;
  out.T_world_camera = Eigen::Isometry3d::Identity();
  report_.map_us = clock.lap();
  report_.keyframes = map_.keyframes();
  report_.live_points = map_.live_points();
  return out;
}

Eigen::Isometry3d MapTracker::lightweight_tracking(const Frame& frame, const Features& current,
                                                   const KeypointGrid& grid,
                                                   std::vector<int>& point_of) {
  const ProjectionMatchConfig& c = config_.map.projection;
  const auto count = [&] {
    return static_cast<int>(
        std::count_if(point_of.begin(), point_of.end(), [](int p) { return p >= 0; }));
  };
  if (state_ == State::kLost) {
    const Relocalisation r = relocaliser_.relocalise(map_, matcher_, current, point_of);
    report_.source = r.found ? TrackSource::kRelocalised : TrackSource::kLost;
    report_.last_frame_matches = count();
    if (r.found) {
      last_relocalisation_frame_ = frame.index;
      reference_keyframe_ = r.keyframe;
    }
    return r.T_camera_world;
  }
  const Eigen::Isometry3d predicted =
      velocity_ ? *velocity_ * last_T_camera_world_ : last_T_camera_world_;
  for (const float scale : {1.f, 2.f}) {
    std::fill(point_of.begin(), point_of.end(), -1);
    matcher_.match_last_frame(map_, last_keypoints_, last_point_of_, predicted, current, grid,
                              *bounds_, scale, point_of);
    if (count() >= c.min_last_frame_matches) {
      report_.source = TrackSource::kMotion;
      report_.last_frame_matches = count();
      return predicted;
    }
  }
  std::fill(point_of.begin(), point_of.end(), -1);
  if (reference_keyframe_ >= 0) {
    matcher_.match_keyframe(map_, map_.keyframe(reference_keyframe_), current, 0.7f, point_of);
  }
  report_.last_frame_matches = count();
  report_.source = count() >= c.min_reference_matches ? TrackSource::kKeyframe : TrackSource::kLost;
  return last_T_camera_world_;
}

bool MapTracker::enough_proven(const std::vector<int>& point_of) const {
  const HistoryConfig& h = config_.map.history;
  if (h.probation_kept <= 0) return false;
  int proven = 0;
  for (const int id : point_of) proven += (id >= 0 && map_.point(id).history.proven(h)) ? 1 : 0;
  return proven >= h.min_proven_matches;
}

Eigen::Isometry3d MapTracker::rough_pose(const Features& current, const std::vector<int>& point_of,
                                         const Eigen::Isometry3d& guess, FrameStats& stats) const {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> observed;
  const HistoryConfig& h = config_.map.history;
  const bool on_probation = enough_proven(point_of);
  for (std::size_t k = 0; k < point_of.size(); ++k) {
    if (point_of[k] < 0) continue;
    const MapPoint& p = map_.point(point_of[k]);
    if (p.history.distrusted(h)) continue;  // never builds the rough pose
    if (on_probation && !p.history.proven(h)) continue;
    points.push_back(p.position_world);
    observed.push_back(current.undistorted[k]);
  }
  // A consensus beyond the jump limit from the prediction is refused there (rough_pose.hpp).
  const RoughPose rough = rough_pose_.estimate(points, observed, guess);
  if (!rough.from_ransac) return guess;
  stats.rough_from_ransac = true;
  stats.ransac_inliers = rough.ransac_inliers;
  return rough.T_cur_prev;  // here: world -> current camera
}

void MapTracker::match_local_map(const Frame& frame, const Features& current,
                                 const KeypointGrid& grid, const Eigen::Isometry3d& T_camera_world,
                                 std::vector<int>& point_of) {
  std::vector<int> matched;
  for (const int p : point_of) {
    if (p >= 0) matched.push_back(p);
  }
  int reference = -1;
  const std::vector<int> keyframes =
      map_.local_keyframes(matched, config_.map.local_map, reference);
  if (reference >= 0) reference_keyframe_ = reference;
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(map_.points_created()), 0);
  for (const int p : matched) taken[at(p)] = 1;
  std::vector<int> candidates;
  for (const int p : map_.local_points(keyframes)) {
    if (taken[at(p)] == 0) candidates.push_back(p);
  }
  // A wider search right after relocalisation, whose pose is coarser (ORB-SLAM2: th 5).
  const bool relocalised = frame.index < last_relocalisation_frame_ + 2;
  const ProjectionMatchConfig& c = config_.map.projection;
  report_.local_map_matches =
      matcher_.match_local_map(map_, candidates, T_camera_world, current, grid, *bounds_,
                               relocalised ? c.relocalised_radius_px : c.local_map_radius_px,
                               config_.map.local_map.viewing_cos_limit, point_of);
}

MapTracker::Matched MapTracker::gather(const Frame& frame, const Features& current,
                                       const std::vector<int>& point_of, TrackResult& out) const {
  Matched m;
  // One distance per match serves the screen's evidence and the guard: beyond the evidence's
  // own radius its value is 0 whatever the distance, so a longer reach changes nothing there.
  const double evidence_reach_px = mask_evidence_reach_px(config_);
  const double reach_px = std::max(evidence_reach_px, guard_.reach_px(config_.mask.source));
  const bool mask_distances = reach_px > 0.0;
  const MaskDistance to_mask(mask_distances ? frame.mask : cv::Mat(), reach_px);
  const bool on_probation = enough_proven(point_of);
  for (std::size_t k = 0; k < point_of.size(); ++k) {
    const int id = point_of[k];
    if (id < 0) continue;
    const MapPoint& p = map_.point(id);
    m.keypoint.push_back(static_cast<int>(k));
    m.point.push_back(id);
    m.points_world.push_back(p.position_world);
    m.observed.push_back(current.undistorted[k]);
    // ORB-SLAM's noise model: a keypoint at octave o is 1.2^o times less precise.
    m.sigma.push_back(
        hbos::sigma_from_octave(current.keypoints[k].octave, config_.extraction.scale_factor));
    if (mask_distances) m.mask_distance_px.push_back(to_mask.at(current.keypoints[k].pt));
    m.evidence.outlier_history.push_back(p.history.outlier_share());
    if (on_probation) {
      m.evidence.provisional.push_back(p.history.proven(config_.map.history) ? 0 : 1);
    }
    const cv::Point2f& now = current.keypoints[k].pt;
    const auto before = last_pixel_of_point_.find(id);
    const cv::Point2f then = before != last_pixel_of_point_.end() ? before->second : now;
    out.matches.push_back(
        {{now.x, now.y}, {then.x, then.y}, current.on_person[k] != 0 || p.on_person, false});
  }
  out.stats.matches = static_cast<int>(m.point.size());
  if (config_.map.noise_history.enabled) {
    // A point whose residual has stayed large counts as one the screen rejected before.
    std::vector<PointNoise> noise;
    noise.reserve(m.point.size());
    for (const int id : m.point) noise.push_back(map_.point(id).screened_noise);
    const std::vector<double> shares = noise_shares(noise, config_.map.noise_history);
    for (std::size_t i = 0; i < shares.size(); ++i)
      m.evidence.outlier_history[i] = std::max(m.evidence.outlier_history[i], shares[i]);
  }
  if (evidence_reach_px > 0.0) m.evidence.mask_distance_px = m.mask_distance_px;
  return m;
}

void MapTracker::refine_on_survivors(const Matched& m, ScreenOutcome& screen,
                                     Eigen::Isometry3d& T) const {
  const auto survivors = std::count(screen.inlier.begin(), screen.inlier.end(), std::uint8_t{1});
  if (survivors < config_.screen.min_inliers) return;
  const auto start = Clock::now();
  std::vector<std::uint8_t> use = screen.inlier;
  keep_out_provisional(m.evidence.provisional, static_cast<int>(config_.screen.min_inliers), use);
  if (config_.map.point_noise.enabled) {
    refiner_.refine(m.points_world, m.observed, refinement_sigma(m, use), use, T);
  } else {
    refiner_.refine(m.points_world, m.observed, m.sigma, use, T);
  }
  screen.refine_us += std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

std::vector<double> MapTracker::refinement_sigma(const Matched& m,
                                                 const std::vector<std::uint8_t>& use) const {
  std::vector<PointNoise> noise;
  noise.reserve(m.point.size());
  for (const int id : m.point) noise.push_back(map_.point(id).noise);
  std::vector<double> sigma = m.sigma;
  widen_by_point_noise(noise, use, config_.map.point_noise, sigma);
  return sigma;
}

void MapTracker::record_point_noise(const Matched& m, const ScreenOutcome& screen,
                                    const Eigen::Isometry3d& T_camera_world) {
  const PointNoiseConfig& survivors = config_.map.point_noise;
  const NoiseHistoryConfig& screened = config_.map.noise_history;
  for (std::size_t i = 0; i < m.point.size(); ++i) {
    const bool kept = i < screen.inlier.size() && screen.inlier[i] != 0;
    if (!kept && !screened.enabled) continue;
    const Eigen::Vector3d p_c = T_camera_world * m.points_world[i];
    if (!(p_c.z() > 0.0)) continue;
    const Eigen::Vector2d e = (m.observed[i] - refiner_.camera().project(p_c)) / m.sigma[i];
    MapPoint& p = map_.point(m.point[i]);
    if (kept && survivors.enabled) p.noise.record(e.squaredNorm(), survivors.memory);
    if (screened.enabled) p.screened_noise.record(e.squaredNorm(), screened.memory);
  }
}

void MapTracker::update_history(const Matched& m, const ScreenOutcome& screen,
                                std::vector<int>& point_of) {
  const HistoryConfig& c = config_.map.history;
  for (std::size_t i = 0; i < m.point.size(); ++i) {
    const bool rejected = i >= screen.inlier.size() || screen.inlier[i] == 0;
    MapPoint& p = map_.point(m.point[i]);
    p.history.record(rejected, c.forgetting);
    if (p.history.should_cull(c)) {
      map_.cull(p.id);
      ++report_.culled_now;
    }
    // Outliers leave the frame (as ORB-SLAM2 drops them after PoseOptimization): they neither
    // carry over to the next frame nor become observations of a new keyframe.
    if (rejected) point_of[at(m.keypoint[i])] = -1;
  }
}

void MapTracker::finish(const Frame& frame, Features current, const std::vector<int>& point_of,
                        const Eigen::Isometry3d& T_camera_world, TrackResult& out) {
  const RelocalisationConfig& r = config_.map.relocalisation;
  const KeyframeConfig& kc = config_.map.keyframes;
  int survivors = 0, tracked_close = 0, untracked_close = 0;
  for (std::size_t k = 0; k < point_of.size(); ++k) {
    const float d = current.depth_m[k];
    const bool close = d > 0.f && d < kc.close_depth_m;
    if (point_of[k] >= 0) {
      ++survivors;
      tracked_close += close ? 1 : 0;
    } else {
      untracked_close += close ? 1 : 0;
    }
  }
  const bool after_relocalisation = frame.index < last_relocalisation_frame_ + kc.max_frames;
  bool ok = survivors >= (after_relocalisation ? r.min_inliers_relocalised : r.min_inliers);
  // A jump: frame-to-frame motion no camera makes in 1/30 s means a wrong pose, not motion.
  const Eigen::Isometry3d step = T_camera_world * last_T_camera_world_.inverse();
  if (report_.source != TrackSource::kRelocalised && config_.jump_limit.exceeded_by(step)) {
    ok = false;
  }
  if (!ok) {
    count_match_statistics(out);
    lose(out);
    return;
  }
  velocity_.reset();
  if (state_ == State::kTracking) velocity_ = step;
  state_ = State::kTracking;
  out.stats.tracked = true;
  out.T_world_camera = T_camera_world.inverse();
  count_match_statistics(out);

  // The keyframe decision (keyframe_policy.hpp).
  KeyframeEvidence e;
  e.frames_since_keyframe = frame.index - last_keyframe_frame_;
  e.frames_since_relocalisation = frame.index - last_relocalisation_frame_;
  e.keyframes_in_map = map_.keyframes();
  e.tracked = survivors;
  e.tracked_close = tracked_close;
  e.untracked_close = untracked_close;
  if (reference_keyframe_ >= 0) {
    const int min_views = reference_min_observations(map_.keyframes());
    for (const int p : map_.keyframe(reference_keyframe_).point_of) {
      if (p >= 0 && map_.alive(p) &&
          static_cast<int>(map_.point(p).observations.size()) >= min_views) {
        ++e.reference_tracked;
      }
    }
  }
  last_keypoints_ = current.keypoints;
  last_point_of_ = point_of;
  last_pixel_of_point_.clear();
  for (std::size_t k = 0; k < point_of.size(); ++k) {
    if (point_of[k] >= 0) last_pixel_of_point_[point_of[k]] = current.keypoints[k].pt;
  }
  last_T_camera_world_ = T_camera_world;
  if (need_keyframe(e, kc)) {
    insert_keyframe(frame, std::move(current), point_of, T_camera_world);
    adjust_around_new_keyframe();
  }
  report_.keyframes = map_.keyframes();
  report_.live_points = map_.live_points();
  report_.culled_points = map_.culled_points();
}

void MapTracker::adjust_around_new_keyframe() {
  if (!config_.map.local_bundle.enabled || map_.keyframes() < 2) return;
  Stopwatch clock;
  const LocalBundleReport r = adjust_local_map(map_, reference_keyframe_, refiner_.camera(),
                                               config_.map.local_bundle, config_.map.history);
  report_.bundle_outliers = r.discarded ? -1 : r.outliers;
  // The next frame is predicted from this one, which is the keyframe just adjusted, and tracks
  // the points the keyframe still observes.
  const KeyFrame& adjusted = map_.keyframe(reference_keyframe_);
  last_T_camera_world_ = adjusted.T_camera_world;
  last_point_of_ = adjusted.point_of;
  report_.bundle_us = clock.lap();
}

void MapTracker::lose(TrackResult& out) {
  if (state_ == State::kTracking) state_ = State::kLost;
  velocity_.reset();
  report_.source = TrackSource::kLost;
  out.stats.tracked = false;
  out.T_world_camera = no_pose();
  report_.keyframes = map_.keyframes();
  report_.live_points = map_.live_points();
  report_.culled_points = map_.culled_points();
}

void MapTracker::insert_keyframe(const Frame& frame, Features current,
                                 const std::vector<int>& point_of,
                                 const Eigen::Isometry3d& T_camera_world) {
  const KeyframeConfig& kc = config_.map.keyframes;
  // New points (keyframe_policy.hpp) from the keypoints that observe none.
  std::vector<std::uint8_t> taken(current.size(), 0);
  for (std::size_t k = 0; k < current.size() && k < point_of.size(); ++k)
    taken[k] = point_of[k] >= 0 ? 1 : 0;
  const std::vector<int> fresh = select_new_points(current.depth_m, taken, kc);

  KeyFrame keyframe;
  keyframe.frame_index = frame.index;
  keyframe.T_camera_world = T_camera_world;
  keyframe.point_of = point_of;
  keyframe.point_of.resize(current.size(), -1);
  keyframe.features = std::move(current);
  reference_keyframe_ = map_.add_keyframe(std::move(keyframe), fresh, refiner_.camera());
  last_keyframe_frame_ = frame.index;
  report_.keyframe_inserted = true;
  // The new points join the last frame, so the next frame can track them by projection.
  const KeyFrame& added = map_.keyframe(reference_keyframe_);
  last_point_of_ = added.point_of;
  for (std::size_t k = 0; k < added.point_of.size(); ++k) {
    if (added.point_of[k] >= 0)
      last_pixel_of_point_[added.point_of[k]] = added.features.keypoints[k].pt;
  }
  if (last_keypoints_.empty()) last_keypoints_ = added.features.keypoints;
}

}  // namespace hbos::slam
