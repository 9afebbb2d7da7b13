#include "frontend/frame_matching.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/features2d.hpp>

namespace hbos::slam {

FrameMatcher::FrameMatcher(const MatchingConfig& config) : config_(config) {
  if (config_.max_hamming < 0 || config_.max_hamming > 256 ||
      !(config_.ratio >= 0.0 && config_.ratio < 1.0)) {
    throw InvalidArgument(fmt::format(
        "matching settings: max Hamming {} must lie in [0, 256], ratio {} in [0, 1) (0 = off)",
        config_.max_hamming, config_.ratio));
  }
}

std::vector<FeatureMatch> FrameMatcher::match(const Features& previous,
                                              const Features& current) const {
  std::vector<FeatureMatch> matches;
  // Only previous features with depth can be back-projected, so only they are candidates.
  std::vector<int> with_depth;
  for (std::size_t i = 0; i < previous.size(); ++i) {
    if (previous.depth_m[i] > 0.f) with_depth.push_back(static_cast<int>(i));
  }
  if (with_depth.empty() || current.size() == 0) return matches;
  cv::Mat candidates(static_cast<int>(with_depth.size()), previous.descriptors.cols, CV_8U);
  for (std::size_t r = 0; r < with_depth.size(); ++r) {
    previous.descriptors.row(with_depth[r]).copyTo(candidates.row(static_cast<int>(r)));
  }

  cv::BFMatcher matcher(cv::NORM_HAMMING, /*crossCheck=*/false);
  std::vector<std::vector<cv::DMatch>> forward;
  matcher.knnMatch(current.descriptors, candidates, forward, 2);
  std::vector<cv::DMatch> backward;
  if (config_.cross_check) matcher.match(candidates, current.descriptors, backward);

  for (const auto& nearest : forward) {
    if (nearest.empty()) continue;
    const cv::DMatch& best = nearest[0];
    if (best.distance > static_cast<float>(config_.max_hamming)) continue;
    if (config_.ratio > 0.0 && nearest.size() > 1 &&
        !(best.distance < static_cast<float>(config_.ratio) * nearest[1].distance)) {
      continue;
    }
    if (config_.cross_check &&
        backward[static_cast<std::size_t>(best.trainIdx)].trainIdx != best.queryIdx) {
      continue;
    }
    matches.push_back({with_depth[static_cast<std::size_t>(best.trainIdx)], best.queryIdx,
                       static_cast<int>(best.distance)});
  }
  return matches;
}

}  // namespace hbos::slam
