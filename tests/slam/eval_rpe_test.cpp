// RPE properties: the script's nearest-index search, zero for identical or globally transformed
// trajectories, known drift rates recovered, the delta units, the "last index" quirk, the
// 2 × median ground-truth tolerance and self-pairs across estimate gaps.
#include "eval/associate.hpp"
#include "eval/rpe.hpp"
#include "eval_test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using Catch::Matchers::Contains;
using hbos::slam::compute_rpe;
using hbos::slam::find_closest_index;
using hbos::slam::RpeDeltaUnit;
using hbos::slam::RpeParams;
using hbos::slam::RpeResult;
using hbos::slam::Trajectory;
using hbos::slam::test::random_rotation;
using hbos::slam::test::random_vector;
using hbos::slam::test::synthetic_trajectory;
using hbos::slam::test::transformed;

namespace {

RpeParams delta(double value, RpeDeltaUnit unit) {
  RpeParams p;
  p.delta = value;
  p.unit = unit;
  return p;
}

// A ground truth standing still in orientation while moving along x at `speed`, sampled every
// `period` seconds, and an estimate of it that drifts: extra velocity `drift` [m/s] and yaw rate
// `yaw_rate` [rad/s].
Trajectory straight_line(Eigen::Index n, double period, double speed, const Eigen::Vector3d& drift,
                         double yaw_rate, const std::string& name) {
  std::vector<double> stamps;
  std::vector<Eigen::Isometry3d> poses;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * period;
    stamps.push_back(1000.0 + t);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(speed * t, 0.0, 0.0) + drift * t;
    pose.linear() = Eigen::AngleAxisd(yaw_rate * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    poses.push_back(pose);
  }
  return hbos::slam::make_trajectory(name, stamps, poses);
}

}  // namespace

TEST_CASE("find_closest_index: nearest element, first probed on ties", "[eval][rpe]") {
  const std::vector<double> v = {0.0, 1.0, 2.0, 3.0, 4.0};
  CHECK(find_closest_index(v, 2.4) == 2);
  CHECK(find_closest_index(v, 2.6) == 3);
  CHECK(find_closest_index(v, 3.0) == 3);
  CHECK(find_closest_index(v, -5.0) == 0);
  CHECK(find_closest_index(v, 10.0) == 4);
  // 2.5 is as near to 2 as to 3; the search probes index 2 before index 3.
  CHECK(find_closest_index(v, 2.5) == 2);
  // 0.5 ties 0 and 1: index 0 is the initial best and index 1 is probed later, not nearer.
  CHECK(find_closest_index(v, 0.5) == 0);
  CHECK(find_closest_index({7.0}, -1.0) == 0);
  CHECK_THROWS_WITH(find_closest_index({}, 1.0), Contains("empty"));

  std::mt19937 rng(2);
  std::uniform_real_distribution<double> uniform(0.0, 100.0);
  for (int k = 0; k < 200; ++k) {
    std::vector<double> values(1 + rng() % 50);
    for (double& x : values) x = uniform(rng);
    std::sort(values.begin(), values.end());
    const double t = uniform(rng) * 1.2 - 10.0;
    double nearest = INFINITY;
    for (const double x : values) nearest = std::min(nearest, std::abs(x - t));
    CHECK(std::abs(values[static_cast<std::size_t>(find_closest_index(values, t))] - t) == nearest);
  }
}

TEST_CASE("RPE of a trajectory against itself, or against a global transform of it, is zero",
          "[eval][rpe]") {
  std::mt19937 rng(6);
  const Trajectory gt = synthetic_trajectory(800, 1305031102.0, 0.01);
  const Trajectory moved = transformed(gt, random_rotation(rng), random_vector(rng, 3.0), 1.0);
  for (const Trajectory* est : {&gt, &moved}) {
    const RpeResult r = compute_rpe(gt, *est);
    CHECK(r.trans_m.count > 600);
    CHECK(r.trans_m.max < 1e-12);
    // arccos near 1 amplifies rounding: a zero angle computes as up to ~2e-8 rad. This is the
    // floor of the script's formula, kept for parity.
    CHECK(r.rot_deg.max < 1e-5);
    CHECK(r.n_pairs_with_i_equal_j == 0);
  }
}

