#pragma once
/// \file
/// The pose a PnP RANSAC returns, and whether it is the consensus it reports. cv::solvePnPRansac
/// returns its inliers' Levenberg-Marquardt refit, not the pose that found them; on a distant,
/// shallow scene that refit can leave the consensus altogether (docs/results.md, "A frame-to-frame
/// pose that jumped 5 m"). The rough pose and the relocaliser both ask this question of their
/// RANSAC.

#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include <vector>

namespace hbos::slam {

/// OpenCV's rotation vector and translation (object to camera, doubles) as a pose.
[[nodiscard]] Eigen::Isometry3d pose_from_rodrigues(const cv::Mat& rvec, const cv::Mat& tvec);

/// True when at least half of `inliers` (indices into `object` and `image`), and at least
/// `min_held` of them, reproject within `threshold_px` of their observations under `pose`
/// (object point to camera). A point behind the camera is not held.
[[nodiscard]] bool refit_holds_inliers(const std::vector<cv::Point3d>& object,
                                       const std::vector<cv::Point2d>& image,
                                       const std::vector<int>& inliers,
                                       const Eigen::Isometry3d& pose,
                                       const hbos::PinholeCamerad& camera, double threshold_px,
                                       int min_held);

}  // namespace hbos::slam
