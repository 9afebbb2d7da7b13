// The rigid residual field (rigid_field.hpp): the pinhole's motion Jacobian against finite
// differences, the fit recovering a camera motion it is given, what it cannot absorb, and the
// default screen refitting rigidly. Synthetic frames test properties here; what the rigid field
// does on real and rendered frames is measured in docs/results.md ("A field only a camera motion
// can give").

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "../support/screening_eval.hpp"

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Where a point at pixel `uv` and depth `z` appears after the scene moves by `motion`
/// (P -> P + t + w x P, exactly: the rotation applied as a rotation).
Vec2 moved_pixel(const hbos::PinholeCamerad& camera, const Vec2& uv, double z, const Vec6& motion) {
  const Vec3 p = camera.back_project(uv, z);
  const Vec3 w = motion.tail<3>();
  const Eigen::AngleAxisd rotation(w.norm(), w.norm() > 0.0 ? Vec3(w.normalized()) : Vec3::UnitZ());
  return camera.project(rotation * p + motion.head<3>());
}

/// `n` matches over a 640 x 480 image at depths in [z_lo, z_hi], whose residuals are the pixel
/// shift of `motion` plus `shift(p)` plus noise of `noise` px per axis; sigma 1.
template <class Shift>
hbos::Matchesd moved_matches(const hbos::PinholeCamerad& camera, int n, double z_lo, double z_hi,
                             const Vec6& motion, const Shift& shift, double noise,
                             std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 640.0), v(0.0, 480.0), z(z_lo, z_hi);
  std::normal_distribution<double> e(0.0, noise);
  hbos::Matchesd m;
  for (int i = 0; i < n; ++i) {
    const Vec2 p(u(rng), v(rng));
    const double depth = z(rng);
    const Vec2 observed = moved_pixel(camera, p, depth, motion) + shift(p) + Vec2(e(rng), e(rng));
    m.add(p, observed);
    m.set_depth(m.size() - 1, depth);
  }
  return m;
}

Vec2 no_shift(const Vec2&) { return Vec2::Zero(); }

using hbos_test::rejected_share;

}  // namespace

TEST_CASE("the pinhole's motion Jacobian is the first-order pixel shift of a small rigid motion",
          "[rigid_field]") {
  const hbos::PinholeCamerad camera;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 640.0), v(0.0, 480.0), z(0.4, 8.0), unit(-1.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec2 p(u(rng), v(rng));
    const double depth = z(rng);
    Vec6 direction;
    for (int k = 0; k < 6; ++k) direction(k) = unit(rng);
    // Translations of centimetres, rotations of a tenth of a degree, then ten times smaller:
    // the first-order error falls with the square of the step.
    direction.head<3>() *= 0.01;
    direction.tail<3>() *= 0.002;
    const Vec2 shift = camera.pixel_motion(p, 1.0 / depth, direction);
    const Vec2 exact = moved_pixel(camera, p, depth, direction) - p;
    const Vec2 shift_small = camera.pixel_motion(p, 1.0 / depth, 0.1 * direction);
    const Vec2 exact_small = moved_pixel(camera, p, depth, 0.1 * direction) - p;
    INFO("trial " << trial << " pixel " << p.transpose() << " depth " << depth);
    CHECK(shift_small.isApprox(0.1 * shift, 1e-12));  // linear in the motion
    const double error = (exact - shift).norm(), error_small = (exact_small - shift_small).norm();
    CHECK(error_small <= 0.02 * error + 1e-9);
    CHECK(error <= 0.05 * exact.norm() + 1e-9);
  }
  SECTION("a point of unknown depth moves as a point at infinity: by the rotation alone") {
    Vec6 rotation_only = Vec6::Zero();
    rotation_only.tail<3>() << 1e-3, -2e-3, 5e-4;
    Vec6 with_translation = rotation_only;
    with_translation.head<3>() << 0.02, -0.01, 0.03;
    const Vec2 p(100.0, 400.0);
    CHECK(camera.pixel_motion(p, 0.0, with_translation) ==
          camera.pixel_motion(p, 0.0, rotation_only));
    CHECK(hbos::inverse_depth_of(std::numeric_limits<double>::quiet_NaN()) == 0.0);
    CHECK(hbos::inverse_depth_of(4.0) == 0.25);
    const hbos::ResidualField<double> field = [&] {
      hbos::ResidualField<double> f;
      f.rigid = true;
      f.motion = with_translation;
      return f;
    }();
    CHECK(field.at(p) == camera.pixel_motion(p, 0.0, with_translation));
    CHECK(field.at(p, 0.5) == camera.pixel_motion(p, 0.5, with_translation));
  }
}

