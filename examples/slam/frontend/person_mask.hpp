#pragma once
/// \file
/// Stage 1a: the dynamic-object mask the feature extractor avoids, from one of four sources
/// (see MaskSource): none, the exact composited silhouette, a degraded copy of it that fails the
/// way real segmenters do, or a person detector's boxes.

#include "frontend/config.hpp"
#include "frontend/person_detector.hpp"

#include <opencv2/core.hpp>

#include <memory>
#include <vector>

namespace hbos::slam {

/// The exact mask made worse as FINDINGS.md did: eroded by `degraded_erosion_px` (the edges
/// leak), the lower `degraded_unmasked_lower` of the person's height removed (legs missed), and
/// nothing at all in every `degraded_missing_every`-th frame (index % N == N - 1: a missed
/// detection). CV_8U, 255 = masked.
[[nodiscard]] cv::Mat degrade_mask(const cv::Mat& exact, int index, const MaskConfig& config);

/// Filled boxes. CV_8U, 255 = masked.
[[nodiscard]] cv::Mat boxes_to_mask(const std::vector<PersonBox>& boxes, cv::Size size);

class PersonMasker {
 public:
  /// Loads the detector when the source is kDetector (throws as PersonDetector does).
  explicit PersonMasker(const MaskConfig& config);

  /// The mask of frame `index` (CV_8U, 255 = do not extract there) from its colour image and the
  /// scenario's label mask (255 = person; empty when there is no person).
  [[nodiscard]] cv::Mat mask(int index, const cv::Mat& bgr, const cv::Mat& label);

  /// The detector's boxes of the last call (kDetector only).
  [[nodiscard]] const std::vector<PersonBox>& last_boxes() const { return boxes_; }

 private:
  MaskConfig config_;
  std::unique_ptr<PersonDetector> detector_;
  std::vector<PersonBox> boxes_;
};

}  // namespace hbos::slam
