// Unit tests of pose leverage (hbos/screening/pose_leverage.hpp): the analytic Jacobian against
// finite differences, group_leverage against an independent generalised eigensolver, its
// invariances and monotonicity, the far-background scenario it exists for, and its edge cases.

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "../support/alloc_counter.hpp"

namespace {

/// std::mt19937_64 is fully specified; the uniform transform is our own, so a seed gives the same
/// numbers on every standard library.
struct Rng {
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed) : engine(seed) {}
  double uniform(double a, double b) {
    return a + (b - a) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
  }
  Eigen::Index index(Eigen::Index n) {  // in [0, n)
    return static_cast<Eigen::Index>(engine() % static_cast<std::uint64_t>(n));
  }
};

Eigen::Isometry3d random_pose(Rng& rng) {
  Eigen::Vector3d axis(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  axis.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(rng.uniform(0.0, 0.6), axis).toRotationMatrix();
  T.translation() = Eigen::Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  return T;
}

/// n matches for `in_group` or the rest; points seen by the camera at `T_cur_world` at pixel
/// (u, v) and depth z, and ORB-like sigmas (1.2^octave).
struct Frame {
  std::vector<Eigen::Vector3d> points;  // world frame [m]
  std::vector<double> sigma;            // [px]
  std::vector<char> use;
  std::vector<char> in_group;

  [[nodiscard]] Eigen::Index size() const { return static_cast<Eigen::Index>(points.size()); }
  void add(const Eigen::Vector3d& X, double s, bool group, bool used = true) {
    points.push_back(X);
    sigma.push_back(s);
    use.push_back(used ? 1 : 0);
    in_group.push_back(group ? 1 : 0);
  }
  void add_seen(Rng& rng, const hbos::PinholeCamerad& camera, const Eigen::Isometry3d& T, double u0,
                double u1, double v0, double v1, double z0, double z1, bool group) {
    const Eigen::Vector3d p =
        camera.back_project({rng.uniform(u0, u1), rng.uniform(v0, v1)}, rng.uniform(z0, z1));
    add(T.inverse() * p, std::pow(1.2, std::floor(rng.uniform(0.0, 8.0))), group);
  }
};

std::size_t at(Eigen::Index i) { return static_cast<std::size_t>(i); }

hbos::GroupLeverage measure(const Frame& f, const hbos::PinholeCamerad& camera,
                            const Eigen::Isometry3d& T, double min_depth = 1e-3) {
  return hbos::group_leverage(
      f.size(), [&](Eigen::Index i) { return f.points[at(i)]; },
      [&](Eigen::Index i) { return f.sigma[at(i)]; },
      [&](Eigen::Index i) { return f.use[at(i)] != 0; },
      [&](Eigen::Index i) { return f.in_group[at(i)] != 0; }, camera, T, min_depth);
}

/// A random frame: `n_rest` matches over the image at depth 0.5-8 m and `n_group` in a random
/// box, at a random pose.
Frame random_frame(Rng& rng, const hbos::PinholeCamerad& camera, const Eigen::Isometry3d& T,
                   int n_rest, int n_group) {
  Frame f;
  for (int i = 0; i < n_rest; ++i) f.add_seen(rng, camera, T, 0, 640, 0, 480, 0.5, 8.0, false);
  const double u0 = rng.uniform(0, 540);
  const double v0 = rng.uniform(0, 380);
  for (int i = 0; i < n_group; ++i)
    f.add_seen(rng, camera, T, u0, u0 + 100, v0, v0 + 100, 0.5, 3.0, true);
  return f;
}

/// The pixel of X after the left perturbation delta = (omega, tau) of T, as refine_pose applies
/// it (R <- exp(omega) R, t <- exp(omega) t + tau), with the rotation from Eigen's AngleAxis.
Eigen::Vector2d perturbed_pixel(const hbos::PinholeCamerad& camera, const Eigen::Isometry3d& T,
                                const Eigen::Vector3d& X,
                                const Eigen::Matrix<double, 6, 1>& delta) {
  const Eigen::Vector3d omega = delta.head<3>();
  Eigen::Isometry3d update = Eigen::Isometry3d::Identity();
  if (omega.norm() > 0)
    update.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix();
  update.translation() = delta.tail<3>();
  return camera.project((update * T) * X);
}

/// d pixel / d delta at delta = 0 by central differences.
Eigen::Matrix<double, 2, 6> numeric_jacobian(const hbos::PinholeCamerad& camera,
                                             const Eigen::Isometry3d& T, const Eigen::Vector3d& X) {
  constexpr double h = 1e-6;
  Eigen::Matrix<double, 2, 6> J;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    delta(k) = h;
    J.col(k) =
        (perturbed_pixel(camera, T, X, delta) - perturbed_pixel(camera, T, X, -delta)) / (2 * h);
  }
  return J;
}

