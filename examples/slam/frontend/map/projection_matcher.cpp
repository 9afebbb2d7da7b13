#include "frontend/map/projection_matcher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include "common/index.hpp"

namespace hbos::slam {

namespace {

using examples::at;

constexpr int kHistogramBins = 30;  // ORBmatcher's HISTO_LENGTH

// Orientation change from `before` to `after` [deg, 0..360).
float rotation_deg(float before, float after) {
  float d = before - after;
  if (d < 0.f) d += 360.f;
  return d >= 360.f ? d - 360.f : d;
}

// Undoes the matches in `made` whose rotation is inconsistent; returns those kept.
int filter_rotations(const std::vector<int>& made, const std::vector<float>& delta,
                     std::vector<int>& point_of) {
  const std::vector<std::uint8_t> keep = consistent_rotations(delta);
  int kept = 0;
  for (std::size_t m = 0; m < made.size(); ++m) {
    if (keep[m] != 0) {
      ++kept;
    } else {
      point_of[at(made[m])] = -1;
    }
  }
  return kept;
}

}  // namespace

KeypointGrid::KeypointGrid(const Features& features, const ImageBounds& bounds, double cell_px)
    : features_(&features), bounds_(bounds), cell_px_(cell_px) {
  columns_ = std::max(1, static_cast<int>(std::ceil((bounds.max_x - bounds.min_x) / cell_px)));
  rows_ = std::max(1, static_cast<int>(std::ceil((bounds.max_y - bounds.min_y) / cell_px)));
  cells_.resize(static_cast<std::size_t>(columns_ * rows_));
  for (std::size_t i = 0; i < features.size(); ++i) {
    const Eigen::Vector2d& p = features.undistorted[i];
    const int cx = static_cast<int>(std::floor((p.x() - bounds.min_x) / cell_px));
    const int cy = static_cast<int>(std::floor((p.y() - bounds.min_y) / cell_px));
    if (cx < 0 || cy < 0 || cx >= columns_ || cy >= rows_) continue;
    cells_[static_cast<std::size_t>(cy * columns_ + cx)].push_back(static_cast<int>(i));
  }
}

std::vector<int> KeypointGrid::in_area(double x, double y, double radius, int min_octave,
                                       int max_octave) const {
  std::vector<int> found;
  const auto cell = [&](double v, double origin, int n) {
    return std::clamp(static_cast<int>(std::floor((v - origin) / cell_px_)), 0, n - 1);
  };
  if (x + radius < bounds_.min_x || x - radius >= bounds_.max_x || y + radius < bounds_.min_y ||
      y - radius >= bounds_.max_y) {
    return found;
  }
  const int x0 = cell(x - radius, bounds_.min_x, columns_),
            x1 = cell(x + radius, bounds_.min_x, columns_);
  const int y0 = cell(y - radius, bounds_.min_y, rows_),
            y1 = cell(y + radius, bounds_.min_y, rows_);
  for (int cy = y0; cy <= y1; ++cy) {
    for (int cx = x0; cx <= x1; ++cx) {
      for (const int i : cells_[static_cast<std::size_t>(cy * columns_ + cx)]) {
        const Eigen::Vector2d& p = features_->undistorted[at(i)];
        if (std::abs(p.x() - x) >= radius || std::abs(p.y() - y) >= radius) continue;
        const int octave = features_->keypoints[at(i)].octave;
        if ((min_octave >= 0 && octave < min_octave) || (max_octave >= 0 && octave > max_octave)) {
          continue;
        }
        found.push_back(i);
      }
    }
  }
  return found;
}

std::vector<std::uint8_t> consistent_rotations(const std::vector<float>& delta_deg) {
  std::array<int, kHistogramBins> count{};
  std::vector<int> bin_of(delta_deg.size());
  for (std::size_t m = 0; m < delta_deg.size(); ++m) {
    int bin = static_cast<int>(delta_deg[m] * kHistogramBins / 360.f);
    bin = std::clamp(bin, 0, kHistogramBins - 1);
    bin_of[m] = bin;
    ++count[at(bin)];
  }
  // The three fullest bins (ORBmatcher::ComputeThreeMaxima).
  std::array<int, kHistogramBins> order{};
  for (int b = 0; b < kHistogramBins; ++b) order[at(b)] = b;
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return count[at(a)] > count[at(b)]; });
  std::array<std::uint8_t, kHistogramBins> keep_bin{};
  const int fullest = count[at(order[0])];
  for (std::size_t k = 0; k < 3; ++k) {
    const int c = count[at(order[k])];
    if (c > 0 && (k == 0 || 10 * c >= fullest)) keep_bin[at(order[k])] = 1;
  }
  std::vector<std::uint8_t> keep(delta_deg.size());
  for (std::size_t m = 0; m < delta_deg.size(); ++m) keep[m] = keep_bin[at(bin_of[m])];
  return keep;
}

