#pragma once
/// \file
/// A keyframe: a tracked frame kept in the map, with its features, its pose and, per keypoint,
/// the map point it observes. Covisibility weights (shared map points with other keyframes)
/// give the local map its neighbours.

#include "frontend/orb_extraction.hpp"

#include <Eigen/Geometry>

#include <map>
#include <vector>

namespace hbos::slam {

struct KeyFrame {
  int id = 0;
  int frame_index = 0;                                               ///< the frame it was made from
  Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();  ///< world -> camera
  Features features;
  std::vector<int> point_of;     ///< per keypoint: the map point id it observes, -1 = none
  std::map<int, int> covisible;  ///< other keyframe id -> map points both observe

  [[nodiscard]] Eigen::Vector3d center_world() const {
    return T_camera_world.inverse().translation();
  }
  /// Keypoints with a map point that is not culled (pass the map's culled test).
  template <class IsAlive>
  [[nodiscard]] int tracked_points(IsAlive&& alive) const {
    int n = 0;
    for (const int p : point_of) n += (p >= 0 && alive(p)) ? 1 : 0;
    return n;
  }
};

}  // namespace hbos::slam
