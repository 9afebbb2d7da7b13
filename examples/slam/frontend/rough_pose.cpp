#include "frontend/rough_pose.hpp"

#include "frontend/pnp_pose.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/calib3d.hpp>

namespace hbos::slam {

RoughPoseEstimator::RoughPoseEstimator(const RoughPoseConfig& config, hbos::PinholeCamerad camera,
                                       JumpLimit jump_limit)
    : config_(config), camera_(camera), jump_limit_(jump_limit) {
  if (!(config_.ransac_threshold_px > 0.0) || config_.ransac_iterations < 1 ||
      !(config_.ransac_confidence > 0.0 && config_.ransac_confidence < 1.0) ||
      config_.min_inliers < 4) {
    throw InvalidArgument(
        fmt::format("rough pose settings: RANSAC threshold {} px must be > 0, iterations {} >= 1, "
                    "confidence {} in (0, 1), min inliers {} >= 4",
                    config_.ransac_threshold_px, config_.ransac_iterations,
                    config_.ransac_confidence, config_.min_inliers));
  }
  if (!(config_.history_rejected_share >= 0.0 && config_.history_rejected_share <= 1.0) ||
      !(config_.history_trigger_share >= 0.0 && config_.history_trigger_share <= 1.0)) {
    throw InvalidArgument(
        fmt::format("rough pose settings: history_rejected_share {} and history_trigger_share {} "
                    "must lie in [0, 1]",
                    config_.history_rejected_share, config_.history_trigger_share));
  }
}

bool RoughPoseEstimator::consensus(const std::vector<cv::Point3d>& object,
                                   const std::vector<cv::Point2d>& image,
                                   const std::vector<std::uint8_t>& use, Eigen::Isometry3d& pose,
                                   std::vector<int>& inliers) const {
  std::vector<cv::Point3d> used_object;
  std::vector<cv::Point2d> used_image;
  const std::vector<cv::Point3d>* o = &object;
  const std::vector<cv::Point2d>* i = &image;
  if (!use.empty()) {
    for (std::size_t k = 0; k < object.size(); ++k) {
      if (use[k] == 0) continue;
      used_object.push_back(object[k]);
      used_image.push_back(image[k]);
    }
    o = &used_object;
    i = &used_image;
  }
  if (static_cast<int>(o->size()) < config_.min_inliers) return false;
  const cv::Matx33d K(camera_.fx, 0.0, camera_.cx, 0.0, camera_.fy, camera_.cy, 0.0, 0.0, 1.0);
  cv::Mat rvec, tvec;
  // Keypoints are already undistorted: no distortion coefficients here.
  const bool ok = cv::solvePnPRansac(*o, *i, K, cv::noArray(), rvec, tvec,
                                     /*useExtrinsicGuess=*/false, config_.ransac_iterations,
                                     static_cast<float>(config_.ransac_threshold_px),
                                     config_.ransac_confidence, inliers);
  if (!ok || static_cast<int>(inliers.size()) < config_.min_inliers) return false;
  const Eigen::Isometry3d found = pose_from_rodrigues(rvec, tvec);
  // A refit that left its own inliers is no consensus (frontend/pnp_pose.hpp).
  if (config_.check_refit &&
      !refit_holds_inliers(*o, *i, inliers, found, camera_, config_.ransac_threshold_px,
                           config_.min_inliers)) {
    return false;
  }
  pose = found;
  return true;
}

double RoughPoseEstimator::remembered_support(const std::vector<cv::Point3d>& object,
                                              const std::vector<cv::Point2d>& image,
                                              const std::vector<OutlierShare>& memory,
                                              const Eigen::Isometry3d& pose) const {
  const double threshold2 = config_.ransac_threshold_px * config_.ransac_threshold_px;
  double support = 0.0;
  for (std::size_t k = 0; k < object.size(); ++k) {
    const Eigen::Vector3d p = pose * Eigen::Vector3d(object[k].x, object[k].y, object[k].z);
    if (!(p.z() > 0.0)) continue;
    const Eigen::Vector2d r = camera_.project(p) - Eigen::Vector2d(image[k].x, image[k].y);
    if (r.squaredNorm() <= threshold2) support += memory[k].static_trust();
  }
  return support;
}

RoughPose RoughPoseEstimator::estimate(const std::vector<Eigen::Vector3d>& points_prev,
                                       const std::vector<Eigen::Vector2d>& observed,
                                       const Eigen::Isometry3d& constant_velocity,
                                       const std::vector<OutlierShare>& memory) const {
  const RoughPose pose = best_consensus(points_prev, observed, constant_velocity, memory);
  // A consensus that puts the camera further from the prediction than the jump limit allows
  // (JumpLimit::departs_from_prediction) is a wrong one, e.g. a person holding a third of the
  // matches: the prediction stays.
  if (pose.from_ransac &&
      jump_limit_.departs_from_prediction(pose.T_cur_prev * constant_velocity.inverse()))
    return RoughPose{constant_velocity};
  return pose;
}

RoughPose RoughPoseEstimator::best_consensus(const std::vector<Eigen::Vector3d>& points_prev,
                                             const std::vector<Eigen::Vector2d>& observed,
                                             const Eigen::Isometry3d& constant_velocity,
                                             const std::vector<OutlierShare>& memory) const {
  RoughPose pose;
  pose.T_cur_prev = constant_velocity;
  if (config_.method == RoughPoseMethod::kConstantVelocity ||
      static_cast<int>(points_prev.size()) < config_.min_inliers) {
    return pose;
  }
  detail::require(memory.empty() || memory.size() == points_prev.size(),
                  "rough pose: ", memory.size(), " track memories for ", points_prev.size(),
                  " matches");
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  object.reserve(points_prev.size());
  image.reserve(points_prev.size());
  for (std::size_t i = 0; i < points_prev.size(); ++i) {
    object.emplace_back(points_prev[i].x(), points_prev[i].y(), points_prev[i].z());
    image.emplace_back(observed[i].x(), observed[i].y());
  }
  std::vector<int> inliers;
  if (!consensus(object, image, {}, pose.T_cur_prev, inliers)) return pose;
  pose.from_ransac = true;
  pose.ransac_inliers = static_cast<int>(inliers.size());
  if (!config_.history_consensus || memory.empty()) return pose;

  // The largest consensus is not always the world: a person close to the camera, holding a fifth
  // of the matches, plus the far background its motion barely moves, can outnumber the rest.
  // The tracks remember which matches the screen rejected in earlier frames; when the consensus
  // leans on many such tracks, the consensus of the tracks mostly kept is the other candidate.
  // A track never screened is not among them: it has no memory, and a person's tracks are born
  // again and again as the body turns (docs/results.md, stop 27).
  const auto rejected = [&](std::size_t k) {
    return memory[k].share() > config_.history_rejected_share;
  };
  std::size_t leaning = 0;
  for (const int k : inliers) leaning += rejected(static_cast<std::size_t>(k)) ? 1U : 0U;
  if (static_cast<double>(leaning) <
      config_.history_trigger_share * static_cast<double>(inliers.size()))
    return pose;
  std::vector<std::uint8_t> kept(object.size());
  for (std::size_t k = 0; k < object.size(); ++k)
    kept[k] = !rejected(k) && memory[k].screenings() > 0.0 ? 1 : 0;
  Eigen::Isometry3d other;
  std::vector<int> other_inliers;
  if (!consensus(object, image, kept, other, other_inliers)) return pose;
  // Both judged on every match, each inlier weighted by how far its track's screenings vouch
  // for it: a newborn track counts for nothing, not as a track never rejected.
  if (remembered_support(object, image, memory, other) >
      remembered_support(object, image, memory, pose.T_cur_prev)) {
    pose.T_cur_prev = other;
    pose.ransac_inliers = static_cast<int>(other_inliers.size());
    pose.from_remembered_statics = true;
  }
  return pose;
}

}  // namespace hbos::slam
