// The front end's screening stage (frontend/residual_screen.hpp): the map tracker's points on
// probation are passed as flagged matches, and with provisional_consensus (the default) the
// default screen takes their coherence over one another too; the rounds after the first gate at
// their own floor (later_rounds_gate_floor).

#include <catch2/catch.hpp>

#include "frontend/config.hpp"
#include "frontend/pose_refiner.hpp"
#include "frontend/residual_screen.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
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

namespace {

// A room of 500 points 3-4 m away (noise 0.3 px) under the true pose, 40 of them observed
// 2.25 px off in a random direction: inside chi^2's gate (2.447 px/sigma at sigma 1), beyond a
// gate of 2.0.
Frame room_with_a_tail(std::size_t& tail_begin) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), room_depth(3.0, 4.0), angle(0.0, 6.283);
  std::normal_distribution<double> noise(0.0, 0.3);
  Frame f;
  tail_begin = 460;
  for (std::size_t i = 0; i < 500; ++i) {
    const double z = room_depth(rng);
    const Eigen::Vector3d p(u(rng) * 0.55 * z, u(rng) * 0.42 * z, z);
    const double a = angle(rng);
    const Eigen::Vector2d off = i >= tail_begin
                                    ? Eigen::Vector2d(2.25 * std::cos(a), 2.25 * std::sin(a))
                                    : Eigen::Vector2d(noise(rng), noise(rng));
    f.points.push_back(p);
    f.observed.push_back(kCamera.project(p) + off);
    f.sigma.push_back(1.0);
  }
  return f;
}

/// Screens `f` with a stage of `config` that screened it before under `first_refiner`, and
/// with a fresh stage, both under `refiner`: nothing may carry over from one call to the next.
void check_used_stage_gives_fresh_bits(const slam::ScreenStageConfig& config, const Frame& f,
                                       const slam::PoseRefiner& first_refiner,
                                       const slam::PoseRefiner& refiner) {
  slam::ResidualScreen used(config), fresh(config);
  Eigen::Isometry3d T1 = Eigen::Isometry3d::Identity(), T2 = T1;
  (void)used.screen(f.points, f.observed, f.sigma, T1, first_refiner, f.evidence);
  T1 = Eigen::Isometry3d::Identity();
  const slam::ScreenOutcome again = used.screen(f.points, f.observed, f.sigma, T1, refiner);
  const slam::ScreenOutcome first = fresh.screen(f.points, f.observed, f.sigma, T2, refiner);
  CHECK(again.magnitude == first.magnitude);
  CHECK(T1.matrix() == T2.matrix());
}

}  // namespace

TEST_CASE("the screening stage's later rounds gate at their own floor, the first at chi^2's",
          "[screen_stage]") {
  std::size_t tail = 0;
  const Frame f = room_with_a_tail(tail);
  const slam::PoseRefiner refiner(slam::RefinementConfig{}, kCamera);
  const auto screen_with = [&](int rounds, double later_floor) {
    slam::ScreenStageConfig config;
    config.rounds = rounds;
    config.later_rounds_gate_floor = later_floor;
    slam::ResidualScreen stage(config);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    return stage.screen(f.points, f.observed, f.sigma, T, refiner, f.evidence);
  };
  // Unset, each tracker resolves its own; the stage alone screens every round alike.
  slam::Config map_config, frame_config;
  map_config.tracker = slam::TrackerKind::kMap;
  CHECK(slam::later_rounds_gate_floor(map_config) == 0.0);
  CHECK(slam::later_rounds_gate_floor(frame_config) ==
        Approx(3.0 * hbos::NoiseGate{}.min_scale).epsilon(1e-15));
  CHECK(slam::screen_stage_for(frame_config).later_rounds_gate_floor ==
        slam::later_rounds_gate_floor(frame_config));
  map_config.screen.later_rounds_gate_floor = 1.5;  // set: the same for either tracker
  CHECK(slam::later_rounds_gate_floor(map_config) == 1.5);
  CHECK_FALSE(slam::ScreenStageConfig{}.later_rounds_gate_floor.has_value());
  const std::size_t n = f.points.size();
  // The first round is chi^2's gate whatever the later floor: the tail is kept.
  const slam::ScreenOutcome one_round = screen_with(1, 2.0);
  CHECK(one_round.inlier == screen_with(1, 0.0).inlier);
  CHECK(kept_share(one_round, tail, n) == 1.0);
  // After a refinement the gate closes to max(2.0, 3 s): the tail goes, the room stays.
  const slam::ScreenOutcome later = screen_with(4, 2.0);
  CHECK(later.rounds == 4);
  CHECK(later.magnitude_cut == Approx(2.0));
  CHECK(kept_share(later, tail, n) == 0.0);
  CHECK(kept_share(later, 0, tail) > 0.99);
  // Nothing carries over from one frame to the next: the first round of every call is judged at
  // chi^2's floor again, so a stage that screened before gives a fresh stage's bits.
  {
    slam::ScreenStageConfig config;
    config.later_rounds_gate_floor = 2.0;
    check_used_stage_gives_fresh_bits(config, f, refiner, refiner);
  }
  // With 0 every round keeps chi^2's floor.
  const slam::ScreenOutcome same = screen_with(4, 0.0);
  CHECK(same.magnitude_cut == Approx(2.447));
  CHECK(kept_share(same, tail, n) == 1.0);
  // A baseline has no noise gate to lower: the setting changes nothing.
  slam::ScreenStageConfig chi2;
  chi2.select("chi2");
  const auto chi2_with = [&](double later_floor) {
    chi2.later_rounds_gate_floor = later_floor;
    slam::ResidualScreen stage(chi2);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    return stage.screen(f.points, f.observed, f.sigma, T, refiner, f.evidence).inlier;
  };
  CHECK(chi2_with(2.0) == chi2_with(0.0));
}

