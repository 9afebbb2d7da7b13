// ATE properties: zero for identical and for rigidly / similarly transformed trajectories,
// recovery of the transform, the fixed scale factor, and the share tracked.
#include "eval/ate.hpp"
#include "eval/evaluate.hpp"
#include "eval/tracked_share.hpp"
#include "eval_test_support.hpp"

#include <catch2/catch.hpp>

#include <random>

using Catch::Matchers::Contains;
using hbos::slam::AlignmentKind;
using hbos::slam::AteParams;
using hbos::slam::AteResult;
using hbos::slam::compute_ate;
using hbos::slam::Trajectory;
using hbos::slam::test::random_rotation;
using hbos::slam::test::random_vector;
using hbos::slam::test::synthetic_trajectory;
using hbos::slam::test::transformed;

namespace {

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

AteParams sim3() {
  AteParams p;
  p.alignment = AlignmentKind::kSim3;
  return p;
}

// The estimate at other stamps: every pose of `gt` shifted in time by `shift` (< max_difference),
// so association has to do real work.
Trajectory shifted(const Trajectory& t, double shift) {
  Trajectory s = t;
  for (double& stamp : s.stamps) stamp += shift;
  return s;
}

}  // namespace

TEST_CASE("ATE of a trajectory against itself is zero", "[eval][ate]") {
  const Trajectory gt = synthetic_trajectory(300, 1305031102.0, 0.01);
  for (const AteParams& params : {AteParams{}, sim3()}) {
    const AteResult ate = compute_ate(gt, gt, params);
    CHECK(ate.stats.count == 300);
    CHECK(ate.stats.max < 1e-14);
    CHECK(ate.stats.rmse < 1e-14);
    CHECK(max_abs(ate.alignment.rotation - Eigen::Matrix3d::Identity()) < 1e-14);
    CHECK(std::abs(ate.alignment.scale - 1.0) < 1e-14);
  }
}

TEST_CASE("ATE recovers a known SE(3) between estimate and ground truth", "[eval][ate]") {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(seed);
    const Trajectory gt = synthetic_trajectory(400, 1305031102.0, 0.01);
    // The estimate lives in its own world frame: est = T_est_gt · gt, with stamps 4 ms late.
    const Eigen::Matrix3d r = random_rotation(rng);
    const Eigen::Vector3d t = random_vector(rng, 5.0);
    const Trajectory est = shifted(transformed(gt, r, t, 1.0), 0.004);
    const AteResult ate = compute_ate(gt, est);
    INFO("seed " << seed);
    CHECK(ate.stats.count == 400);
    CHECK(ate.stats.max < 1e-12);
    // The alignment maps the estimate back: R_gt_est = rᵀ, t_gt_est = −rᵀ t.
    CHECK(max_abs(ate.alignment.rotation - r.transpose()) < 1e-13);
    CHECK(max_abs(ate.alignment.translation + r.transpose() * t) < 1e-12);
    CHECK(ate.alignment.scale == 1.0);
    CHECK(max_abs(ate.aligned_positions - ate.gt_positions) < 1e-12);
  }
}

TEST_CASE("Sim(3) ATE recovers a known similarity, SE(3) ATE cannot", "[eval][ate]") {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(50 + seed);
    const Trajectory gt = synthetic_trajectory(200, 100.0, 1.0 / 30.0);
    const Eigen::Matrix3d r = random_rotation(rng);
    const Eigen::Vector3d t = random_vector(rng, 5.0);
    const double scale = 0.31;  // a monocular map is off by an arbitrary factor
    const Trajectory est = transformed(gt, r, t, scale);
    const AteResult similarity = compute_ate(gt, est, sim3());
    INFO("seed " << seed);
    CHECK(similarity.stats.max < 1e-12);
    CHECK(std::abs(similarity.alignment.scale - 1.0 / scale) < 1e-12);
    CHECK(max_abs(similarity.alignment.rotation - r.transpose()) < 1e-13);
    const AteResult rigid = compute_ate(gt, est);
    CHECK(rigid.stats.rmse > 0.05);
    // The scripts' --scale: a fixed factor applied before a rigid alignment.
    AteParams fixed;
    fixed.est_scale = 1.0 / scale;
    CHECK(compute_ate(gt, est, fixed).stats.max < 1e-12);
  }
}

TEST_CASE("ATE errors are the distances after alignment, per association", "[eval][ate]") {
  std::mt19937 rng(4);
  const Trajectory gt = synthetic_trajectory(120, 10.0, 0.05);
  Trajectory est = gt;
  // A known error on two poses only: the aligned estimate cannot absorb it, and the largest
  // error sits on a perturbed pose.
  est.positions.col(30) += Eigen::Vector3d(0.2, 0.0, 0.0);
  est.positions.col(90) += Eigen::Vector3d(0.0, -0.2, 0.0);
  const AteResult ate = compute_ate(gt, est);
  Eigen::Index worst = 0;
  ate.errors.maxCoeff(&worst);
  CHECK((worst == 30 || worst == 90));
  CHECK(ate.errors.size() == 120);
  CHECK(ate.stats.rmse == Approx(std::sqrt(ate.errors.squaredNorm() / 120.0)).epsilon(1e-15));
  CHECK(ate.stats.max < 0.2);  // alignment spreads part of the error
  CHECK(ate.stats.max > 0.15);
}

