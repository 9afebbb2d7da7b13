#pragma once
/// \file
/// The mask's neighbourhood for the screen: how far each keypoint lies from the nearest pixel of
/// the frame's dynamic-object mask. A segmenter's mask misses a person's edges, hands and what
/// they carry, so a match just outside it whose residual is off is more likely a leak than one
/// far away; hbos's MaskEvidence (hbos/screening/strategies.hpp) reads these distances, and only
/// those within its radius matter (beyond it the evidence is 0 whatever the distance).

#include "frontend/config.hpp"

#include <opencv2/core.hpp>

namespace hbos::slam {

/// The reach of the screen's mask evidence [px] when the tracker should pass mask distances:
/// asked for (ScreenStageConfig::mask_evidence), a mask source that makes masks, and a screen
/// that reads them (hbos's HbosScreen with its mask evidence on). 0 otherwise: nothing to pass.
[[nodiscard]] double mask_evidence_reach_px(const Config& config);

class MaskDistance {
 public:
  /// `mask`: CV_8U, 255 = masked (Frame::mask); distances are measured up to `reach_px` (>= 0).
  /// Each lookup scans the square of that reach around the keypoint, so the cost follows the
  /// keypoints, not the image (bench/bench_mask_distance compares a whole-image transform).
  MaskDistance(const cv::Mat& mask, double reach_px);

  /// [px] Euclidean distance from `pixel` (image coordinates, as cv::KeyPoint::pt, rounded to
  /// the nearest pixel; outside the image, the nearest pixel inside it) to the nearest masked
  /// pixel when it is at most the reach: 0 on the mask. +inf when no masked pixel is that close
  /// (or the mask is empty).
  [[nodiscard]] double at(const cv::Point2f& pixel) const;

 private:
  /// Side of the coarse blocks [px]: a lookup scans only the blocks of its square that hold a
  /// masked pixel, so a keypoint far from the mask costs a few block tests.
  static constexpr int kBlock = 16;

  cv::Mat mask_;
  cv::Mat occupied_;  ///< CV_8U, one per kBlock x kBlock block: 1 = holds a masked pixel
  double reach_px_ = 0.0;
  int reach_ = 0;  ///< the reach in whole pixels, rounded down
};

}  // namespace hbos::slam