TEST_CASE("the screening stage refits a rigid field in the later rounds: both trackers' own",
          "[screen_stage]") {
  slam::Config map_config, frame_config;
  map_config.tracker = slam::TrackerKind::kMap;
  CHECK(slam::later_rounds_rigid_field(frame_config));
  CHECK(slam::later_rounds_rigid_field(map_config));
  CHECK(slam::screen_stage_for(frame_config).later_rounds_rigid_field == true);
  CHECK(slam::screen_stage_for(map_config).later_rounds_rigid_field == true);
  map_config.screen.later_rounds_rigid_field = false;  // set: taken as it is
  CHECK_FALSE(slam::later_rounds_rigid_field(map_config));
  CHECK_FALSE(slam::screen_stage_for(map_config).later_rounds_rigid_field.value());
  CHECK_FALSE(slam::ScreenStageConfig{}.later_rounds_rigid_field.has_value());

  std::size_t tail = 0;
  const Frame f = room_with_a_tail(tail);
  const auto stage_config = [](int rounds, bool rigid) {
    slam::ScreenStageConfig config;
    config.rounds = rounds;
    config.later_rounds_gate_floor = 2.0;
    config.later_rounds_rigid_field = rigid;
    return config;
  };
  const slam::PoseRefiner refiner(slam::RefinementConfig{}, kCamera);
  const auto screen_with = [&](int rounds, bool rigid) {
    slam::ResidualScreen stage(stage_config(rounds, rigid));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    return stage.screen(f.points, f.observed, f.sigma, T, refiner, f.evidence);
  };
  // The first round is the same screen either way.
  CHECK(screen_with(1, true).magnitude == screen_with(1, false).magnitude);
  // After it, the room stays and the tail goes, as with the affine refit.
  const slam::ScreenOutcome rigid = screen_with(4, true);
  CHECK(rigid.rounds == 4);
  CHECK(kept_share(rigid, tail, f.points.size()) == 0.0);
  CHECK(kept_share(rigid, 0, tail) > 0.99);
  // The intrinsics are the refiner's of each call: a stage that screened with another camera
  // gives a fresh stage's bits.
  hbos::PinholeCamerad other = kCamera;
  other.fx *= 1.05;
  const slam::PoseRefiner other_refiner(slam::RefinementConfig{}, other);
  check_used_stage_gives_fresh_bits(stage_config(4, true), f, other_refiner, refiner);
}

TEST_CASE("the screening stage refuses a later rounds' floor that is negative or not finite",
          "[screen_stage]") {
  for (const double bad : {-0.5, std::numeric_limits<double>::infinity()}) {
    slam::ScreenStageConfig config;
    config.later_rounds_gate_floor = bad;
    CHECK_THROWS_WITH(slam::ResidualScreen(config), Catch::Contains("later rounds' gate floor") &&
                                                        Catch::Contains("must be finite and >= 0"));
  }
}
