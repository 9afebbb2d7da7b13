#pragma once
/// \file
/// Lost and found (Tracking::Relocalization): the current frame's keypoints are matched by
/// descriptor to the map points of each recent keyframe (most recent first; ORB-SLAM2 picks its
/// candidates by bag of words over the whole map), and a candidate with enough matches gives a
/// pose by PnP RANSAC. The tracker then confirms that pose against the local map with a
/// stricter inlier count than usual.

#include "frontend/map/map.hpp"
#include "frontend/map/map_config.hpp"
#include "frontend/map/projection_matcher.hpp"
#include "frontend/orb_extraction.hpp"

#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>

#include <vector>

namespace hbos::slam {

struct Relocalisation {
  bool found = false;
  Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();
  int keyframe = -1;  ///< the keyframe it was found against
  int pnp_inliers = 0;
};

class Relocaliser {
 public:
  Relocaliser(const RelocalisationConfig& config, hbos::PinholeCamerad camera);

  /// Tries the `recent_keyframes` most recent keyframes. On success `point_of` (per current
  /// keypoint) holds the PnP inliers' map points; otherwise it is left all -1.
  [[nodiscard]] Relocalisation relocalise(const Map& map, const ProjectionMatcher& matcher,
                                          const Features& current,
                                          std::vector<int>& point_of) const;

 private:
  RelocalisationConfig config_;
  hbos::PinholeCamerad camera_;
};

}  // namespace hbos::slam
