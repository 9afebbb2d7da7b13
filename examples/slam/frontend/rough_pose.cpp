#include "frontend/rough_pose.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace hbos::slam {

RoughPoseEstimator::RoughPoseEstimator(const RoughPoseConfig& config, hbos::PinholeCamerad camera)
    : config_(config), camera_(camera) {
  if (!(config_.ransac_threshold_px > 0.0) || config_.ransac_iterations < 1 ||
      !(config_.ransac_confidence > 0.0 && config_.ransac_confidence < 1.0) ||
      config_.min_inliers < 4) {
    throw InvalidArgument(
        fmt::format("rough pose settings: RANSAC threshold {} px must be > 0, iterations {} >= 1, "
                    "confidence {} in (0, 1), min inliers {} >= 4",
                    config_.ransac_threshold_px, config_.ransac_iterations,
                    config_.ransac_confidence, config_.min_inliers));
  }
}

RoughPose RoughPoseEstimator::estimate(const std::vector<Eigen::Vector3d>& points_prev,
                                       const std::vector<Eigen::Vector2d>& observed,
                                       const Eigen::Isometry3d& constant_velocity) const {
  RoughPose pose;
  pose.T_cur_prev = constant_velocity;
  if (config_.method == RoughPoseMethod::kConstantVelocity ||
      static_cast<int>(points_prev.size()) < config_.min_inliers) {
    return pose;
  }
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  object.reserve(points_prev.size());
  image.reserve(points_prev.size());
  for (std::size_t i = 0; i < points_prev.size(); ++i) {
    object.emplace_back(points_prev[i].x(), points_prev[i].y(), points_prev[i].z());
    image.emplace_back(observed[i].x(), observed[i].y());
  }
  const cv::Matx33d K(camera_.fx, 0.0, camera_.cx, 0.0, camera_.fy, camera_.cy, 0.0, 0.0, 1.0);
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  // Keypoints are already undistorted: no distortion coefficients here.
  const bool ok = cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec,
                                     /*useExtrinsicGuess=*/false, config_.ransac_iterations,
                                     static_cast<float>(config_.ransac_threshold_px),
                                     config_.ransac_confidence, inliers);
  if (!ok || static_cast<int>(inliers.size()) < config_.min_inliers) return pose;
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d rotation;
  cv::cv2eigen(cv::Mat(R), rotation);
  pose.T_cur_prev.linear() = rotation;
  pose.T_cur_prev.translation() =
      Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  pose.from_ransac = true;
  pose.ransac_inliers = static_cast<int>(inliers.size());
  return pose;
}

}  // namespace hbos::slam
