#pragma once
/// \file
/// The mask's neighbourhood for the screen: how far each keypoint lies from the nearest pixel of
/// the frame's dynamic-object mask. A segmenter's mask misses a person's edges, hands and what
/// they carry, so a match just outside it whose residual is off is more likely a leak than one
/// far away; hbos's MaskEvidence (hbos/screening/strategies.hpp) reads these distances.

#include "frontend/config.hpp"

#include <opencv2/core.hpp>

namespace hbos::slam {

/// Whether a tracker passes mask distances to the screen: asked for (ScreenStageConfig::
/// mask_evidence) and a mask source that makes masks.
[[nodiscard]] inline bool passes_mask_distance(const Config& config) {
  return config.screen.mask_evidence && config.mask.source != MaskSource::kNone;
}

class MaskDistance {
 public:
  /// `mask`: CV_8U, 255 = masked (Frame::mask). An empty image or one with no masked pixel
  /// (a frame where the detector found nobody) puts every pixel infinitely far away.
  explicit MaskDistance(const cv::Mat& mask);

  /// [px] Euclidean distance from `pixel` (image coordinates, as cv::KeyPoint::pt) to the
  /// nearest masked pixel: 0 on the mask, +inf when nothing is masked. A pixel outside the image
  /// takes the distance of the nearest pixel inside it.
  [[nodiscard]] double at(const cv::Point2f& pixel) const;

 private:
  cv::Mat distance_;  ///< CV_32F, one per pixel; empty when nothing is masked
};

}  // namespace hbos::slam
