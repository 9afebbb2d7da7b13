#include "frontend/map/map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace hbos::slam {

int Map::add_keyframe(KeyFrame keyframe, const std::vector<int>& new_points,
                      const hbos::PinholeCamerad& camera) {
  keyframe.id = keyframes();
  const int kf = keyframe.id;
  keyframe.point_of.resize(keyframe.features.size(), -1);
  const Eigen::Isometry3d T_world_camera = keyframe.T_camera_world.inverse();
  for (const int k : new_points) {
    const auto i = static_cast<std::size_t>(k);
    if (keyframe.point_of[i] >= 0 || !(keyframe.features.depth_m[i] > 0.f)) continue;
    MapPoint p;
    p.id = points_created();
    p.position_world =
        T_world_camera * camera.back_project(keyframe.features.undistorted[i],
                                             static_cast<double>(keyframe.features.depth_m[i]));
    p.reference_keyframe = kf;
    p.on_person = keyframe.features.on_person[i] != 0;
    keyframe.point_of[i] = p.id;
    points_.push_back(std::move(p));
  }
  keyframes_.push_back(std::move(keyframe));
  KeyFrame& added = keyframes_.back();

  // Observations, and covisibility: every other keyframe seeing one of these points shares it.
  std::unordered_map<int, int> shared;
  for (std::size_t i = 0; i < added.point_of.size(); ++i) {
    const int id = added.point_of[i];
    if (id < 0) continue;
    MapPoint& p = points_[at(id)];
    for (const auto& [other, keypoint] : p.observations) {
      static_cast<void>(keypoint);
      ++shared[other];
    }
    p.observations.emplace_back(kf, static_cast<int>(i));
    update_point(p);
  }
  for (const auto& [other, weight] : shared) {
    added.covisible[other] = weight;
    keyframes_[at(other)].covisible[kf] = weight;
  }
  return kf;
}

void Map::cull(int point_id) {
  MapPoint& p = points_[at(point_id)];
  if (p.culled) return;
  p.culled = true;
  ++culled_;
}

void Map::set_keyframe_pose(int keyframe_id, const Eigen::Isometry3d& T_camera_world) {
  keyframes_[at(keyframe_id)].T_camera_world = T_camera_world;
}

void Map::set_point_position(int point_id, const Eigen::Vector3d& position_world) {
  MapPoint& p = points_[at(point_id)];
  p.position_world = position_world;
  if (!p.observations.empty()) update_point(p);
}

void Map::erase_observation(int keyframe_id, int keypoint) {
  KeyFrame& kf = keyframes_[at(keyframe_id)];
  const int id = kf.point_of[static_cast<std::size_t>(keypoint)];
  if (id < 0) return;
  kf.point_of[static_cast<std::size_t>(keypoint)] = -1;
  MapPoint& p = points_[at(id)];
  const auto mine = std::find(p.observations.begin(), p.observations.end(),
                              std::pair<int, int>(keyframe_id, keypoint));
  if (mine == p.observations.end()) return;
  p.observations.erase(mine);
  // The covisibility this observation gave: one shared point less with every other observer.
  for (const auto& [other, other_keypoint] : p.observations) {
    static_cast<void>(other_keypoint);
    if (other == keyframe_id) continue;
    for (auto [a, b] : {std::pair(keyframe_id, other), std::pair(other, keyframe_id)}) {
      auto& links = keyframes_[at(a)].covisible;
      const auto link = links.find(b);
      if (link != links.end() && --link->second <= 0) links.erase(link);
    }
  }
  if (p.observations.empty()) {
    cull(id);
    return;
  }
  // The scale range is read at the reference keyframe's view: hand it to the oldest left.
  if (p.reference_keyframe == keyframe_id) p.reference_keyframe = p.observations.front().first;
  update_point(p);
}

