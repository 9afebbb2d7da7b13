// The front end's screening stage (frontend/residual_screen.hpp) and the map tracker's points
// on probation: they are passed as flagged matches, and with provisional_consensus (the default)
// the default screen takes their coherence over one another too.

#include <catch2/catch.hpp>

#include "frontend/config.hpp"
#include "frontend/pose_refiner.hpp"
#include "frontend/residual_screen.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace {

namespace slam = hbos::slam;

const hbos::PinholeCamerad kCamera{535.4, 539.2, 320.1, 247.6};

struct Frame {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> observed;
  std::vector<double> sigma;
  slam::MatchEvidence evidence;
  std::size_t person_begin = 0;
};

// A room of proven points 3-4 m away (noise 0.4 px) and new points on probation: 60 of the
// room's, scattered, and 80 on a person 1 m away, each 1.6 px off (inside chi^2's gate).
Frame room_with_new_person_points() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), room_depth(3.0, 4.0);
  std::uniform_real_distribution<double> person_x(0.15, 0.35), person_y(-0.2, 0.2);
  std::normal_distribution<double> noise(0.0, 0.4);
  Frame f;
  const auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector2d& offset, bool fresh) {
    f.points.push_back(p);
    f.observed.push_back(kCamera.project(p) + offset + Eigen::Vector2d(noise(rng), noise(rng)));
    f.sigma.push_back(1.0);
    f.evidence.provisional.push_back(fresh ? 1 : 0);
  };
  for (int i = 0; i < 400; ++i) {
    const double z = room_depth(rng);
    add({u(rng) * 0.55 * z, u(rng) * 0.42 * z, z}, Eigen::Vector2d::Zero(), false);
  }
  for (int i = 0; i < 60; ++i) {
    const double z = room_depth(rng);
    add({u(rng) * 0.55 * z, u(rng) * 0.42 * z, z}, Eigen::Vector2d::Zero(), true);
  }
  f.person_begin = f.points.size();
  for (int i = 0; i < 80; ++i) add({person_x(rng), person_y(rng), 1.0}, {1.6, 0.3}, true);
  return f;
}

double kept_share(const slam::ScreenOutcome& out, std::size_t begin, std::size_t end) {
  std::size_t kept = 0;
  for (std::size_t i = begin; i < end; ++i) kept += out.inlier[i];
  return static_cast<double>(kept) / static_cast<double>(end - begin);
}

}  // namespace

TEST_CASE("the screening stage lets new points vouch for each other unless told not to",
          "[map][screen_stage]") {
  const Frame f = room_with_new_person_points();
  const slam::PoseRefiner refiner(slam::RefinementConfig{}, kCamera);
  const auto screen_with = [&](bool consensus) {
    slam::ScreenStageConfig config;
    config.rounds = 1;  // the screen alone: no refinement between rounds
    config.provisional_consensus = consensus;
    slam::ResidualScreen stage(config);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    return stage.screen(f.points, f.observed, f.sigma, T, refiner, f.evidence);
  };
  REQUIRE(slam::ScreenStageConfig{}.provisional_consensus);
  const slam::ScreenOutcome with = screen_with(true);
  const slam::ScreenOutcome without = screen_with(false);
  const std::size_t n = f.points.size();
  // Without: no proven point sits among the person's new ones, so nothing vouches against them.
  CHECK(kept_share(without, f.person_begin, n) > 0.8);
  CHECK(kept_share(with, f.person_begin, n) < 0.2);
  // The room's new points and the proven ones stay.
  CHECK(kept_share(with, 400, f.person_begin) > 0.95);
  CHECK(kept_share(with, 0, 400) > 0.98);
  for (std::size_t i = 0; i < 400; ++i) CHECK(with.inlier[i] == without.inlier[i]);
}
