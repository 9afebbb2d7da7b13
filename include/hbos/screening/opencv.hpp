#pragma once
/// \file
/// Optional OpenCV adapter for reprojection screening: fills hbos::Matches from cv::Point2f,
/// cv::KeyPoint and cv::DMatch, reads the dynamic-mask prior from a cv::Mat, and filters matches
/// by a screen's result. Never included by hbos/hbos.hpp; needs OpenCV's core module (>= 4) and
/// features2d for cv::KeyPoint / cv::DMatch.
///
/// Conventions: in a cv::DMatch, `queryIdx` indexes the predicted points (map points or
/// previous-frame points reprojected with the rough pose) and `trainIdx` the current frame's
/// keypoints; a keypoint's scale sigma is `scale_factor^octave` (ORB-SLAM's pyramid). Mask
/// images are 8-bit, single channel, nonzero = on a dynamic object.
///
/// Threading: every function is re-entrant.

#include <opencv2/core.hpp>
#include <opencv2/core/types.hpp>

#include <cmath>
#include <vector>

#include "hbos/error.hpp"
#include "hbos/screening/residual_field.hpp"
#include "hbos/screening/screen.hpp"

namespace hbos {

/// A cv::Point2f as an Eigen 2-vector [px].
template <class Scalar = double>
[[nodiscard]] Eigen::Matrix<Scalar, 2, 1> to_eigen(const cv::Point2f& p) {
  return {static_cast<Scalar>(p.x), static_cast<Scalar>(p.y)};
}

/// True when `mask` (CV_8UC1, nonzero = dynamic) is set at the pixel nearest to `p`; false
/// outside the image. An empty mask flags nothing.
/// \throws InvalidArgument when the mask is neither empty nor CV_8UC1.
[[nodiscard]] inline bool on_mask(const cv::Mat& mask, const cv::Point2f& p) {
  if (mask.empty()) return false;
  detail::require(mask.type() == CV_8UC1, "dynamic mask must be CV_8UC1, got OpenCV type ",
                  mask.type());
  const int x = static_cast<int>(std::lround(p.x));
  const int y = static_cast<int>(std::lround(p.y));
  if (x < 0 || y < 0 || x >= mask.cols || y >= mask.rows) return false;
  return mask.at<unsigned char>(y, x) != 0;
}

/// Fills `out` (cleared first) from parallel vectors of predicted and observed pixels, all with
/// sigma 1, flagged where `dynamic_mask` is set at the observed pixel.
/// \throws InvalidArgument when the vectors differ in length.
template <class Scalar>
void fill_matches(const std::vector<cv::Point2f>& predicted,
                  const std::vector<cv::Point2f>& observed, Matches<Scalar>& out,
                  const cv::Mat& dynamic_mask = cv::Mat()) {
  detail::require(predicted.size() == observed.size(), "predicted has ", predicted.size(),
                  " points but observed has ", observed.size());
  out.clear();
  out.reserve(static_cast<Eigen::Index>(predicted.size()));
  for (std::size_t i = 0; i < predicted.size(); ++i)
    out.add(to_eigen<Scalar>(predicted[i]), to_eigen<Scalar>(observed[i]), Scalar(1),
            on_mask(dynamic_mask, observed[i]));
}

/// Fills `out` (cleared first) with one match per cv::DMatch: the prediction
/// `predicted[m.queryIdx]`, the keypoint `keypoints[m.trainIdx]`, its sigma
/// `scale_factor^octave`, and the prior flag from `dynamic_mask` at the keypoint.
/// \throws InvalidArgument on an index out of range or a negative octave.
template <class Scalar>
void fill_matches(const std::vector<cv::Point2f>& predicted,
                  const std::vector<cv::KeyPoint>& keypoints,
                  const std::vector<cv::DMatch>& matches, Matches<Scalar>& out,
                  const cv::Mat& dynamic_mask = cv::Mat(), double scale_factor = 1.2) {
  out.clear();
  out.reserve(static_cast<Eigen::Index>(matches.size()));
  for (std::size_t k = 0; k < matches.size(); ++k) {
    const cv::DMatch& m = matches[k];
    detail::require(m.queryIdx >= 0 && static_cast<std::size_t>(m.queryIdx) < predicted.size(),
                    "match ", k, ": queryIdx ", m.queryIdx, " out of range [0, ", predicted.size(),
                    ")");
    detail::require(m.trainIdx >= 0 && static_cast<std::size_t>(m.trainIdx) < keypoints.size(),
                    "match ", k, ": trainIdx ", m.trainIdx, " out of range [0, ", keypoints.size(),
                    ")");
    const cv::KeyPoint& kp = keypoints[static_cast<std::size_t>(m.trainIdx)];
    out.add(to_eigen<Scalar>(predicted[static_cast<std::size_t>(m.queryIdx)]),
            to_eigen<Scalar>(kp.pt),
            static_cast<Scalar>(sigma_from_octave(kp.octave, scale_factor)),
            on_mask(dynamic_mask, kp.pt));
  }
}

/// The matches a screen kept, in their original order. `matches` must be the vector the
/// screened Matches were filled from.
/// \throws InvalidArgument when the sizes differ.
template <class Scalar>
[[nodiscard]] std::vector<cv::DMatch> kept_matches(const std::vector<cv::DMatch>& matches,
                                                   const ScreenResult<Scalar>& result) {
  detail::require(static_cast<Eigen::Index>(matches.size()) == result.size(),
                  "the result screened ", result.size(), " matches but ", matches.size(),
                  " were given");
  std::vector<cv::DMatch> kept;
  kept.reserve(static_cast<std::size_t>(result.n_inliers()));
  for (std::size_t i = 0; i < matches.size(); ++i)
    if (result.inlier(static_cast<Eigen::Index>(i))) kept.push_back(matches[i]);
  return kept;
}

/// The screen's inlier mask as the 0/1 vector OpenCV functions take (e.g. a solvePnP mask).
template <class Scalar>
[[nodiscard]] std::vector<unsigned char> inlier_mask(const ScreenResult<Scalar>& result) {
  std::vector<unsigned char> mask(static_cast<std::size_t>(result.size()));
  for (Eigen::Index i = 0; i < result.size(); ++i)
    mask[static_cast<std::size_t>(i)] = result.inlier(i) ? 1 : 0;
  return mask;
}

}  // namespace hbos
