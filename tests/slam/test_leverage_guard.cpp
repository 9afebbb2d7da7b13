// The mask neighbourhood's leverage guard (frontend/leverage_guard.hpp): the survivors near the
// mask are dropped exactly when they alone would decide a direction of the pose and the other
// survivors, on their own, put them off. The scenes are the situation it was built for (every
// static point on a far wall, a few near points on a person's rim that moves) and its controls
// (the same rim with the statics spread in depth; a rim that does not move).

#include <catch2/catch.hpp>

#include "frontend/config.hpp"
#include "frontend/leverage_guard.hpp"
#include "frontend/pose_refiner.hpp"

#include <hbos/error.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using hbos::slam::GuardOutcome;
using hbos::slam::LeverageGuard;
using hbos::slam::LeverageGuardConfig;
using hbos::slam::MaskSource;
using hbos::slam::PoseRefiner;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const hbos::PinholeCamerad kCamera{535.4, 539.2, 320.1, 247.6};

struct Scene {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> observed;
  std::vector<double> sigma;
  std::vector<double> mask_distance_px;
  std::vector<std::uint8_t> inlier;
  int rim = 0;  ///< the last `rim` points are the near group
};

// `static_count` static points over the whole image at depths [z_near, z_far], then `rim_count` rim
// points at 1.5 m in the image's left third, 2-8 px from the mask. Under the identity pose each
// point is observed where it projects plus noise of sigma 0.5 px (seeded); the rim moves by
// `rim_shift_px` in u. With `static_bias_px`, the statics of each 80 px cell share an offset of
// that sigma, as neighbours do on real frames.
Scene scene(double z_near, double z_far, unsigned seed, double rim_shift_px = 3.0,
            int rim_count = 20, double static_bias_px = 0.0, int static_count = 400) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(20.0, 620.0), v(20.0, 460.0), z(z_near, z_far);
  std::uniform_real_distribution<double> rim_u(60.0, 200.0), rim_v(150.0, 400.0), gap(2.0, 8.0);
  std::normal_distribution<double> noise(0.0, 0.5);
  Scene s;
  const auto add = [&](double px, double py, double depth, double distance, double shift) {
    s.points.emplace_back((px - kCamera.cx) / kCamera.fx * depth,
                          (py - kCamera.cy) / kCamera.fy * depth, depth);
    s.observed.emplace_back(px + shift + noise(rng), py + noise(rng));
    s.sigma.push_back(1.0);
    s.mask_distance_px.push_back(distance);
    s.inlier.push_back(1);
  };
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> cell_offset(8 * 6);
  for (Eigen::Vector2d& o : cell_offset) o = static_bias_px * Eigen::Vector2d(unit(rng), unit(rng));
  for (int i = 0; i < static_count; ++i) {
    const double px = u(rng), py = v(rng);
    const Eigen::Vector2d o = cell_offset[static_cast<std::size_t>(static_cast<int>(py / 80.0) * 8 +
                                                                   static_cast<int>(px / 80.0))];
    add(px, py, z(rng), kInf, 0.0);
    s.observed.back() += o;
  }
  for (int i = 0; i < rim_count; ++i) add(rim_u(rng), rim_v(rng), 1.5, gap(rng), rim_shift_px);
  s.rim = rim_count;
  return s;
}

int rim_kept(const Scene& s) {
  int kept = 0;
  for (std::size_t i = s.inlier.size() - static_cast<std::size_t>(s.rim); i < s.inlier.size(); ++i)
    kept += s.inlier[i];
  return kept;
}

const PoseRefiner kRefiner(hbos::slam::RefinementConfig{}, kCamera);

GuardOutcome apply(const LeverageGuard& guard, Scene& s,
                   const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity()) {
  return guard.apply(s.points, s.observed, s.sigma, s.mask_distance_px, T, kRefiner, s.inlier);
}

}  // namespace

TEST_CASE("leverage guard: a moving rim that alone decides the pose is dropped, otherwise kept",
          "[frontend][guard]") {
  const LeverageGuard guard(LeverageGuardConfig{});
  for (unsigned seed = 1; seed <= 5; ++seed) {
    CAPTURE(seed);
    Scene far_wall = scene(4.5, 5.0, seed);
    // The rough pose has followed the rim (as RANSAC and the screen's rounds do in such frames):
    // refined on every match, the pose fits the rim too.
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    kRefiner.refine(far_wall.points, far_wall.observed, far_wall.sigma, far_wall.inlier, T);
    const GuardOutcome on_wall = apply(guard, far_wall, T);
    CHECK(on_wall.ratio > 2.0);
    CHECK(on_wall.disagreement > 1.5);
    CHECK(on_wall.shift_scales > 3.0);
    CHECK(on_wall.dropped == 20);
    CHECK(rim_kept(far_wall) == 0);
    // Only the rim: the 400 statics stay.
    int statics_kept = 0;
    for (int i = 0; i < 400; ++i) statics_kept += far_wall.inlier[static_cast<std::size_t>(i)];
    CHECK(statics_kept == 400);

    Scene spread = scene(0.8, 5.0, seed);
    const GuardOutcome in_depth = apply(guard, spread);
    CHECK(in_depth.ratio < 0.5);
    CHECK(std::isnan(in_depth.disagreement));  // not asked: the statics fix the pose
    CHECK(in_depth.dropped == 0);
    CHECK(rim_kept(spread) == 20);

    // A rim that does not move is as decisive, but the far wall agrees with it: kept.
    Scene still = scene(4.5, 5.0, seed, 0.0);
    const GuardOutcome agreeing = apply(guard, still);
    CHECK(agreeing.ratio > 2.0);
    CHECK(agreeing.disagreement < 0.7);
    CHECK(agreeing.dropped == 0);
    CHECK(rim_kept(still) == 20);
  }
}