TEST_CASE("the rigid fit recovers the motion its residuals come from, past a person",
          "[rigid_field]") {
  const hbos::PinholeCamerad camera;
  Vec6 motion;
  motion << 0.004, -0.003, 0.01, 1.5e-3, -1e-3, 2e-3;  // residuals of up to ~2.5 px
  hbos::Matchesd m = moved_matches(camera, 400, 0.8, 6.0, motion, no_shift, 0.3, 5);
  // A person: 100 matches in one box, 6 px off the motion's shift.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(400.0, 520.0), v(150.0, 420.0);
  for (int i = 0; i < 100; ++i) {
    const Vec2 p(u(rng), v(rng));
    m.add(p, moved_pixel(camera, p, 2.0, motion) + Vec2(6.0, 1.0));
    m.set_depth(m.size() - 1, 2.0);
  }
  hbos::detail::RigidFitWork scratch;
  const auto all = [](Eigen::Index) { return true; };
  // Started from a constant field at the median of the statics' shift: the person lies outside
  // the 3-sigma window from the start, and the statics' support grows to all of them.
  hbos::ResidualField<double> start;
  const hbos::ResidualField<double> field =
      hbos::detail::fit_rigid_field(m, all, start, camera, 3.0, 5, scratch);
  REQUIRE(field.rigid);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < 400; ++i) {
    const Vec2 c = field.at(m.predicted(i), hbos::inverse_depth_of(m.depth(i)));
    const Vec2 truth = moved_pixel(camera, m.predicted(i), m.depth(i), motion) - m.predicted(i);
    worst = std::max(worst, (c - truth).norm());
  }
  CHECK(worst < 0.15);  // px: the noise (0.3 px over 400 matches) and the linearisation
  Eigen::Index person_inside = 0;
  for (Eigen::Index i = 400; i < 500; ++i)
    person_inside += scratch.inside[static_cast<std::size_t>(i)];
  CHECK(person_inside == 0);

  SECTION("too few supporting matches keep the start") {
    hbos::ResidualField<double> affine;
    affine.offset = Vec2(0.5, -0.25);
    const auto five = [](Eigen::Index i) { return i < 5; };
    const auto kept = hbos::detail::fit_rigid_field(m, five, affine, camera, 3.0, 5, scratch);
    CHECK_FALSE(kept.rigid);
    CHECK(kept.offset == affine.offset);
  }
}