TEST_CASE("RPE recovers known drift rates per delta", "[eval][rpe]") {
  const Trajectory gt = straight_line(2000, 0.01, 0.5, Eigen::Vector3d::Zero(), 0.0, "gt");
  const double yaw_rate = 2.0 * 3.141592653589793 / 180.0;  // 2 deg/s
  const Trajectory est =
      straight_line(2000, 0.01, 0.5, Eigen::Vector3d(0.0, 0.03, 0.0), yaw_rate, "est");
  for (const double seconds : {0.5, 1.0, 2.0}) {
    const RpeResult r = compute_rpe(gt, est, delta(seconds, RpeDeltaUnit::kSeconds));
    INFO("delta " << seconds << " s");
    // Rotation: the estimate turns by 2 deg/s more than the ground truth.
    CHECK(r.rot_deg.mean == Approx(2.0 * seconds).epsilon(1e-9));
    CHECK(r.rot_deg.std_dev < 1e-6);
    // Translation: gt moves 0.5·Δ along x without turning; the estimate's relative motion,
    // expressed in its own (turned) frame, differs from it by a rotation-dependent amount, so
    // compare with the closed form for pose i → j.
    for (const auto& pair : r.pairs) {
      const double dt = est.stamps[static_cast<std::size_t>(pair.est1)] -
                        est.stamps[static_cast<std::size_t>(pair.est0)];
      const double ti = est.stamps[static_cast<std::size_t>(pair.est0)] - 1000.0;
      // E_j⁻¹E_i = [R(−ω dt) | R(−ω t_j)(p_i − p_j)], G_j⁻¹G_i = [I | (−0.5 dt, 0, 0)].
      const Eigen::Vector3d pi(0.5 * ti, 0.03 * ti, 0.0);
      const Eigen::Vector3d pj(0.5 * (ti + dt), 0.03 * (ti + dt), 0.0);
      const Eigen::Matrix3d rj =
          Eigen::AngleAxisd(yaw_rate * (ti + dt), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Matrix3d rel_rot =
          Eigen::AngleAxisd(-yaw_rate * dt, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Vector3d rel_trans = rj.transpose() * (pi - pj);
      // error = (E_j⁻¹E_i)⁻¹ G_j⁻¹G_i, translation: R_relᵀ (t_G − t_rel)
      const Eigen::Vector3d expected =
          rel_rot.transpose() * (Eigen::Vector3d(-0.5 * dt, 0.0, 0.0) - rel_trans);
      CHECK(pair.trans_error == Approx(expected.norm()).epsilon(1e-9));
    }
  }
}

TEST_CASE("RPE delta in frames pairs i with i + delta and drops pairs ending on the last pose",
          "[eval][rpe]") {
  const Trajectory gt = synthetic_trajectory(200, 0.0, 0.01);
  const RpeResult r = compute_rpe(gt, gt, delta(5, RpeDeltaUnit::kFrames));
  // i = 0 .. 193 give j = i + 5 <= 198; i = 194 gives j = 199, the last pose, which the script
  // drops; larger i clamp to the last pose too.
  CHECK(r.n_candidates == 194);
  CHECK(r.pairs.size() == 194);
  for (const auto& pair : r.pairs) CHECK(pair.est1 - pair.est0 == 5);
  CHECK_THROWS_WITH(compute_rpe(gt, gt, delta(2.5, RpeDeltaUnit::kFrames)),
                    Contains("whole number"));
}

TEST_CASE("RPE delta in metres is measured along the ground truth", "[eval][rpe]") {
  const Trajectory gt = straight_line(1000, 0.01, 0.5, Eigen::Vector3d::Zero(), 0.0, "gt");
  // The estimate is twice too long: by its own path length (evaluate_rpe.py's 'm'), 1 m would
  // be 1 s; along the ground truth it is 2 s.
  const Trajectory est = straight_line(1000, 0.01, 1.0, Eigen::Vector3d::Zero(), 0.0, "est");
  const RpeResult r = compute_rpe(gt, est, delta(1.0, RpeDeltaUnit::kMetresAlongGt));
  REQUIRE(r.pairs.size() > 700);
  for (const auto& pair : r.pairs) {
    CHECK(std::abs(gt.stamps[static_cast<std::size_t>(pair.gt1)] -
                   gt.stamps[static_cast<std::size_t>(pair.gt0)] - 2.0) < 0.0051);
    CHECK(pair.trans_error == Approx(1.0).epsilon(1e-9));  // 2 m vs 1 m travelled
  }
}

TEST_CASE("RPE ground-truth tolerance is 2 x the median ground-truth period, not 0.02 s",
          "[eval][rpe]") {
  // 10 Hz ground truth: tolerance 0.2 s. Estimate stamps 0.04 s after the ground truth's are
  // too far for the ATE association (0.02 s) but fine for the RPE.
  const Trajectory gt10 = synthetic_trajectory(300, 0.0, 0.1);
  const Trajectory late = synthetic_trajectory(250, 0.04, 0.1);
  const RpeResult r = compute_rpe(gt10, late);
  CHECK(r.gt_max_time_difference == Approx(0.2).epsilon(1e-9));
  CHECK(r.pairs.size() == 250 - 11);  // delta 1 s = 10 poses; pairs ending on the last dropped
  CHECK(hbos::slam::associate(gt10, late).empty());

  // 100 Hz ground truth recorded in bursts (3 samples every 0.1 s): median period 0.01 s, so the
  // tolerance is 0.02 s, and estimate stamps between the bursts (0.04 s from the nearest ground
  // truth) are all skipped; the RPE is then refused.
  const Trajectory dense = synthetic_trajectory(3000, 0.0, 0.01);
  std::vector<double> stamps;
  std::vector<Eigen::Isometry3d> poses;
  for (Eigen::Index i = 0; i < dense.size(); ++i) {
    if (i % 10 >= 3) continue;
    stamps.push_back(dense.stamps[static_cast<std::size_t>(i)]);
    poses.push_back(dense.pose(i));
  }
  const Trajectory bursts = hbos::slam::make_trajectory("bursts", stamps, poses);
  const Trajectory between = synthetic_trajectory(280, 0.06, 0.1);
  CHECK_THROWS_WITH(compute_rpe(bursts, between),
                    Contains("only 0 pose pairs have ground truth within 0.02"));
}

TEST_CASE("RPE across an estimate gap longer than delta compares a pose with itself",
          "[eval][rpe]") {
  const Trajectory gt = synthetic_trajectory(1500, 0.0, 0.01);
  // Drop 3 s of estimate (tracking lost): for the pose before the gap, the pose nearest to
  // "t + 1 s" is itself.
  std::vector<double> stamps;
  std::vector<Eigen::Isometry3d> poses;
  for (Eigen::Index i = 0; i < gt.size(); ++i) {
    if (i > 500 && i < 800) continue;
    stamps.push_back(gt.stamps[static_cast<std::size_t>(i)]);
    poses.push_back(gt.pose(i));
  }
  const Trajectory est = hbos::slam::make_trajectory("gappy", stamps, poses);
  const RpeResult r = compute_rpe(gt, est);
  CHECK(r.n_pairs_with_i_equal_j > 0);
  for (const auto& pair : r.pairs) {
    if (pair.est0 == pair.est1) CHECK(pair.trans_error < 1e-15);
  }
}

TEST_CASE("RPE scale factor, overlap check and parameter checks", "[eval][rpe]") {
  std::mt19937 rng(12);
  const Trajectory gt = synthetic_trajectory(400, 0.0, 0.01);
  const Trajectory big = transformed(gt, random_rotation(rng), random_vector(rng, 1.0), 4.0);
  RpeParams scaled;
  scaled.est_scale = 0.25;
  CHECK(compute_rpe(gt, big, scaled).trans_m.max < 1e-12);
  CHECK(compute_rpe(gt, big).trans_m.mean > 0.05);

  const Trajectory late = synthetic_trajectory(400, 500.0, 0.01, "late.txt");
  CHECK_THROWS_WITH(compute_rpe(gt, late), Contains("hardly overlap in time"));
  CHECK_THROWS_WITH(compute_rpe(gt, gt, delta(0.0, RpeDeltaUnit::kSeconds)), Contains("delta"));
  RpeParams bad_scale;
  bad_scale.est_scale = -1.0;
  CHECK_THROWS_WITH(compute_rpe(gt, gt, bad_scale), Contains("est_scale"));
  // A delta longer than the sequence leaves no pair; far longer (1e16 s), the sums rounded to one
  // number and every pose was paired with the first, exit 0.
  for (const double d : {10.0, 1e16})
    CHECK_THROWS_WITH(compute_rpe(gt, gt, delta(d, RpeDeltaUnit::kSeconds)),
                      Contains("exceeds the whole span of"));
  CHECK_THROWS_WITH(compute_rpe(gt, gt, delta(1e18, RpeDeltaUnit::kFrames)),
                    Contains("exceeds the whole span of"));
}
