#include "frontend/person_mask.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace hbos::slam {

cv::Mat degrade_mask(const cv::Mat& exact, int index, const MaskConfig& config) {
  cv::Mat degraded(exact.size(), CV_8UC1, cv::Scalar(0));
  if (config.degraded_missing_every > 0 &&
      index % config.degraded_missing_every == config.degraded_missing_every - 1) {
    return degraded;
  }
  const int r = config.degraded_erosion_px;
  if (r > 0) {
    const cv::Mat disc =
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1));
    cv::erode(exact, degraded, disc);
  } else {
    exact.copyTo(degraded);
  }
  const cv::Rect person = cv::boundingRect(exact);
  if (person.area() > 0 && config.degraded_unmasked_lower > 0.0) {
    const int cut =
        person.y +
        static_cast<int>(std::lround((1.0 - config.degraded_unmasked_lower) * person.height));
    if (cut < degraded.rows) {
      degraded.rowRange(std::max(cut, 0), degraded.rows).setTo(cv::Scalar(0));
    }
  }
  return degraded;
}

cv::Mat boxes_to_mask(const std::vector<PersonBox>& boxes, cv::Size size) {
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  for (const PersonBox& b : boxes)
    mask(b.box & cv::Rect(cv::Point(0, 0), size)).setTo(cv::Scalar(255));
  return mask;
}

PersonMasker::PersonMasker(const MaskConfig& config) : config_(config) {
  if (config_.degraded_erosion_px < 0 || config_.degraded_missing_every < 0 ||
      !(config_.degraded_unmasked_lower >= 0.0 && config_.degraded_unmasked_lower <= 1.0)) {
    throw InvalidArgument(fmt::format(
        "degraded mask settings: erosion {} px and missing-every {} must be >= 0, unmasked lower "
        "share {} in [0, 1]",
        config_.degraded_erosion_px, config_.degraded_missing_every,
        config_.degraded_unmasked_lower));
  }
  if (config_.source == MaskSource::kDetector)
    detector_ = std::make_unique<PersonDetector>(config_);
}

cv::Mat PersonMasker::mask(int index, const cv::Mat& bgr, const cv::Mat& label) {
  const cv::Mat no_person = cv::Mat::zeros(bgr.size(), CV_8UC1);
  switch (config_.source) {
    case MaskSource::kNone:
      return no_person;
    case MaskSource::kExact:
      return label.empty() ? no_person : label.clone();
    case MaskSource::kDegraded:
      return label.empty() ? no_person : degrade_mask(label, index, config_);
    case MaskSource::kDetector:
      boxes_ = detector_->detect(bgr);
      return boxes_to_mask(boxes_, bgr.size());
    case MaskSource::kFiles:  // read by FrameSource (frontend/mask_files.hpp), not computed
      return no_person;
  }
  return no_person;
}

}  // namespace hbos::slam