TEST_CASE("a rigid field does not absorb a field no camera motion gives", "[rigid_field]") {
  // An anisotropic stretch of the image (u by +0.4 %, v by -0.4 % about the centre) is affine,
  // and no small rigid motion gives it: the affine fit takes it up, the rigid fit cannot.
  const hbos::PinholeCamerad camera;
  const auto stretch = [&](const Vec2& p) {
    return Vec2(0.004 * (p.x() - camera.cx), -0.004 * (p.y() - camera.cy));
  };
  const hbos::Matchesd m = moved_matches(camera, 500, 2.0, 2.0, Vec6::Zero(), stretch, 0.05, 13);
  hbos::detail::RigidFitWork scratch;
  const auto all = [](Eigen::Index) { return true; };
  const hbos::ResidualField<double> rigid =
      hbos::detail::fit_rigid_field(m, all, {}, camera, 10.0, 5, scratch);
  REQUIRE(rigid.rigid);
  hbos::detail::FieldSamples<double> samples;
  hbos::detail::collect_field_samples(m, all, samples);
  std::vector<double> work;
  const hbos::ResidualField<double> affine =
      hbos::detail::dominant_field(samples, hbos::ResidualCenter::Affine, 10.0, 5, work);
  double total = 0.0, left_rigid = 0.0, left_affine = 0.0;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const Vec2 r = m.residual(i);
    total += r.squaredNorm();
    left_rigid += (r - rigid.at(m.predicted(i), 0.5)).squaredNorm();
    left_affine += (r - affine.at(m.predicted(i))).squaredNorm();
  }
  CHECK(left_affine < 0.01 * total);
  CHECK(left_rigid > 0.5 * total);
}

TEST_CASE("the default screen refitting rigidly keeps the statics of a forward step at many depths",
          "[rigid_field][screen]") {
  // A pose error of a forward step: each static match's residual is radial and scales with its
  // inverse depth, which no field in the pixel alone follows when the depths spread from 0.7 to
  // 6 m. The rigid refit follows it; the affine refit leaves the near matches at the image's
  // edge off centre.
  const hbos::PinholeCamerad camera;
  Vec6 forward = Vec6::Zero();
  forward(2) = 0.025;
  hbos::Matchesd m = moved_matches(camera, 600, 0.7, 6.0, forward, no_shift, 0.4, 21);
  hbos::HbosScreen affine;
  hbos::HbosScreen rigid;
  rigid.field.refit_model = hbos::RefitModel::Rigid;
  rigid.field.camera = camera;
  hbos::ReprojectionScreend affine_screen(affine), rigid_screen(rigid);
  const double lost_affine = rejected_share(affine_screen.screen(m), 0, m.size());
  const auto& r = rigid_screen.screen(m);
  const double lost_rigid = rejected_share(r, 0, m.size());
  INFO("statics lost: affine " << lost_affine << ", rigid " << lost_rigid);
  CHECK(r.field().rigid);
  CHECK(lost_rigid < 0.5 * lost_affine);
  CHECK(lost_rigid < 0.05);

  SECTION("in float too") {
    hbos::Matchesf mf;
    for (Eigen::Index i = 0; i < m.size(); ++i) {
      mf.add(m.predicted(i).cast<float>(), m.observed(i).cast<float>());
      mf.set_depth(i, static_cast<float>(m.depth(i)));
    }
    hbos::ReprojectionScreenf screen_f(rigid);
    const auto& rf = screen_f.screen(mf);
    CHECK(rf.field().rigid);
    Eigen::Index differ = 0;
    for (Eigen::Index i = 0; i < m.size(); ++i) differ += rf.inlier(i) != r.inlier(i) ? 1 : 0;
    CHECK(differ <= 3);
  }
}

TEST_CASE("the rigid refit's settings are validated", "[rigid_field][errors]") {
  hbos::HbosScreen s;
  s.field.refit_model = hbos::RefitModel::Rigid;
  s.field.camera.fx = 0.0;
  CHECK_THROWS_WITH(hbos::ReprojectionScreend(s), Catch::Contains("PinholeCamera fx"));
  s.field.camera = hbos::PinholeCamerad{};
  s.residuals.center = hbos::ResidualCenter::None;
  CHECK_THROWS_WITH(hbos::ReprojectionScreend(s), Catch::Contains("refit_model Rigid"));
  s.residuals.center = hbos::ResidualCenter::Affine;
  s.field.refit_on_static = false;
  CHECK_THROWS_WITH(hbos::ReprojectionScreend(s), Catch::Contains("refit_model Rigid"));
}