/// group_leverage's ratio computed independently: numeric Jacobians and Eigen's generalised
/// eigensolver on (H_group, H_rest).
double reference_ratio(const Frame& f, const hbos::PinholeCamerad& camera,
                       const Eigen::Isometry3d& T) {
  Eigen::MatrixXd H_group = Eigen::MatrixXd::Zero(6, 6);
  Eigen::MatrixXd H_rest = Eigen::MatrixXd::Zero(6, 6);
  for (std::size_t i = 0; i < f.points.size(); ++i) {
    if (f.use[i] == 0 || (T * f.points[i]).z() <= 1e-3) continue;
    const Eigen::Matrix<double, 2, 6> J = numeric_jacobian(camera, T, f.points[i]);
    (f.in_group[i] != 0 ? H_group : H_rest) += J.transpose() * J / (f.sigma[i] * f.sigma[i]);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      H_group, H_rest, Eigen::EigenvaluesOnly | Eigen::Ax_lBx);
  REQUIRE(solver.info() == Eigen::Success);
  return solver.eigenvalues().maxCoeff();
}

bool close(double a, double b, double rel) {
  return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b));
}

}  // namespace

TEST_CASE("projection_jacobian matches central differences of the perturbed projection",
          "[pose_leverage]") {
  const hbos::PinholeCamerad camera;
  Rng rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Isometry3d T = random_pose(rng);
    const Eigen::Vector3d p_c = camera.back_project(
        {rng.uniform(-100, 740), rng.uniform(-100, 580)}, rng.uniform(0.3, 20.0));
    const Eigen::Vector3d X = T.inverse() * p_c;
    const Eigen::Vector3d p = T * X;
    const Eigen::Matrix<double, 2, 6> J = hbos::detail::projection_jacobian(camera, p, 1.0 / p.z());
    const Eigen::Matrix<double, 2, 6> J_numeric = numeric_jacobian(camera, T, X);
    INFO("trial " << trial << "\nanalytic\n" << J << "\nnumeric\n" << J_numeric);
    CHECK((J - J_numeric).norm() <= 1e-6 * J.norm());
  }
}

TEST_CASE("group_leverage agrees with a generalised eigensolver on numeric Jacobians",
          "[pose_leverage]") {
  const hbos::PinholeCamerad camera;
  Rng rng(23);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Isometry3d T = random_pose(rng);
    Frame f = random_frame(rng, camera, T, 3 + static_cast<int>(rng.index(100)),
                           1 + static_cast<int>(rng.index(30)));
    // Some matches unused, and group membership shuffled into the rest as well.
    for (std::size_t i = 0; i < f.points.size(); ++i) {
      if (rng.uniform(0, 1) < 0.1) f.use[i] = 0;
      if (rng.uniform(0, 1) < 0.05) f.in_group[i] = 1;
    }
    const hbos::GroupLeverage L = measure(f, camera, T);
    const double reference = reference_ratio(f, camera, T);
    INFO("trial " << trial << " group " << L.group << " rest " << L.rest << " ratio " << L.ratio
                  << " reference " << reference);
    if (L.rest < 3) {
      CHECK(std::isinf(L.ratio));
      continue;
    }
    CHECK(close(L.ratio, reference, 1e-6));
  }
}

