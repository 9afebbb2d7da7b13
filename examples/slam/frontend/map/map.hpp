#pragma once
/// \file
/// The map: keyframes and the points they created, with ORB-SLAM2's bookkeeping of
/// observations, viewing directions, scale ranges and covisibility, and the local map a frame
/// is tracked against (Tracking::UpdateLocalKeyFrames / UpdateLocalPoints).
///
/// Points are never erased, only culled (`MapPoint::culled`), so ids stay valid indices.

#include "frontend/map/keyframe.hpp"
#include "frontend/map/map_config.hpp"
#include "frontend/map/map_point.hpp"

#include <hbos/screening/pinhole.hpp>

#include <vector>

namespace hbos::slam {

class Map {
 public:
  /// `scale_factor` and `levels` are the ORB pyramid's (for the points' scale ranges).
  Map(float scale_factor, int levels) : scale_factor_(scale_factor), levels_(levels) {}

  /// Adds `keyframe` (its id is set here) and returns the id. `point_of` entries >= 0 become
  /// observations of those points (whose views, ranges and descriptors are updated); then every
  /// keypoint listed in `new_points` with depth creates a new point. Covisibility is updated.
  int add_keyframe(KeyFrame keyframe, const std::vector<int>& new_points,
                   const hbos::PinholeCamerad& camera);

  /// Marks the point culled: it is matched no more, and counted in culled_points().
  void cull(int point_id);
  /// Moves a keyframe (local bundle adjustment); its points' views are not refreshed here.
  void set_keyframe_pose(int keyframe_id, const Eigen::Isometry3d& T_camera_world);
  /// Moves a point and refreshes its mean view and scale range.
  void set_point_position(int point_id, const Eigen::Vector3d& position_world);
  /// Forgets that `keyframe_id`'s keypoint observes its point (an outlier of the bundle
  /// adjustment), with the covisibility it gave; a point left without observations is culled.
  void erase_observation(int keyframe_id, int keypoint);

  /// The keyframes a frame whose matched points are `matched_points` is tracked against: those
  /// observing the most of them (first), then their best covisible neighbours, at most
  /// config.max_keyframes. Also returns, in `reference`, the one sharing the most (-1: none).
  [[nodiscard]] std::vector<int> local_keyframes(const std::vector<int>& matched_points,
                                                 const LocalMapConfig& config,
                                                 int& reference) const;
  /// The live points of `keyframes`, each once.
  [[nodiscard]] std::vector<int> local_points(const std::vector<int>& keyframes) const;

  [[nodiscard]] bool empty() const { return keyframes_.empty(); }
  [[nodiscard]] const KeyFrame& keyframe(int id) const { return keyframes_[at(id)]; }
  [[nodiscard]] const MapPoint& point(int id) const { return points_[at(id)]; }
  [[nodiscard]] MapPoint& point(int id) { return points_[at(id)]; }
  [[nodiscard]] bool alive(int point_id) const { return !points_[at(point_id)].culled; }
  [[nodiscard]] int keyframes() const { return static_cast<int>(keyframes_.size()); }
  [[nodiscard]] int points_created() const { return static_cast<int>(points_.size()); }
  [[nodiscard]] int culled_points() const { return culled_; }
  [[nodiscard]] int live_points() const { return points_created() - culled_; }
  [[nodiscard]] float scale_factor() const { return scale_factor_; }
  [[nodiscard]] int levels() const { return levels_; }

 private:
  static std::size_t at(int id) { return static_cast<std::size_t>(id); }
  // MapPoint::UpdateNormalAndDepth and ComputeDistinctiveDescriptors.
  void update_point(MapPoint& point) const;

  float scale_factor_;
  int levels_;
  std::vector<KeyFrame> keyframes_;
  std::vector<MapPoint> points_;
  int culled_ = 0;
};

}  // namespace hbos::slam
