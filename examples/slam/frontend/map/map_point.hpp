#pragma once
/// \file
/// A map point: a 3D point created from a keyframe's keypoint with depth, with what ORB-SLAM2's
/// MapPoint keeps for matching — a representative descriptor, its observations, its mean
/// viewing direction and the distance range over which ORB can detect it — plus the screen's
/// memory (screening_history.hpp).

#include "frontend/map/point_noise.hpp"
#include "frontend/map/screening_history.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace hbos::slam {

using Descriptor = std::array<std::uint8_t, 32>;  ///< one 256-bit ORB descriptor

/// [bits] Hamming distance between two ORB descriptors.
[[nodiscard]] int hamming(const Descriptor& a, const Descriptor& b);
/// [bits] the same against a 32-byte row of a cv::Mat of descriptors.
[[nodiscard]] int hamming(const Descriptor& a, const std::uint8_t* row);
[[nodiscard]] Descriptor descriptor_of(const std::uint8_t* row);

struct MapPoint {
  int id = 0;
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();  ///< [m]
  Descriptor descriptor{};  ///< the observation with least median distance to the others
  /// (keyframe id, keypoint index) of every keyframe that observes the point.
  std::vector<std::pair<int, int>> observations;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< mean unit viewing direction (world)
  /// [m] ORB detects the point between these camera distances (MapPoint::UpdateNormalAndDepth):
  /// max = d_ref * 1.2^octave_ref, min = max / 1.2^(levels - 1).
  float min_distance_m = 0.f;
  float max_distance_m = 0.f;
  int reference_keyframe = 0;  ///< the keyframe that created it
  ScreeningHistory history;
  PointNoise noise;  ///< its residuals under the refined poses (point_noise.hpp)
  /// the same over every frame that screened it, kept or rejected (noise_history.hpp)
  PointNoise screened_noise;
  bool culled = false;  ///< screened out again and again: never matched or used again
  /// Made from a keypoint on the composited person (the label): read by statistics only.
  bool on_person = false;

  /// Octave ORB is expected to detect the point at from `distance_m` (MapPoint::PredictScale).
  [[nodiscard]] int predict_octave(double distance_m, float scale_factor, int levels) const;
};

}  // namespace hbos::slam
