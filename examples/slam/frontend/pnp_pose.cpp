#include "frontend/pnp_pose.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include <cstddef>

namespace hbos::slam {

Eigen::Isometry3d pose_from_rodrigues(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d rotation;
  cv::cv2eigen(cv::Mat(R), rotation);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  return pose;
}

bool refit_holds_inliers(const std::vector<cv::Point3d>& object,
                         const std::vector<cv::Point2d>& image, const std::vector<int>& inliers,
                         const Eigen::Isometry3d& pose, const hbos::PinholeCamerad& camera,
                         double threshold_px, int min_held) {
  const double threshold2 = threshold_px * threshold_px;
  std::size_t held = 0;
  for (const int k : inliers) {
    const auto& q = object[static_cast<std::size_t>(k)];
    const Eigen::Vector3d p = pose * Eigen::Vector3d(q.x, q.y, q.z);
    if (!(p.z() > 0.0)) continue;
    const auto& u = image[static_cast<std::size_t>(k)];
    if ((camera.project(p) - Eigen::Vector2d(u.x, u.y)).squaredNorm() <= threshold2) ++held;
  }
  // The refit of a sound consensus moves few of its inliers across the threshold (about as many
  // in as out); half lost is a different pose.
  return 2 * held >= inliers.size() && static_cast<int>(held) >= min_held;
}

}  // namespace hbos::slam