TEST_CASE("ATE needs at least two associations", "[eval][ate]") {
  const Trajectory gt = synthetic_trajectory(50, 0.0, 0.01);
  const Trajectory far = synthetic_trajectory(50, 100.0, 0.01, "late.txt");
  CHECK_THROWS_WITH(compute_ate(gt, far),
                    Contains("only 0 associated pose pairs") && Contains("late.txt"));
  AteParams bad;
  bad.est_scale = 0.0;
  CHECK_THROWS_WITH(compute_ate(gt, gt, bad), Contains("est_scale"));
}

TEST_CASE("share tracked: evaluated poses over the frames in the ground-truth span",
          "[eval][tracked]") {
  const Trajectory gt = synthetic_trajectory(1001, 50.0, 0.01);  // 10 s of ground truth
  // Without a frame list the frames are counted from the estimate's own spacing: 150 poses at
  // 30 Hz over the first 5 s of a 10 s span, and a 1 s gap in them, miss 30 + ~150 frames.
  std::vector<double> evaluated;
  for (int i = 0; i < 180; ++i) {
    if (i >= 60 && i < 90) continue;  // the gap: 30 frames not tracked
    evaluated.push_back(50.0 + i / 30.0);
  }
  REQUIRE(evaluated.size() == 150);
  const auto by_spacing = hbos::slam::compute_tracked_share(evaluated, gt);
  CHECK(by_spacing.basis == "estimate spacing");
  CHECK(by_spacing.frame_period == Approx(1.0 / 30.0));
  // 150 evaluated + 30 in the gap + floor(4.03 s * 30 Hz) = 121 after the last pose (120 if
  // the division rounds down).
  CHECK(by_spacing.sequence_frames >= 150 + 30 + 120);
  CHECK(by_spacing.sequence_frames <= 150 + 30 + 121);
  CHECK(by_spacing.share <= 1.0);
  // An estimate denser than the camera cannot make the share exceed 1.
  std::vector<double> dense;
  for (int i = 0; i <= 330; ++i) dense.push_back(50.0 + i / 33.0);
  CHECK(hbos::slam::compute_tracked_share(dense, gt).share == 1.0);
  CHECK_THROWS_WITH(hbos::slam::compute_tracked_share(std::vector<double>{50.0}, gt),
                    Contains("--frames"));
  // A frame list counts only frames inside the span, and dropped frames lower the count.
  std::vector<double> frames = {49.0, 49.99};
  for (int i = 0; i < 250; ++i) frames.push_back(50.0 + 0.04 * i);
  frames.push_back(60.5);
  const auto by_list = hbos::slam::compute_tracked_share(200, gt, frames);
  CHECK(by_list.sequence_frames == 250);
  CHECK(by_list.share == Approx(0.8).epsilon(1e-15));
  CHECK(by_list.basis == "frame list");
  CHECK_THROWS_WITH(hbos::slam::compute_tracked_share(1, gt, std::vector<double>{1.0, 2.0}),
                    Contains("none of the 2 frame stamps"));
  CHECK_THROWS_WITH(hbos::slam::compute_tracked_share(260, gt, frames),
                    Contains("another sequence"));
}

TEST_CASE("evaluate(): one association for SE(3) and Sim(3), RPE uses the Sim(3) scale",
          "[eval][evaluate]") {
  std::mt19937 rng(8);
  const Trajectory gt = synthetic_trajectory(600, 20.0, 0.01);
  const Trajectory est = transformed(gt, random_rotation(rng), random_vector(rng, 2.0), 2.5);
  hbos::slam::EvaluationParams params;
  params.sim3 = true;
  const hbos::slam::Evaluation e = hbos::slam::evaluate(gt, est, params);
  REQUIRE(e.ate_sim3.has_value());
  REQUIRE(e.rpe.has_value());
  CHECK(e.ate.stats.count == e.ate_sim3->stats.count);
  CHECK(&e.main_ate() == &*e.ate_sim3);
  CHECK(e.ate_sim3->stats.max < 1e-12);
  CHECK(e.rpe->trans_m.max < 1e-12);  // relative motions scaled by 1/2.5 match exactly
  CHECK(e.tracked.evaluated_poses == 600);
  params.sim3 = false;
  const hbos::slam::Evaluation unscaled = hbos::slam::evaluate(gt, est, params);
  CHECK_FALSE(unscaled.ate_sim3.has_value());
  CHECK(&unscaled.main_ate() == &unscaled.ate);
  CHECK(unscaled.rpe->trans_m.mean > 0.1);  // 2.5× too long relative motions
  params.rpe = false;
  CHECK_FALSE(hbos::slam::evaluate(gt, est, params).rpe.has_value());
}