ProjectionMatcher::ProjectionMatcher(const ProjectionMatchConfig& config,
                                     hbos::PinholeCamerad camera, float scale_factor, int levels)
    : config_(config), camera_(camera), scale_factor_(scale_factor), levels_(levels) {
  scale_.resize(at(levels));
  for (int o = 0; o < levels; ++o) scale_[at(o)] = std::pow(scale_factor, static_cast<float>(o));
}

int ProjectionMatcher::match_last_frame(const Map& map, const std::vector<cv::KeyPoint>& last,
                                        const std::vector<int>& last_point_of,
                                        const Eigen::Isometry3d& T_camera_world,
                                        const Features& current, const KeypointGrid& grid,
                                        const ImageBounds& bounds, float radius_scale,
                                        std::vector<int>& point_of) const {
  std::vector<int> made;
  std::vector<float> delta;
  for (std::size_t i = 0; i < last_point_of.size(); ++i) {
    const int id = last_point_of[i];
    if (id < 0 || !map.alive(id)) continue;
    const MapPoint& p = map.point(id);
    const Eigen::Vector3d pc = T_camera_world * p.position_world;
    if (!(pc.z() > 0.0)) continue;
    const Eigen::Vector2d px = camera_.project(pc);
    if (!bounds.contains(px)) continue;
    const int octave = last[i].octave;
    const double radius =
        static_cast<double>(radius_scale * config_.last_frame_radius_px * scale_[at(octave)]);
    int best = std::numeric_limits<int>::max(), best_k = -1;
    for (const int k : grid.in_area(px.x(), px.y(), radius, octave - 1, octave + 1)) {
      if (point_of[at(k)] >= 0) continue;
      const int d = hamming(p.descriptor, current.descriptors.ptr<std::uint8_t>(k));
      if (d < best) {
        best = d;
        best_k = k;
      }
    }
    if (best_k < 0 || best > config_.max_hamming) continue;
    point_of[at(best_k)] = id;
    made.push_back(best_k);
    delta.push_back(rotation_deg(last[i].angle, current.keypoints[at(best_k)].angle));
  }
  if (!config_.check_orientation) return static_cast<int>(made.size());
  return filter_rotations(made, delta, point_of);
}