void Map::update_point(MapPoint& p) const {
  // Mean viewing direction over the observations.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const auto& [kf, keypoint] : p.observations) {
    static_cast<void>(keypoint);
    const Eigen::Vector3d view = p.position_world - keyframes_[at(kf)].center_world();
    if (view.norm() > 0.0) normal += view.normalized();
  }
  if (normal.norm() > 0.0) p.normal = normal.normalized();

  // Scale range from the reference keyframe (MapPoint::UpdateNormalAndDepth):
  // max = distance * 1.2^octave, min = max / 1.2^(levels - 1).
  const KeyFrame& ref = keyframes_[at(p.reference_keyframe)];
  int octave = 0;
  for (const auto& [kf, keypoint] : p.observations) {
    if (kf == p.reference_keyframe) {
      octave = ref.features.keypoints[static_cast<std::size_t>(keypoint)].octave;
    }
  }
  const double distance = (p.position_world - ref.center_world()).norm();
  p.max_distance_m =
      static_cast<float>(distance * std::pow(static_cast<double>(scale_factor_), octave));
  p.min_distance_m = p.max_distance_m / std::pow(scale_factor_, static_cast<float>(levels_ - 1));

  // The representative descriptor: least median distance to the others (the last 8 views).
  std::vector<Descriptor> views;
  const std::size_t first = p.observations.size() > 8 ? p.observations.size() - 8 : 0;
  for (std::size_t o = first; o < p.observations.size(); ++o) {
    const auto& [kf, keypoint] = p.observations[o];
    views.push_back(
        descriptor_of(keyframes_[at(kf)].features.descriptors.ptr<std::uint8_t>(keypoint)));
  }
  if (views.size() <= 2) {
    p.descriptor = views.front();
    return;
  }
  int best_median = std::numeric_limits<int>::max();
  std::vector<int> distances(views.size());
  for (std::size_t a = 0; a < views.size(); ++a) {
    for (std::size_t b = 0; b < views.size(); ++b) distances[b] = hamming(views[a], views[b]);
    const auto middle = distances.begin() + static_cast<std::ptrdiff_t>((views.size() - 1) / 2);
    std::nth_element(distances.begin(), middle, distances.end());
    if (*middle < best_median) {
      best_median = *middle;
      p.descriptor = views[a];
    }
  }
}

std::vector<int> Map::local_keyframes(const std::vector<int>& matched_points,
                                      const LocalMapConfig& config, int& reference) const {
  // Keyframes observing the frame's matched points, by how many they observe.
  std::unordered_map<int, int> votes;
  for (const int id : matched_points) {
    if (id < 0 || points_[at(id)].culled) continue;
    for (const auto& [kf, keypoint] : points_[at(id)].observations) {
      static_cast<void>(keypoint);
      ++votes[kf];
    }
  }
  std::vector<std::pair<int, int>> ranked(votes.begin(), votes.end());  // (kf, votes)
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first > b.first;
  });
  reference = ranked.empty() ? -1 : ranked.front().first;

  const auto cap = static_cast<std::size_t>(std::max(config.max_keyframes, 1));
  std::vector<int> local;
  std::vector<std::uint8_t> taken(keyframes_.size(), 0);
  const auto take = [&](int kf) {
    if (local.size() >= cap || taken[at(kf)] != 0) return;
    taken[at(kf)] = 1;
    local.push_back(kf);
  };
  for (const auto& [kf, n] : ranked) {
    static_cast<void>(n);
    take(kf);
  }
  // Neighbours: the best covisible keyframes of each (most sharing first).
  const std::vector<int> direct = local;
  for (const int kf : direct) {
    std::vector<std::pair<int, int>> neighbours(keyframes_[at(kf)].covisible.begin(),
                                                keyframes_[at(kf)].covisible.end());
    std::sort(neighbours.begin(), neighbours.end(),
              [](const auto& a, const auto& b) { return a.second > b.second; });
    const std::size_t n = std::min(neighbours.size(), static_cast<std::size_t>(config.neighbours));
    for (std::size_t k = 0; k < n; ++k) take(neighbours[k].first);
  }
  return local;
}

std::vector<int> Map::local_points(const std::vector<int>& keyframes) const {
  std::vector<int> points;
  std::vector<std::uint8_t> seen(points_.size(), 0);
  for (const int kf : keyframes) {
    for (const int id : keyframes_[at(kf)].point_of) {
      if (id < 0 || seen[at(id)] != 0 || points_[at(id)].culled) continue;
      seen[at(id)] = 1;
      points.push_back(id);
    }
  }
  return points;
}

}  // namespace hbos::slam