TEST_CASE(
    "leverage guard: a large group's small offset counts against what the frame's "
    "neighbours share",
    "[frontend][guard]") {
  // 400 points along the mask next to 1200 statics that span 1-5 m (a detector box gives a real
  // frame's survivors near its edge in such numbers), all off by 0.3 px: 0.6 noise scales (the
  // noise is 0.5 px). Their number alone makes that significant. Where the statics of each
  // neighbourhood share an offset of 0.15 px (0.3 scales, what real frames show), the group's
  // offset is what static neighbours do here: kept, and with it the near points that decide the
  // pose. Where the statics are independent, as rendered ones are, the same offset is not:
  // dropped.
  LeverageGuardConfig independent_noise;
  independent_noise.bias_cell_px = 0.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    CAPTURE(seed);
    Scene real_like = scene(1.0, 5.0, seed, 0.3, 400, 0.15, 1200);
    const GuardOutcome kept = apply(LeverageGuard(LeverageGuardConfig{}), real_like);
    CHECK(kept.ratio > 1.2);
    CHECK(kept.shared_bias > 0.15);
    CHECK(kept.disagreement < 0.9);
    CHECK(kept.dropped == 0);
    CHECK(rim_kept(real_like) == 400);

    Scene same = scene(1.0, 5.0, seed, 0.3, 400, 0.15, 1200);
    const GuardOutcome assumed_independent = apply(LeverageGuard(independent_noise), same);
    CHECK(assumed_independent.shift_scales == kept.shift_scales);
    CHECK(assumed_independent.disagreement > 1.5);
    CHECK(assumed_independent.dropped == 400);

    Scene rendered_like = scene(1.0, 5.0, seed, 0.3, 400, 0.0, 1200);
    const GuardOutcome measured = apply(LeverageGuard(LeverageGuardConfig{}), rendered_like);
    CHECK(measured.shared_bias < 0.15);
    CHECK(measured.disagreement > 1.5);
    CHECK(measured.dropped == 400);
  }
}

TEST_CASE("leverage guard: what it leaves alone", "[frontend][guard]") {
  SECTION("switched off") {
    LeverageGuardConfig off;
    off.enabled = false;
    Scene s = scene(4.5, 5.0, 7);
    const GuardOutcome g = apply(LeverageGuard(off), s);
    CHECK(std::isnan(g.ratio));
    CHECK(g.dropped == 0);
    CHECK(rim_kept(s) == 20);
    CHECK(LeverageGuard(off).reach_px(MaskSource::kDegraded) == 0.0);
  }
  SECTION("no mask distances, or no survivor near the mask") {
    const LeverageGuard guard(LeverageGuardConfig{});
    Scene s = scene(4.5, 5.0, 7);
    const GuardOutcome none = guard.apply(s.points, s.observed, s.sigma, {},
                                          Eigen::Isometry3d::Identity(), kRefiner, s.inlier);
    CHECK(std::isnan(none.ratio));
    CHECK(rim_kept(s) == 20);
    for (double& d : s.mask_distance_px) d = kInf;
    const GuardOutcome far = apply(guard, s);
    CHECK(std::isnan(far.ratio));
    CHECK(rim_kept(s) == 20);
    CHECK(guard.reach_px(MaskSource::kNone) == 0.0);
    CHECK(guard.reach_px(MaskSource::kDetector) == LeverageGuardConfig{}.radius_px);
  }
  SECTION("rejected matches are neither measured nor restored") {
    const LeverageGuard guard(LeverageGuardConfig{});
    Scene s = scene(4.5, 5.0, 7);
    for (std::size_t i = 400; i < 420; ++i) s.inlier[i] = 0;
    const GuardOutcome g = apply(guard, s);
    CHECK(std::isnan(g.ratio));
    CHECK(g.dropped == 0);
    CHECK(rim_kept(s) == 0);
  }
  SECTION("a rim beyond the radius is not the group") {
    LeverageGuardConfig narrow;
    narrow.radius_px = 1.5;  // the rim lies 2-8 px away
    Scene s = scene(4.5, 5.0, 7);
    const GuardOutcome g = apply(LeverageGuard(narrow), s);
    CHECK(g.dropped == 0);
    CHECK(rim_kept(s) == 20);
  }
}

TEST_CASE("leverage guard: bad settings and inputs are refused by name", "[frontend][guard]") {
  for (const double radius : {0.0, -1.0, kInf, std::nan("")}) {
    LeverageGuardConfig c;
    c.radius_px = radius;
    CHECK_THROWS_AS(LeverageGuard(c), hbos::InvalidArgument);
  }
  for (const double ratio : {0.0, -2.0, kInf}) {
    LeverageGuardConfig c;
    c.max_ratio = ratio;
    CHECK_THROWS_WITH(LeverageGuard(c), Catch::Contains("ratio limit"));
    LeverageGuardConfig r;
    r.consistency_z = ratio;
    CHECK_THROWS_WITH(LeverageGuard(r), Catch::Contains("consistency z"));
  }
  for (const double shift : {-0.5, kInf, std::nan("")}) {
    LeverageGuardConfig c;
    c.bias_cell_px = shift;
    CHECK_THROWS_WITH(LeverageGuard(c), Catch::Contains("shared-bias cell"));
  }
  const LeverageGuard guard(LeverageGuardConfig{});
  Scene s = scene(4.5, 5.0, 3);
  s.sigma.pop_back();
  CHECK_THROWS_WITH(apply(guard, s), Catch::Contains("419 sigmas"));
}
