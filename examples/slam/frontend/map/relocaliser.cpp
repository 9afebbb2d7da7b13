#include "frontend/map/relocaliser.hpp"

#include "frontend/pnp_pose.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>

namespace hbos::slam {

Relocaliser::Relocaliser(const RelocalisationConfig& config, hbos::PinholeCamerad camera)
    : config_(config), camera_(camera) {}

Relocalisation Relocaliser::relocalise(const Map& map, const ProjectionMatcher& matcher,
                                       const Features& current, std::vector<int>& point_of) const {
  Relocalisation out;
  const cv::Matx33d K(camera_.fx, 0.0, camera_.cx, 0.0, camera_.fy, camera_.cy, 0.0, 0.0, 1.0);
  const int last = map.keyframes() - 1;
  const int first = std::max(0, map.keyframes() - config_.recent_keyframes);
  for (int kf = last; kf >= first; --kf) {
    std::fill(point_of.begin(), point_of.end(), -1);
    if (matcher.match_keyframe(map, map.keyframe(kf), current, config_.ratio, point_of) <
        config_.min_matches) {
      continue;
    }
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    std::vector<int> keypoint;
    for (std::size_t k = 0; k < point_of.size(); ++k) {
      if (point_of[k] < 0) continue;
      const Eigen::Vector3d& p = map.point(point_of[k]).position_world;
      object.emplace_back(p.x(), p.y(), p.z());
      image.emplace_back(current.undistorted[k].x(), current.undistorted[k].y());
      keypoint.push_back(static_cast<int>(k));
    }
    cv::Mat rvec, tvec;
    std::vector<int> inliers;
    const bool ok = cv::solvePnPRansac(
        object, image, K, cv::noArray(), rvec, tvec, false, config_.ransac_iterations,
        static_cast<float>(config_.ransac_threshold_px), 0.99, inliers, cv::SOLVEPNP_EPNP);
    if (!ok || static_cast<int>(inliers.size()) < config_.min_pnp_inliers) continue;
    const Eigen::Isometry3d T_camera_world = pose_from_rodrigues(rvec, tvec);
    // RANSAC returns its inliers' refit, which can leave them (frontend/pnp_pose.hpp): then
    // this keyframe gave no pose, and an older one may.
    if (config_.check_refit &&
        !refit_holds_inliers(object, image, inliers, T_camera_world, camera_,
                             config_.ransac_threshold_px, config_.min_pnp_inliers)) {
      continue;
    }
    // Keep the inliers' matches only.
    std::vector<int> kept(point_of.size(), -1);
    for (const int m : inliers) {
      const auto k = static_cast<std::size_t>(keypoint[static_cast<std::size_t>(m)]);
      kept[k] = point_of[k];
    }
    point_of = std::move(kept);
    out.T_camera_world = T_camera_world;
    out.found = true;
    out.keyframe = kf;
    out.pnp_inliers = static_cast<int>(inliers.size());
    return out;
  }
  std::fill(point_of.begin(), point_of.end(), -1);
  return out;
}

}  // namespace hbos::slam