TEST_CASE("group_leverage is invariant to the world's scale, a common sigma factor and the order",
          "[pose_leverage]") {
  const hbos::PinholeCamerad camera;
  Rng rng(37);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Isometry3d T = random_pose(rng);
    const Frame f = random_frame(rng, camera, T, 60, 12);
    const double ratio = measure(f, camera, T).ratio;
    REQUIRE(std::isfinite(ratio));
    REQUIRE(ratio > 0);

    for (const double k : {0.01, 0.37, 3.0, 250.0}) {
      Frame scaled = f;
      for (auto& X : scaled.points) X *= k;
      Eigen::Isometry3d T_scaled = T;
      T_scaled.translation() *= k;
      INFO("trial " << trial << " world scale " << k);
      CHECK(close(measure(scaled, camera, T_scaled).ratio, ratio, 1e-9));
    }
    for (const double c : {0.1, 1.7, 40.0}) {
      Frame scaled = f;
      for (auto& s : scaled.sigma) s *= c;
      INFO("trial " << trial << " sigma factor " << c);
      CHECK(close(measure(scaled, camera, T).ratio, ratio, 1e-9));
    }
    // Fisher-Yates with our own draws, so the permutation is the same on every library.
    Frame permuted = f;
    for (std::size_t i = permuted.points.size() - 1; i > 0; --i) {
      const auto j = at(rng.index(static_cast<Eigen::Index>(i + 1)));
      std::swap(permuted.points[i], permuted.points[j]);
      std::swap(permuted.sigma[i], permuted.sigma[j]);
      std::swap(permuted.use[i], permuted.use[j]);
      std::swap(permuted.in_group[i], permuted.in_group[j]);
    }
    INFO("trial " << trial << " permuted");
    CHECK(close(measure(permuted, camera, T).ratio, ratio, 1e-9));
  }
}

TEST_CASE(
    "a match added to the rest never raises the ratio; one added to the group never lowers it",
    "[pose_leverage]") {
  const hbos::PinholeCamerad camera;
  Rng rng(41);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Isometry3d T = random_pose(rng);
    Frame f = random_frame(rng, camera, T, 20, 5);
    double ratio = measure(f, camera, T).ratio;
    REQUIRE(std::isfinite(ratio));
    for (int step = 0; step < 30; ++step) {
      const bool to_group = rng.uniform(0, 1) < 0.5;
      // Anywhere in the image, near or far: either kind of match can bite.
      f.add_seen(rng, camera, T, 0, 640, 0, 480, 0.4, 10.0, to_group);
      const double next = measure(f, camera, T).ratio;
      INFO("trial " << trial << " step " << step << (to_group ? " group " : " rest ") << ratio
                    << " -> " << next);
      if (to_group) {
        CHECK(next >= ratio * (1 - 1e-9));
      } else {
        CHECK(next <= ratio * (1 + 1e-9));
      }
      ratio = next;
    }
  }
}

TEST_CASE("a near group decides the pose when the background is far, not when it spans depth",
          "[pose_leverage]") {
  // 400 static matches over the whole image and 20 near ones (1.5 m) in the top-left corner, with
  // ORB-like sigmas. With the statics all at 4.5-5 m a rotation and a translation move them alike
  // and the near group alone fixes that direction; with the statics spread over 0.8-5 m their
  // depths separate the two. Measured over these seeds: 18-31 (far) and 0.22-0.41 (spread).
  const hbos::PinholeCamerad camera;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.4, -0.2, 1.0);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    for (const bool spread : {false, true}) {
      Rng rng(seed);
      Frame f;
      for (int i = 0; i < 400; ++i)
        f.add_seen(rng, camera, T, 0, 640, 0, 480, spread ? 0.8 : 4.5, 5.0, false);
      for (int i = 0; i < 20; ++i) f.add_seen(rng, camera, T, 0, 100, 0, 100, 1.5, 1.5, true);
      const hbos::GroupLeverage L = measure(f, camera, T);
      INFO("seed " << seed << (spread ? " statics at 0.8-5 m" : " statics at 4.5-5 m") << " ratio "
                   << L.ratio);
      CHECK(L.group == 20);
      CHECK(L.rest == 400);
      if (spread) {
        CHECK(L.ratio < 1.0);
      } else {
        CHECK(L.ratio > 1.0);
      }
    }
  }
}

