// A dynamic-scene trajectory (Bonn RGB-D Dynamic, ORB-SLAM2 + YOLACT estimate). No reference
// numbers exist for it, so this checks properties that must hold for any correct evaluator.
#include "eval/evaluate.hpp"
#include "eval/trajectory_io.hpp"
#include "eval_test_support.hpp"

#include <catch2/catch.hpp>

#include <random>

using hbos::slam::Evaluation;
using hbos::slam::Trajectory;

namespace {

const std::string kBonn = "data/bonn_gt_and_orbslam_yolact_amos/";

void check_consistent(const hbos::slam::ErrorStatistics& s) {
  CHECK(s.min >= 0.0);
  CHECK(s.min <= s.median);
  CHECK(s.median <= s.max);
  CHECK(s.mean <= s.rmse);
  CHECK(s.rmse * s.rmse == Approx(s.mean * s.mean + s.std_dev * s.std_dev).epsilon(1e-12));
}

}  // namespace

TEST_CASE("Bonn dynamic sequence: reads strictly, evaluates, and behaves", "[eval][bonn]") {
  const Trajectory gt =
      hbos::slam::read_tum_trajectory(hbos::slam::test::eval_data(kBonn + "groundtruth.txt"));
  const Trajectory est =
      hbos::slam::read_tum_trajectory(hbos::slam::test::eval_data(kBonn + "CameraTrajectory.txt"));
  REQUIRE(gt.size() == 360);
  REQUIRE(est.size() == 358);
  // ORB-SLAM2 starts its map at the first camera pose.
  CHECK(est.positions.col(0).isZero());
  CHECK(est.rotation(0).isIdentity());

  hbos::slam::EvaluationParams params;
  params.sim3 = true;
  const Evaluation e = hbos::slam::evaluate(gt, est, params);
  // Both run at 30 Hz over the same 12 s: nearly every estimate pose associates.
  CHECK(e.ate.stats.count >= 350);
  CHECK(e.ate.stats.count <= est.size());
  check_consistent(e.ate.stats);
  check_consistent(e.ate_sim3->stats);
  // A good RGB-D run: centimetre-level ATE, scale within a few per cent of 1.
  CHECK(e.ate.stats.rmse > 1e-3);
  CHECK(e.ate.stats.rmse < 0.05);
  CHECK(std::abs(e.ate_sim3->alignment.scale - 1.0) < 0.05);
  // One more degree of freedom never fits worse.
  CHECK(e.ate_sim3->stats.rmse <= e.ate.stats.rmse);
  // The RPE tolerance follows the 30 Hz ground truth: 2 × 1/30 s, not the ATE's 0.02 s.
  REQUIRE(e.rpe.has_value());
  CHECK(e.rpe->gt_max_time_difference > 0.06);
  CHECK(e.rpe->gt_max_time_difference < 0.07);
  CHECK(e.rpe->trans_m.count > 300);
  check_consistent(e.rpe->trans_m);
  check_consistent(e.rpe->rot_deg);
  // 11.99986 s of ground truth at 30 Hz: 360 frames, of which nearly all are evaluated.
  // Counted from the estimate's stamps and gaps (issue 11): 359 for the 360 listed frames.
  CHECK(std::abs(e.tracked.sequence_frames - 360) <= 1);
  CHECK(e.tracked.share > 0.95);
  CHECK(e.tracked.share <= 1.0);

  // ATE after alignment and RPE do not depend on the estimate's world frame.
  std::mt19937 rng(21);
  const Trajectory moved = hbos::slam::test::transformed(
      est, hbos::slam::test::random_rotation(rng), hbos::slam::test::random_vector(rng, 4.0), 1.0);
  const Evaluation m = hbos::slam::evaluate(gt, moved, params);
  CHECK(m.ate.stats.rmse == Approx(e.ate.stats.rmse).epsilon(1e-9));
  CHECK(m.ate_sim3->stats.rmse == Approx(e.ate_sim3->stats.rmse).epsilon(1e-9));
  CHECK(m.rpe->trans_m.rmse == Approx(e.rpe->trans_m.rmse).epsilon(1e-9));
  CHECK(m.rpe->rot_deg.mean == Approx(e.rpe->rot_deg.mean).epsilon(1e-8));
}
