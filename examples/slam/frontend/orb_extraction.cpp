#include "frontend/orb_extraction.hpp"

#include "frontend/keypoint_spread.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <utility>

namespace hbos::slam {

OrbExtractor::OrbExtractor(const ExtractionConfig& config, CameraModel camera)
    : config_(config), camera_(std::move(camera)) {
  if (config_.features < 1 || config_.features > kMaxOrbFeatures || config_.levels < 1 ||
      !(config_.scale_factor > 1.f) || config_.fast_threshold < 1 ||
      config_.min_fast_threshold < 1 ||
      !(config_.min_depth_m >= 0.0 && config_.max_depth_m > config_.min_depth_m)) {
    throw InvalidArgument(
        fmt::format("ORB settings: features {} must be in [1, 100000] and levels {} >= 1, scale "
                    "factor {} > 1, FAST "
                    "thresholds {}/{} >= 1, depth range [{}, {}] m non-empty",
                    config_.features, config_.levels, config_.scale_factor, config_.fast_threshold,
                    config_.min_fast_threshold, config_.min_depth_m, config_.max_depth_m));
  }
  if (!(config_.spread_cell_px >= 0.f && std::isfinite(config_.spread_cell_px)) ||
      config_.spread_pool < 1) {
    throw InvalidArgument(
        fmt::format("ORB spread: cell {} px must be finite and >= 0 (0: off), pool {} must be >= 1",
                    config_.spread_cell_px, config_.spread_pool));
  }
  if (config_.spread_cell_px > 0.f &&
      static_cast<long>(config_.features) * config_.spread_pool > kMaxOrbFeatures) {
    throw InvalidArgument(
        fmt::format("ORB spread: a pool of {} x {} features = {} exceeds {}; lower --features or "
                    "--orb-spread-pool",
                    config_.spread_pool, config_.features,
                    static_cast<long>(config_.features) * config_.spread_pool, kMaxOrbFeatures));
  }
  const bool spread = config_.spread_cell_px > 0.f;
  orb_ = cv::ORB::create(spread ? config_.features * config_.spread_pool : config_.features,
                         config_.scale_factor, config_.levels,
                         /*edgeThreshold=*/19, /*firstLevel=*/0, /*WTA_K=*/2, cv::ORB::HARRIS_SCORE,
                         /*patchSize=*/31, config_.fast_threshold);
}

Features OrbExtractor::extract(const Frame& frame) {
  cv::Mat gray;
  cv::cvtColor(frame.bgr, gray, cv::COLOR_BGR2GRAY);
  // cv::ORB detects where its mask is non-zero: everywhere but the dynamic-object mask.
  cv::Mat allowed;
  if (frame.mask.empty()) {
    allowed = cv::Mat(gray.size(), CV_8UC1, cv::Scalar(255));
  } else {
    allowed = frame.mask == 0;
  }
  Features f;
  if (config_.spread_cell_px > 0.f) {
    // The pool, spread over the image, then the descriptors of the kept keypoints only.
    orb_->setFastThreshold(config_.fast_threshold);
    orb_->detect(gray, f.keypoints, allowed);
    if (static_cast<int>(f.keypoints.size()) < config_.features) {
      orb_->setFastThreshold(config_.min_fast_threshold);
      orb_->detect(gray, f.keypoints, allowed);
    }
    f.keypoints = spread_keypoints(f.keypoints, config_.features, config_.spread_cell_px);
    orb_->compute(gray, f.keypoints, f.descriptors);
  } else {
    orb_->setFastThreshold(config_.fast_threshold);
    orb_->detectAndCompute(gray, allowed, f.keypoints, f.descriptors);
    if (static_cast<int>(f.keypoints.size()) < config_.features) {
      orb_->setFastThreshold(config_.min_fast_threshold);
      orb_->detectAndCompute(gray, allowed, f.keypoints, f.descriptors);
    }
  }

  std::vector<cv::Point2f> pixels;
  pixels.reserve(f.keypoints.size());
  for (const cv::KeyPoint& k : f.keypoints) pixels.push_back(k.pt);
  const std::vector<cv::Point2f> undistorted = undistort_pixels(camera_, pixels);

  f.undistorted.reserve(pixels.size());
  f.depth_m.reserve(pixels.size());
  f.on_person.reserve(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    f.undistorted.emplace_back(undistorted[i].x, undistorted[i].y);
    // Depth is registered to the colour image as recorded, i.e. at the distorted pixel.
    const int x = std::clamp(static_cast<int>(std::lround(pixels[i].x)), 0, frame.bgr.cols - 1);
    const int y = std::clamp(static_cast<int>(std::lround(pixels[i].y)), 0, frame.bgr.rows - 1);
    const float d = frame.depth_m.at<float>(y, x);
    const bool valid = d >= config_.min_depth_m && d <= config_.max_depth_m;
    f.depth_m.push_back(valid ? d : 0.f);
    f.on_person.push_back(
        !frame.person_label.empty() && frame.person_label.at<std::uint8_t>(y, x) != 0 ? 1 : 0);
  }
  return f;
}

}  // namespace hbos::slam
