#include "frontend/mask_distance.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hbos::slam {

MaskDistance::MaskDistance(const cv::Mat& mask) {
  CV_Assert(mask.empty() || mask.type() == CV_8UC1);
  if (mask.empty() || cv::countNonZero(mask) == 0) return;
  // distanceTransform measures, for every non-zero pixel, the distance to the nearest zero one:
  // so the unmasked pixels are the non-zero ones here.
  cv::Mat unmasked;
  cv::compare(mask, 0, unmasked, cv::CMP_EQ);
  cv::distanceTransform(unmasked, distance_, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
}

double MaskDistance::at(const cv::Point2f& pixel) const {
  if (distance_.empty()) return std::numeric_limits<double>::infinity();
  const int x = std::clamp(static_cast<int>(std::lround(pixel.x)), 0, distance_.cols - 1);
  const int y = std::clamp(static_cast<int>(std::lround(pixel.y)), 0, distance_.rows - 1);
  return static_cast<double>(distance_.at<float>(y, x));
}

}  // namespace hbos::slam
