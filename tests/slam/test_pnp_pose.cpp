// The check both PnP RANSACs of the front end make of the pose they return
// (frontend/pnp_pose.hpp): a refit holds its consensus when half of its inliers still lie
// within the threshold.

#include <catch2/catch.hpp>

#include "frontend/pnp_pose.hpp"

#include <random>
#include <vector>

namespace {

/// `n` points at 2-6 m in front of the camera, observed exactly under `pose`.
struct Scene {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  std::vector<int> inliers;
};

Scene exact_scene(const Eigen::Isometry3d& pose, int n, unsigned seed) {
  const hbos::PinholeCamerad camera;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(20.0, 620.0), v(20.0, 460.0), depth(2.0, 6.0);
  Scene s;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d in_camera = camera.back_project({u(rng), v(rng)}, depth(rng));
    const Eigen::Vector3d p = pose.inverse() * in_camera;
    s.object.emplace_back(p.x(), p.y(), p.z());
    s.image.emplace_back(camera.project(in_camera).x(), camera.project(in_camera).y());
    s.inliers.push_back(i);
  }
  return s;
}

}  // namespace

TEST_CASE("pnp refit: the pose that produced the observations holds every inlier",
          "[frontend][rough_pose]") {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(0.1, -0.05, 0.3));
  pose.rotate(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, 1.0, 0.1).normalized()));
  for (const unsigned seed : {1U, 2U, 3U}) {
    const Scene s = exact_scene(pose, 60, seed);
    CAPTURE(seed);
    CHECK(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, pose, {}, 1.0, 60));
    // One more than it has is too many.
    CHECK_FALSE(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, pose, {}, 1.0, 61));
    // A pose 10 cm to the side moves points at 2-6 m by 9-27 px (fx 535.4): none is held.
    Eigen::Isometry3d moved = pose;
    moved.pretranslate(Eigen::Vector3d(0.1, 0.0, 0.0));
    CHECK_FALSE(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, moved, {}, 1.0, 4));
  }
}

TEST_CASE("pnp refit: exactly half of the inliers held is enough and one fewer is not",
          "[frontend][rough_pose]") {
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Scene s = exact_scene(pose, 40, 7);
  // Push 20 observations 1.5 px off (beyond a 1 px threshold), then a 21st.
  for (int i = 0; i < 20; ++i) s.image[static_cast<std::size_t>(i)].x += 1.5;
  CHECK(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, pose, {}, 1.0, 4));
  s.image[20].y -= 1.5;
  CHECK_FALSE(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, pose, {}, 1.0, 4));
  // Only the listed inliers count: the displaced ones left out, the rest are all held.
  const std::vector<int> rest = {21, 22, 23, 24, 25, 26, 27, 28, 29, 30};
  CHECK(hbos::slam::refit_holds_inliers(s.object, s.image, rest, pose, {}, 1.0, 10));
  // A 2 px threshold holds the displaced ones too.
  CHECK(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, pose, {}, 2.0, 40));
}

TEST_CASE("pnp refit: a point behind the camera is never held", "[frontend][rough_pose]") {
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Scene s = exact_scene(pose, 10, 3);
  // Mirrored through the camera centre, a point projects to the same pixel, from behind.
  for (std::size_t i = 0; i < 6; ++i) s.object[i] = -s.object[i];
  CHECK_FALSE(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, pose, {}, 1.0, 4));
  for (std::size_t i = 0; i < 6; ++i) s.object[i] = -s.object[i];
  CHECK(hbos::slam::refit_holds_inliers(s.object, s.image, s.inliers, pose, {}, 1.0, 10));
}