int ProjectionMatcher::match_local_map(const Map& map, const std::vector<int>& points,
                                       const Eigen::Isometry3d& T_camera_world,
                                       const Features& current, const KeypointGrid& grid,
                                       const ImageBounds& bounds, float radius_px,
                                       float viewing_cos_limit, std::vector<int>& point_of) const {
  const Eigen::Vector3d center = T_camera_world.inverse().translation();
  int made = 0;
  for (const int id : points) {
    if (!map.alive(id)) continue;
    const MapPoint& p = map.point(id);
    // MapPoint in view (Frame::isInFrustum).
    const Eigen::Vector3d pc = T_camera_world * p.position_world;
    if (!(pc.z() > 0.0)) continue;
    const Eigen::Vector2d px = camera_.project(pc);
    if (!bounds.contains(px)) continue;
    const Eigen::Vector3d view = p.position_world - center;
    const double distance = view.norm();
    if (distance < 0.8 * static_cast<double>(p.min_distance_m) ||
        distance > 1.2 * static_cast<double>(p.max_distance_m)) {
      continue;
    }
    const double viewing_cos = view.dot(p.normal) / distance;
    if (viewing_cos < static_cast<double>(viewing_cos_limit)) continue;
    const int octave = p.predict_octave(distance, scale_factor_, levels_);
    // ORBmatcher::RadiusByViewingCos: a point seen head-on moves less in the image.
    const double radius = (viewing_cos > 0.998 ? 2.5 : 4.0) * static_cast<double>(radius_px) *
                          static_cast<double>(scale_[at(octave)]);

    int best = std::numeric_limits<int>::max(), second = best, best_k = -1, best_octave = -1,
        second_octave = -1;
    for (const int k : grid.in_area(px.x(), px.y(), radius, octave - 1, octave)) {
      if (point_of[at(k)] >= 0) continue;
      const int d = hamming(p.descriptor, current.descriptors.ptr<std::uint8_t>(k));
      const int o = current.keypoints[at(k)].octave;
      if (d < best) {
        second = best;
        second_octave = best_octave;
        best = d;
        best_octave = o;
        best_k = k;
      } else if (d < second) {
        second = d;
        second_octave = o;
      }
    }
    if (best_k < 0 || best > config_.max_hamming) continue;
    if (best_octave == second_octave &&
        static_cast<float>(best) > config_.ratio * static_cast<float>(second)) {
      continue;
    }
    point_of[at(best_k)] = id;
    ++made;
  }
  return made;
}

int ProjectionMatcher::match_keyframe(const Map& map, const KeyFrame& keyframe,
                                      const Features& current, float ratio,
                                      std::vector<int>& point_of) const {
  // For each keyframe point, its nearest current keypoint; a keypoint claimed twice keeps the
  // nearer point.
  std::vector<int> claimed_by(current.size(), -1), claimed_distance(current.size(), 0);
  for (std::size_t i = 0; i < keyframe.point_of.size(); ++i) {
    const int id = keyframe.point_of[i];
    if (id < 0 || !map.alive(id)) continue;
    const MapPoint& p = map.point(id);
    int best = std::numeric_limits<int>::max(), second = best, best_k = -1;
    for (std::size_t k = 0; k < current.size(); ++k) {
      if (point_of[k] >= 0) continue;
      const int d =
          hamming(p.descriptor, current.descriptors.ptr<std::uint8_t>(static_cast<int>(k)));
      if (d < best) {
        second = best;
        best = d;
        best_k = static_cast<int>(k);
      } else if (d < second) {
        second = d;
      }
    }
    if (best_k < 0 || best > config_.max_hamming_descriptor ||
        static_cast<float>(best) >= ratio * static_cast<float>(second)) {
      continue;
    }
    if (claimed_by[at(best_k)] >= 0 && claimed_distance[at(best_k)] <= best) continue;
    claimed_by[at(best_k)] = static_cast<int>(i);
    claimed_distance[at(best_k)] = best;
  }
  std::vector<int> made;
  std::vector<float> delta;
  for (std::size_t k = 0; k < current.size(); ++k) {
    if (claimed_by[k] < 0) continue;
    const auto i = at(claimed_by[k]);
    point_of[k] = keyframe.point_of[i];
    made.push_back(static_cast<int>(k));
    delta.push_back(rotation_deg(keyframe.features.keypoints[i].angle, current.keypoints[k].angle));
  }
  if (!config_.check_orientation) return static_cast<int>(made.size());
  return filter_rotations(made, delta, point_of);
}

}  // namespace hbos::slam
