#include "frontend/map/local_mapping.hpp"

#include "frontend/map/local_bundle_adjustment.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hbos::slam {

namespace {

/// The keyframes that move: `keyframe_id` and its most covisible neighbours, at most `cap`.
std::vector<int> moving_keyframes(const Map& map, int keyframe_id, int cap) {
  std::vector<std::pair<int, int>> neighbours(map.keyframe(keyframe_id).covisible.begin(),
                                              map.keyframe(keyframe_id).covisible.end());
  std::sort(neighbours.begin(), neighbours.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first > b.first;
  });
  std::vector<int> moving{keyframe_id};
  for (const auto& [kf, shared] : neighbours) {
    static_cast<void>(shared);
    if (static_cast<int>(moving.size()) >= cap) break;
    moving.push_back(kf);
  }
  return moving;
}

}  // namespace

LocalBundleReport adjust_local_map(Map& map, int keyframe_id, const hbos::PinholeCamerad& camera,
                                   const LocalBundleConfig& config, const HistoryConfig& history) {
  LocalBundleReport report;
  const std::vector<int> moving = moving_keyframes(map, keyframe_id, config.max_keyframes);
  // Only points the screen vouches for: the adjustment has no screen of its own, and a person
  // the mask missed, moving slowly, fits a keyframe's pose nearly as well as the room does.
  std::vector<int> point_ids = map.local_points(moving);
  point_ids.erase(std::remove_if(point_ids.begin(), point_ids.end(),
                                 [&](int id) {
                                   const ScreeningHistory& h = map.point(id).history;
                                   return !h.proven(history) || h.distrusted(history);
                                 }),
                  point_ids.end());
  if (point_ids.empty()) return report;

  // Problem indices: the moving keyframes first, then every other keyframe observing a point.
  std::unordered_map<int, int> keyframe_index, point_index;
  std::vector<int> keyframe_ids;
  std::vector<BundleKeyframe> keyframes;
  const auto add_keyframe = [&](int kf, bool fixed) {
    if (keyframe_index.count(kf) != 0) return;
    keyframe_index[kf] = static_cast<int>(keyframes.size());
    keyframe_ids.push_back(kf);
    keyframes.push_back({map.keyframe(kf).T_camera_world, fixed});
  };
  // The first keyframe defines the world frame: it never moves (ORB-SLAM2 fixes keyframe 0).
  for (const int kf : moving) add_keyframe(kf, kf == 0);
  std::vector<BundlePoint> points;
  points.reserve(point_ids.size());
  for (const int id : point_ids) {
    point_index[id] = static_cast<int>(points.size());
    points.push_back({map.point(id).position_world});
    for (const auto& [kf, keypoint] : map.point(id).observations) {
      static_cast<void>(keypoint);
      add_keyframe(kf, true);
    }
  }
  // A local map no other keyframe observes (the map's first keyframes): its oldest holds it.
  const bool any_fixed = std::any_of(keyframes.begin(), keyframes.end(),
                                     [](const BundleKeyframe& k) { return k.fixed; });
  if (!any_fixed) {
    const auto oldest = std::min_element(keyframe_ids.begin(), keyframe_ids.end());
    keyframes[static_cast<std::size_t>(oldest - keyframe_ids.begin())].fixed = true;
  }

  std::vector<BundleObservation> observations;
  std::vector<std::pair<int, int>> observed_by;  // (keyframe id, keypoint) of each observation
  const double scale = static_cast<double>(map.scale_factor());
  for (const int id : point_ids) {
    for (const auto& [kf, keypoint] : map.point(id).observations) {
      const Features& f = map.keyframe(kf).features;
      const auto k = static_cast<std::size_t>(keypoint);
      BundleObservation o;
      o.keyframe = keyframe_index.at(kf);
      o.point = point_index.at(id);
      o.pixel = f.undistorted[k];
      o.sigma = std::pow(scale, f.keypoints[k].octave);
      o.depth_m = static_cast<double>(f.depth_m[k]);
      observations.push_back(o);
      observed_by.emplace_back(kf, keypoint);
    }
  }

  BundleAdjustmentConfig ba;
  ba.iterations = config.iterations;
  ba.baseline_fx = config.baseline_fx;
  ba.disparity_sigma_px = config.disparity_sigma_px;
  const BundleAdjustmentResult result = adjust_bundle(keyframes, points, observations, camera, ba);

  report.points = static_cast<int>(points.size());
  report.observations = static_cast<int>(observations.size());
  report.iterations = result.iterations;
  report.initial_cost = result.initial_cost;
  report.final_cost = result.final_cost;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    report.moving_keyframes += keyframes[k].fixed ? 0 : 1;
    report.fixed_keyframes += keyframes[k].fixed ? 1 : 0;
    if (keyframes[k].fixed) continue;
    const Eigen::Isometry3d shift =
        keyframes[k].T_camera_world * map.keyframe(keyframe_ids[k]).T_camera_world.inverse();
    const double degrees =
        Eigen::AngleAxisd(shift.linear()).angle() * 180.0 / static_cast<double>(EIGEN_PI);
    if (shift.translation().norm() > config.max_shift_m || degrees > config.max_shift_deg) {
      // Tracked keyframes are centimetres from the truth: an adjustment that moves one further
      // has found another minimum (keyframes a frame apart, points just proven), not a better
      // map. Keep the map as it was.
      report.discarded = true;
      return report;
    }
  }
  for (std::size_t k = 0; k < keyframes.size(); ++k)
    if (!keyframes[k].fixed) map.set_keyframe_pose(keyframe_ids[k], keyframes[k].T_camera_world);
  for (std::size_t j = 0; j < point_ids.size(); ++j)
    map.set_point_position(point_ids[j], points[j].position_world);
  for (std::size_t o = 0; o < observations.size(); ++o) {
    if (result.outlier[o] == 0) continue;
    map.erase_observation(observed_by[o].first, observed_by[o].second);
    ++report.outliers;
  }
  return report;
}

}  // namespace hbos::slam