TEST_CASE("group_leverage edge cases", "[pose_leverage]") {
  const hbos::PinholeCamerad camera;
  Rng rng(53);
  const Eigen::Isometry3d T = random_pose(rng);
  const Frame base = random_frame(rng, camera, T, 40, 8);
  const hbos::GroupLeverage L = measure(base, camera, T);
  REQUIRE(L.group == 8);
  REQUIRE(L.rest == 40);
  REQUIRE(std::isfinite(L.ratio));
  REQUIRE(L.ratio > 0);

  SECTION("an empty group has no leverage") {
    Frame f = base;
    for (auto& g : f.in_group) g = 0;
    const hbos::GroupLeverage E = measure(f, camera, T);
    CHECK(E.ratio == 0.0);
    CHECK(E.group == 0);
    CHECK(E.rest == 48);
    // Also when the rest is empty too, or has too few matches.
    CHECK(measure(Frame{}, camera, T).ratio == 0.0);
  }
  SECTION("fewer than 3 usable matches in the rest: the group is all there is") {
    // The information of 1 or 2 matches is singular, but rounding lets its Cholesky factorisation
    // through now and then (about one frame in six with 2 matches); the count must decide.
    for (int trial = 0; trial < 100; ++trial) {
      const Eigen::Isometry3d T_trial = random_pose(rng);
      Frame f = random_frame(rng, camera, T_trial, 3, 8);
      const Eigen::Index keep = trial % 3;
      Eigen::Index kept = 0;
      for (std::size_t i = 0; i < f.points.size(); ++i)
        if (f.in_group[i] == 0 && kept++ >= keep) f.use[i] = 0;
      const hbos::GroupLeverage R = measure(f, camera, T_trial);
      INFO("trial " << trial << " rest kept " << keep << " ratio " << R.ratio);
      CHECK(R.rest == keep);
      CHECK(R.group == 8);
      CHECK(std::isinf(R.ratio));
      CHECK(R.ratio > 0);
    }
    // Three rest matches in general position already fix a pose.
    Frame f = base;
    Eigen::Index kept = 0;
    for (std::size_t i = 0; i < f.points.size(); ++i)
      if (f.in_group[i] == 0 && kept++ >= 3) f.use[i] = 0;
    CHECK(std::isfinite(measure(f, camera, T).ratio));
  }
  SECTION("points behind the camera or closer than min_depth are skipped, as unused ones") {
    Frame f = base;
    const Eigen::Isometry3d T_world_cur = T.inverse();
    for (const bool group : {false, true}) {
      f.add(T_world_cur * Eigen::Vector3d(0.1, 0.2, -2.0), 1.0, group);        // behind
      f.add(T_world_cur * Eigen::Vector3d(0.0, 0.0, 0.0), 1.0, group);         // at the centre
      f.add(T_world_cur * Eigen::Vector3d(0.01, 0.0, 0.05), 1.0, group);       // nearer than 0.1 m
      f.add(T_world_cur * Eigen::Vector3d(0.1, 0.1, 1.0), 1.0, group, false);  // unused
    }
    const hbos::GroupLeverage S = measure(f, camera, T, 0.1);
    CHECK(S.group == L.group);
    CHECK(S.rest == L.rest);
    CHECK(S.ratio == L.ratio);
    // With the default min_depth the 5 cm points count.
    const hbos::GroupLeverage D = measure(f, camera, T);
    CHECK(D.group == L.group + 1);
    CHECK(D.rest == L.rest + 1);
  }
  SECTION("float agrees with double") {
    const hbos::PinholeCameraf camera_f;
    const auto float_ratio = [&](const Frame& f, const Eigen::Isometry3d& T_d) {
      const Eigen::Isometry3f T_f(T_d.matrix().cast<float>());
      const hbos::GroupLeverage F = hbos::group_leverage(
          f.size(), [&](Eigen::Index i) { return Eigen::Vector3f(f.points[at(i)].cast<float>()); },
          [&](Eigen::Index i) { return static_cast<float>(f.sigma[at(i)]); },
          [&](Eigen::Index i) { return f.use[at(i)] != 0; },
          [&](Eigen::Index i) { return f.in_group[at(i)] != 0; }, camera_f, T_f);
      CHECK(F.group == measure(f, camera, T_d).group);
      CHECK(F.rest == measure(f, camera, T_d).rest);
      return F.ratio;
    };
    CHECK(close(float_ratio(base, T), L.ratio, 1e-4));
    // A far background makes the rest's information ill-conditioned: summed in float it would be
    // off by 1e-4 here; summed in double only the rounding of the inputs remains (about 1e-7).
    Frame far;
    for (int i = 0; i < 2000; ++i) far.add_seen(rng, camera, T, 0, 640, 0, 480, 9.5, 10.0, false);
    for (int i = 0; i < 20; ++i) far.add_seen(rng, camera, T, 0, 100, 0, 100, 1.5, 1.5, true);
    const double far_ratio = measure(far, camera, T).ratio;
    INFO("far background: double " << far_ratio << " float " << float_ratio(far, T));
    CHECK(close(float_ratio(far, T), far_ratio, 2e-6));
  }
  SECTION("a non-finite point fails the depth test; one at infinite depth poisons the result") {
    // NaN anywhere in X makes every coordinate of T * X NaN, so the match is skipped.
    Frame f = base;
    for (const bool group : {false, true})
      f.add(Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 1.0, 2.0), 1.0, group);
    const hbos::GroupLeverage N = measure(f, camera, T);
    CHECK(N.group == L.group);
    CHECK(N.rest == L.rest);
    CHECK(N.ratio == L.ratio);
    // At infinite depth it passes the test but its information is not finite: NaN, never a number
    // that looks like an answer.
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    for (const bool group : {false, true}) {
      Frame g = random_frame(rng, camera, I, 40, 8);
      g.add(Eigen::Vector3d(0.0, 0.0, std::numeric_limits<double>::infinity()), 1.0, group);
      INFO((group ? "in the group" : "in the rest"));
      CHECK(std::isnan(measure(g, camera, I).ratio));
    }
  }
  SECTION("invalid min_depth, intrinsics or sigma throw, naming the field and value") {
    for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity()}) {
      INFO("min_depth " << bad);
      CHECK_THROWS_AS(measure(base, camera, T, bad), hbos::InvalidArgument);
    }
    CHECK_THROWS_WITH(measure(base, camera, T, 0.0),
                      Catch::Contains("min_depth must be finite and > 0, got 0"));
    hbos::PinholeCamerad bad_camera;
    bad_camera.fx = 0.0;
    CHECK_THROWS_AS(measure(base, bad_camera, T), hbos::InvalidArgument);
    CHECK_THROWS_WITH(measure(base, bad_camera, T),
                      Catch::Contains("fx must be finite and > 0, got 0"));
    bad_camera = {};
    bad_camera.cy = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(measure(base, bad_camera, T), hbos::InvalidArgument);

    Frame f = base;
    f.sigma[3] = 0.0;
    CHECK_THROWS_WITH(measure(f, camera, T),
                      Catch::Contains("sigma(3) must be finite and > 0, got 0"));
    f.use[3] = 0;  // an unused match's sigma is never read
    CHECK_NOTHROW(measure(f, camera, T));
  }
}

TEST_CASE("group_leverage allocates nothing", "[pose_leverage][alloc]") {
  const hbos::PinholeCamerad camera;
  Rng rng(61);
  const Eigen::Isometry3d T = random_pose(rng);
  const Frame f = random_frame(rng, camera, T, 300, 20);
  hbos_test::AllocationCounter counter;
  const hbos::GroupLeverage L = measure(f, camera, T);
  CHECK(counter.count() == 0);
  CHECK(std::isfinite(L.ratio));
}
