// The acceptance criteria of issue 3 (point 7) for the magnitude-only screen
// (HbosScreen::magnitude_only(), the default until Screen v2), on labelled synthetic
// correspondences over many seeds. The v2 default is accepted on labelled real residual cases
// instead (test_screen_real_cases.cpp); on these synthetic scenes its noise gate opens to five
// noise scales and it keeps more of the leaked dynamics than chi^2 does (docs/screening.md). The
// seeds here (from 1001) are disjoint from the study's (from 1), whose numbers chose the defaults,
// so these tests check that the choice generalises rather than re-reading the data it was made on.

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>

#include <cmath>
#include <vector>

#include "../support/screening_eval.hpp"
#include "../support/synthetic_scene.hpp"

namespace {

using hbos_test::Conditions;
using hbos_test::Scenario;
using hbos_test::Tally;

constexpr std::uint64_t kFirstSeed = 1001;
constexpr int kSeeds = 150;

const std::vector<hbos::ScreenStrategy>& contenders() {
  static const std::vector<hbos::ScreenStrategy> list{
      hbos::HbosScreen::magnitude_only(), hbos::ChiSquareGate{}, hbos::FixedPixelGate{3.0},
      hbos::QuantileGate{}};
  return list;
}

/// Pose error after one Gauss-Newton refit on the screen's inliers, from the rough pose.
struct PoseError {
  double translation = 0;  ///< [m]
  double rotation = 0;     ///< [rad]
};

PoseError refit_error(const hbos_test::Scene& scene, const hbos::ScreenResult<double>* result) {
  const hbos::PinholeCamerad camera;
  Eigen::Isometry3d T = scene.T_cur_world_rough;
  hbos::refine_pose(
      scene.size(), [&](Eigen::Index i) { return Eigen::Vector3d(scene.points_world.col(i)); },
      [&](Eigen::Index i) { return Eigen::Vector2d(scene.observed.col(i)); },
      [&](Eigen::Index i) { return scene.sigma(i); },
      [&](Eigen::Index i) {
        // No result: the oracle that uses exactly the true static matches.
        return result != nullptr
                   ? result->inlier(i)
                   : scene.label[static_cast<std::size_t>(i)] == hbos_test::Label::Static;
      },
      camera, T);
  return {(T.translation() - scene.T_cur_world_true.translation()).norm(),
          Eigen::AngleAxisd(T.linear().transpose() * scene.T_cur_world_true.linear()).angle()};
}

}  // namespace

TEST_CASE(
    "acceptance: with 0-10 % leakage the default keeps fewer dynamic matches than chi2, fixed "
    "and quantile, at no more static loss than chi2",
    "[acceptance][reprojection]") {
  const Conditions conditions;  // rough pose 0-3 px, measured keypoint noise, 0-5 % gross
  Tally pooled[4];
  for (double leak : {0.025, 0.05, 0.10}) {
    for (Scenario scenario : {Scenario::Mixed, Scenario::Person}) {
      const auto t =
          hbos_test::evaluate(contenders(), scenario, leak, kFirstSeed, kSeeds, conditions);
      INFO("scenario " << hbos_test::scenario_name(scenario) << ", leak " << leak);
      INFO("static loss: default " << t[0].static_loss() << ", chi2 " << t[1].static_loss()
                                   << ", fixed " << t[2].static_loss() << ", quantile "
                                   << t[3].static_loss());
      INFO("dynamic kept: default "
           << t[0].dynamic_survival() << ", chi2 " << t[1].dynamic_survival() << ", fixed "
           << t[2].dynamic_survival() << ", quantile " << t[3].dynamic_survival());
      // Against chi2 and the quantile the margins are wide: check every cell.
      CHECK(t[0].dynamic_survival() < t[1].dynamic_survival());
      CHECK(t[0].dynamic_survival() < t[3].dynamic_survival());
      CHECK(t[0].static_loss() <= t[1].static_loss());
      for (int s = 0; s < 4; ++s) pooled[s] += t[static_cast<std::size_t>(s)];
    }
  }
  // Against the fixed 3 px gate (which drops ~20 % of statics to get there) the margin is a few
  // points, so it is checked on the pooled regime.
  INFO("pooled dynamic kept: default " << pooled[0].dynamic_survival() << ", fixed "
                                       << pooled[2].dynamic_survival());
  CHECK(pooled[0].dynamic_survival() < pooled[2].dynamic_survival());
  CHECK(pooled[0].dynamic_survival() < pooled[1].dynamic_survival());
  CHECK(pooled[0].dynamic_survival() < pooled[3].dynamic_survival());
  CHECK(pooled[0].static_loss() <= pooled[1].static_loss());
  // Gross mismatches never get through the default.
  CHECK(pooled[0].survival(hbos_test::Label::GrossMismatch) < 0.01);
}