TEST_CASE("the later rounds' config: a rigid refit with the caller's intrinsics",
          "[rigid_field][iterated]") {
  const hbos::ScreenConfig own;
  hbos::PinholeCamerad camera;
  camera.fx = 517.3;
  const auto later = hbos::later_rounds_config(own, hbos::LaterRounds{0.0, camera});
  REQUIRE(later.has_value());
  const auto& s = std::get<hbos::HbosScreen>(later->strategy);
  CHECK(s.field.refit_model == hbos::RefitModel::Rigid);
  CHECK(s.field.camera.fx == 517.3);
  CHECK(s.gate.floor == std::get<hbos::HbosScreen>(own.strategy).gate.floor);
  // With a floor too, both change.
  const auto both = hbos::later_rounds_config(own, hbos::LaterRounds{2.0, camera});
  REQUIRE(both.has_value());
  CHECK(std::get<hbos::HbosScreen>(both->strategy).gate.floor == 2.0);
  CHECK(std::get<hbos::HbosScreen>(both->strategy).field.refit_model == hbos::RefitModel::Rigid);
  // Nothing to change: already rigid with these intrinsics, no field to refit, or no noise gate.
  CHECK_FALSE(hbos::later_rounds_config(*later, hbos::LaterRounds{0.0, camera}).has_value());
  hbos::HbosScreen no_refit;
  no_refit.field.refit_on_static = false;
  CHECK_FALSE(
      hbos::later_rounds_config(hbos::ScreenConfig{no_refit}, hbos::LaterRounds{0.0, camera})
          .has_value());
  CHECK_FALSE(hbos::later_rounds_config(hbos::ScreenConfig{hbos::ChiSquareGate{}},
                                        hbos::LaterRounds{0.0, camera})
                  .has_value());
  // Bad intrinsics are refused, naming the value.
  camera.fy = -1.0;
  CHECK_THROWS_WITH(hbos::later_rounds_config(own, hbos::LaterRounds{0.0, camera}),
                    Catch::Contains("PinholeCamera fy must be finite and > 0, got -1"));
}

TEST_CASE("the rounds helper refits rigidly after the first round only, and restores the config",
          "[rigid_field][iterated]") {
  const hbos::PinholeCamerad camera;
  Vec6 rough = Vec6::Zero();
  rough << 0.01, 0.0, 0.02, 0.0, 2e-3, 0.0;
  // Points in front of the camera at the true pose (identity); the rough pose is off by a
  // small motion, so the predictions carry its shift.
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0.0, 640.0), v(0.0, 480.0), z(0.8, 5.0);
  std::normal_distribution<double> e(0.0, 0.3);
  const int n = 300;
  Eigen::Matrix3Xd points(3, n);
  Eigen::Matrix2Xd observed(2, n);
  for (int i = 0; i < n; ++i) {
    const Vec2 p(u(rng), v(rng));
    points.col(i) = camera.back_project(p, z(rng));
    observed.col(i) = p + Vec2(e(rng), e(rng));
  }
  Eigen::Isometry3d T_rough = Eigen::Isometry3d::Identity();
  T_rough.translation() = rough.head<3>();
  T_rough.linear() = Eigen::AngleAxisd(rough(4), Vec3::UnitY()).toRotationMatrix();
  hbos::ReprojectionScreend screen;
  hbos::Matchesd m;
  for (const int rounds : {1, 4}) {
    hbos::IteratedScreenOptions options;
    options.rounds = rounds;
    options.later_rigid_field = true;
    Eigen::Isometry3d T = T_rough;
    hbos::project_matches(points, observed, T, camera, m);
    const auto& r = hbos::screen_and_refine_pose(screen, points, camera, T, m, options);
    INFO("rounds " << rounds);
    CHECK(r.field().rigid == (rounds > 1));
    CHECK(std::get<hbos::HbosScreen>(screen.config().strategy).field.refit_model ==
          hbos::RefitModel::Center);
    if (rounds > 1) {
      CHECK(T.translation().norm() < 2e-3);
      CHECK(rejected_share(r, 0, n) < 0.03);
    }
  }
}
