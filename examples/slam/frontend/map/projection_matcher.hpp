#pragma once
/// \file
/// Matching map points to the current frame's keypoints, as ORB-SLAM2's ORBmatcher does:
/// - by projection into the last frame's neighbourhood (constant-velocity prediction), radius
///   15 px x 1.2^octave, Hamming <= 100, with the rotation-consistency histogram;
/// - by projection of the local map, radius by viewing angle x 1.2^predicted octave, at the
///   predicted octave or one below, Hamming <= 100 and a 0.8 ratio to the second best on the
///   same octave;
/// - by descriptor against one keyframe (ORB-SLAM2 uses its bag of words; here a brute-force
///   search over the keyframe's map points), Hamming <= 50, a ratio test, rotation consistency.
/// Every search writes `point_of` (current keypoint -> map point id, -1 = none), never
/// overwriting a keypoint already matched, and matches a point at most once.

#include "frontend/map/map.hpp"
#include "frontend/map/map_config.hpp"
#include "frontend/orb_extraction.hpp"

#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>

#include <cstdint>
#include <vector>

namespace hbos::slam {

/// [px] The undistorted image's extent: projections outside it cannot be matched.
struct ImageBounds {
  double min_x = 0.0, max_x = 0.0, min_y = 0.0, max_y = 0.0;
  [[nodiscard]] bool contains(const Eigen::Vector2d& px) const {
    return px.x() >= min_x && px.x() < max_x && px.y() >= min_y && px.y() < max_y;
  }
};

/// Keypoints binned into square cells over the undistorted image (Frame::AssignFeaturesToGrid),
/// for radius searches.
class KeypointGrid {
 public:
  KeypointGrid(const Features& features, const ImageBounds& bounds, double cell_px = 16.0);

  /// Keypoints within the square of half-side `radius` [px] around (x, y) whose octave lies in
  /// [min_octave, max_octave] (a negative bound is open).
  [[nodiscard]] std::vector<int> in_area(double x, double y, double radius, int min_octave,
                                         int max_octave) const;

 private:
  const Features* features_;
  ImageBounds bounds_;
  double cell_px_;
  int columns_ = 0, rows_ = 0;
  std::vector<std::vector<int>> cells_;
};

/// The rotation-consistency check (ORBmatcher's HISTO_LENGTH = 30 histogram): `delta_deg[i]` is
/// the orientation change of match i; matches whose bin (12 deg wide) is not among the three
/// fullest are rejected (the second and third only count with at least 10 % of the fullest).
/// Returns 1 = keep.
[[nodiscard]] std::vector<std::uint8_t> consistent_rotations(const std::vector<float>& delta_deg);

class ProjectionMatcher {
 public:
  ProjectionMatcher(const ProjectionMatchConfig& config, hbos::PinholeCamerad camera,
                    float scale_factor, int levels);

  /// The map points of the last frame (`last_point_of`, per keypoint in `last`) projected into
  /// the current frame under `T_camera_world`, searched at the last keypoint's octave +- 1; the
  /// radius is `radius_scale` times the configured one. Returns the matches made.
  int match_last_frame(const Map& map, const std::vector<cv::KeyPoint>& last,
                       const std::vector<int>& last_point_of,
                       const Eigen::Isometry3d& T_camera_world, const Features& current,
                       const KeypointGrid& grid, const ImageBounds& bounds, float radius_scale,
                       std::vector<int>& point_of) const;

  /// The local map's `points` (those not matched yet) projected under `T_camera_world`, kept
  /// when in view (in front, inside the image, within 0.8 min .. 1.2 max distance, seen within
  /// acos(viewing_cos_limit) of their mean direction); `radius_px` is the base radius (1, or 5
  /// after relocalisation). Returns the matches made.
  int match_local_map(const Map& map, const std::vector<int>& points,
                      const Eigen::Isometry3d& T_camera_world, const Features& current,
                      const KeypointGrid& grid, const ImageBounds& bounds, float radius_px,
                      float viewing_cos_limit, std::vector<int>& point_of) const;

  /// The keyframe's live points matched to the current keypoints by descriptor alone (nearest
  /// within max_hamming_descriptor, `ratio` to the second), one point per keypoint, rotation
  /// consistent. Returns the matches made.
  int match_keyframe(const Map& map, const KeyFrame& keyframe, const Features& current, float ratio,
                     std::vector<int>& point_of) const;

 private:
  ProjectionMatchConfig config_;
  hbos::PinholeCamerad camera_;
  std::vector<float> scale_;  ///< 1.2^octave per octave
  float scale_factor_;
  int levels_;
};

}  // namespace hbos::slam