TEST_CASE("acceptance: the default never hurts the static-only case",
          "[acceptance][reprojection]") {
  // Counted over the whole regime (rough pose 0-3 px, 0-5 % gross): fewer statics lost than chi2.
  const Conditions regime;
  const auto t = hbos_test::evaluate({hbos::HbosScreen::magnitude_only(), hbos::ChiSquareGate{}},
                                     Scenario::Static, 0.0, kFirstSeed, kSeeds, regime);
  INFO("static-only, rough pose 0-3 px: static loss default " << t[0].static_loss() << ", chi2 "
                                                              << t[1].static_loss());
  CHECK(t[0].static_loss() <= t[1].static_loss());
  CHECK(t[0].survival(hbos_test::Label::GrossMismatch) < 0.01);

  // What matters is the pose. A screen measured against the rough pose cannot see the part of
  // the pose error that varies with depth, so it is used as ORB-SLAM2 uses chi2: screen -> refit
  // -> re-screen (4 rounds). Its pose must stay within 15 % of the oracle's error (a refit on
  // exactly the true static matches) at every rough-pose error. (Measured: 6-12 % above chi2's,
  // which keeps the ~4 % noise tail the default trims; the paper's screen made it 16x worse.)
  for (double pose_error : {0.0, 1.5, 3.0}) {
    Conditions c;
    c.pose_error_min = c.pose_error_max = pose_error;
    const hbos::PinholeCamerad camera;
    double err[3] = {0, 0, 0}, rot[3] = {0, 0, 0};
    hbos::ReprojectionScreend screens[2] = {hbos::ReprojectionScreend{},
                                            hbos::ReprojectionScreend{hbos::ChiSquareGate{}}};
    hbos::Matchesd matches;
    const int seeds = 60;
    for (int k = 0; k < seeds; ++k) {
      const hbos_test::Scene scene = hbos_test::make_scene(hbos_test::scenario_config(
          Scenario::Static, 0.0, kFirstSeed + static_cast<std::uint64_t>(k), c));
      for (int s = 0; s < 2; ++s) {
        hbos_test::load_matches(scene, matches);
        Eigen::Isometry3d T = scene.T_cur_world_rough;
        hbos::screen_and_refine_pose(screens[s], scene.points_world, camera, T, matches);
        err[s] += (T.translation() - scene.T_cur_world_true.translation()).norm();
        rot[s] +=
            Eigen::AngleAxisd(T.linear().transpose() * scene.T_cur_world_true.linear()).angle();
      }
      const PoseError eo = refit_error(scene, nullptr);
      err[2] += eo.translation;
      rot[2] += eo.rotation;
    }
    INFO("rough pose " << pose_error << " px, mean translation error [mm]: default "
                       << 1e3 * err[0] / seeds << ", chi2 " << 1e3 * err[1] / seeds << ", oracle "
                       << 1e3 * err[2] / seeds);
    INFO("mean rotation error [mrad]: default " << 1e3 * rot[0] / seeds << ", chi2 "
                                                << 1e3 * rot[1] / seeds << ", oracle "
                                                << 1e3 * rot[2] / seeds);
    CHECK(err[0] <= 1.15 * err[2]);
    CHECK(rot[0] <= 1.15 * rot[2]);
  }
}

