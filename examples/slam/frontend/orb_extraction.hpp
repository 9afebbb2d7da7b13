#pragma once
/// \file
/// Stage 1b: ORB features outside the dynamic-object mask, with their undistorted positions and
/// depths.

#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/frame.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include <cstdint>
#include <vector>

namespace hbos::slam {

/// The features of one frame; index i refers to the same feature in every vector.
struct Features {
  std::vector<cv::KeyPoint> keypoints;       ///< on the (distorted) image
  std::vector<Eigen::Vector2d> undistorted;  ///< [px] undistorted positions
  cv::Mat descriptors;                       ///< CV_8U, one 32-byte row per keypoint
  std::vector<float> depth_m;                ///< [m] at the keypoint, 0 = none or out of range
  std::vector<std::uint8_t> on_person;       ///< 1 when the keypoint lies on the person label

  [[nodiscard]] std::size_t size() const { return keypoints.size(); }
};

/// The most ORB features per frame an extractor accepts: 100x ORB-SLAM2's 1000; beyond it
/// cv::ORB's per-level buffers (and then the matcher) need gigabytes for no gain on images of
/// ordinary size.
inline constexpr int kMaxOrbFeatures = 100000;

/// cv::ORB set up as ORB-SLAM2 (1000 features, scale 1.2, 8 levels, FAST 20 with a retry at 7).
/// ORB-SLAM2 falls back to FAST 7 per grid cell; cv::ORB has no cells, so here the whole frame is
/// retried at 7 when FAST 20 finds fewer corners than `features`.
class OrbExtractor {
 public:
  /// Throws hbos::InvalidArgument on settings out of range (features outside
  /// [1, kMaxOrbFeatures], levels < 1, scale factor <= 1, ...).
  OrbExtractor(const ExtractionConfig& config, CameraModel camera);

  [[nodiscard]] Features extract(const Frame& frame);

 private:
  ExtractionConfig config_;
  CameraModel camera_;
  cv::Ptr<cv::ORB> orb_;
};

}  // namespace hbos::slam