TEST_CASE(
    "acceptance: a fixed threshold tuned on one scene fails on another where the default does not",
    "[acceptance][reprojection]") {
  Conditions a, b;
  a.pose_error_min = 0.0;
  a.pose_error_max = 0.5;  // scene A: a good rough pose
  b.pose_error_min = 2.5;
  b.pose_error_max = 3.0;  // scene B: a rough pose off by 2.5-3 px
  const int seeds = 80;
  // Tune: the tightest gate that loses at most 5 % of the statics on A.
  double tuned = 0.0;
  for (double px = 0.5; px <= 8.0; px += 0.25) {
    if (hbos_test::evaluate({hbos::FixedPixelGate{px}}, Scenario::Mixed, 0.05, kFirstSeed, seeds,
                            a)[0]
            .static_loss() <= 0.05) {
      tuned = px;
      break;
    }
  }
  REQUIRE(tuned > 0.0);
  const std::vector<hbos::ScreenStrategy> pair{hbos::FixedPixelGate{tuned},
                                               hbos::HbosScreen::magnitude_only()};
  const auto on_a = hbos_test::evaluate(pair, Scenario::Mixed, 0.05, kFirstSeed, seeds, a);
  const auto on_b = hbos_test::evaluate(pair, Scenario::Mixed, 0.05, kFirstSeed, seeds, b);
  INFO("tuned fixed gate " << tuned << " px");
  INFO("scene A static loss: fixed " << on_a[0].static_loss() << ", default "
                                     << on_a[1].static_loss());
  INFO("scene B static loss: fixed " << on_b[0].static_loss() << ", default "
                                     << on_b[1].static_loss());
  INFO("scene B dynamic kept: fixed " << on_b[0].dynamic_survival() << ", default "
                                      << on_b[1].dynamic_survival());
  // On A both work: the fixed gate meets its 5 % budget, and the default keeps fewer dynamics.
  CHECK(on_a[0].static_loss() <= 0.05);
  CHECK(on_a[1].dynamic_survival() < on_a[0].dynamic_survival());
  // On B the tuned gate throws away most of the scene (pose estimation then rests on a
  // minority of the matches); the default stays within 3x of its loss on A.
  CHECK(on_b[0].static_loss() > 0.4);
  CHECK(on_b[1].static_loss() < 3.0 * on_a[1].static_loss());
  CHECK(on_b[1].static_loss() < 0.15);
}

TEST_CASE("acceptance: the 10-30 % regime, and the paper's literal screen",
          "[acceptance][reprojection]") {
  const Conditions conditions;
  // Reported honestly in docs/screening.md: at 20-30 % the fixed 3 px gate keeps fewer dynamics
  // than the default (at 20 % static loss); the default still beats chi2 and the quantile.
  for (double leak : {0.2, 0.3}) {
    const auto t =
        hbos_test::evaluate(contenders(), Scenario::Mixed, leak, kFirstSeed, 80, conditions);
    INFO("leak " << leak << ": dynamic kept default " << t[0].dynamic_survival() << ", chi2 "
                 << t[1].dynamic_survival() << ", quantile " << t[3].dynamic_survival());
    CHECK(t[0].dynamic_survival() < t[1].dynamic_survival());
    CHECK(t[0].dynamic_survival() < t[3].dynamic_survival());
    CHECK(t[0].static_loss() <= t[1].static_loss());
  }
  // The paper's screen taken literally reproduces FINDINGS.md: bins stretched by gross
  // mismatches let nearly every dynamic match and a large share of gross mismatches through.
  const auto p =
      hbos_test::evaluate({hbos::HbosScreen::paper(), hbos::HbosScreen::magnitude_only()},
                          Scenario::Mixed, 0.05, kFirstSeed, 60, conditions);
  CHECK(p[0].dynamic_survival() > 0.9);
  CHECK(p[0].survival(hbos_test::Label::GrossMismatch) > 0.25);
  CHECK(p[1].dynamic_survival() < 0.5 * p[0].dynamic_survival());
}
