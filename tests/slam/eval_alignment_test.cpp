// Horn/Kabsch and Umeyama alignment: exact recovery of known SE(3) and Sim(3) transforms, the
// reflection fix on mirrored point sets, and input checks.
#include "eval/alignment.hpp"
#include "eval_test_support.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <random>

using Catch::Matchers::Contains;
using hbos::slam::align_rigid;
using hbos::slam::align_similarity;
using hbos::slam::Similarity3;
using hbos::slam::test::random_rotation;
using hbos::slam::test::random_vector;

namespace {

Eigen::Matrix3Xd random_points(std::mt19937& rng, Eigen::Index n, double extent) {
  Eigen::Matrix3Xd points(3, n);
  for (Eigen::Index i = 0; i < n; ++i) points.col(i) = random_vector(rng, extent);
  return points;
}

double cost(const Similarity3& s, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& y) {
  return (s.apply(x) - y).squaredNorm();
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("alignment of a point set with itself is the identity", "[eval][alignment]") {
  std::mt19937 rng(1);
  const Eigen::Matrix3Xd x = random_points(rng, 40, 2.0);
  for (const Similarity3& s : {align_rigid(x, x), align_similarity(x, x)}) {
    CHECK(max_abs(s.rotation - Eigen::Matrix3d::Identity()) < 1e-14);
    CHECK(max_abs(s.translation) < 1e-14);
    CHECK(std::abs(s.scale - 1.0) < 1e-14);
    CHECK(max_abs(s.apply(x) - x) < 1e-14);
  }
}

TEST_CASE("align_rigid recovers a random SE(3) to machine precision", "[eval][alignment]") {
  for (unsigned seed = 1; seed <= 25; ++seed) {
    std::mt19937 rng(seed);
    const Eigen::Matrix3Xd x = random_points(rng, 30, 3.0);
    const Eigen::Matrix3d r = random_rotation(rng);
    const Eigen::Vector3d t = random_vector(rng, 10.0);
    const Eigen::Matrix3Xd y = (r * x).colwise() + t;
    const Similarity3 s = align_rigid(x, y);
    INFO("seed " << seed);
    CHECK(max_abs(s.rotation - r) < 1e-13);
    CHECK(max_abs(s.translation - t) < 1e-12);
    CHECK(s.scale == 1.0);
    CHECK(std::abs(s.rotation.determinant() - 1.0) < 1e-13);
  }
}

TEST_CASE("align_similarity recovers a random Sim(3) to machine precision", "[eval][alignment]") {
  for (unsigned seed = 1; seed <= 25; ++seed) {
    std::mt19937 rng(100 + seed);
    std::uniform_real_distribution<double> log_scale(-3.0, 3.0);
    const Eigen::Matrix3Xd x = random_points(rng, 30, 3.0);
    const Eigen::Matrix3d r = random_rotation(rng);
    const Eigen::Vector3d t = random_vector(rng, 10.0);
    const double c = std::exp(log_scale(rng));
    const Eigen::Matrix3Xd y = ((c * r) * x).colwise() + t;
    const Similarity3 s = align_similarity(x, y);
    INFO("seed " << seed << ", scale " << c);
    CHECK(std::abs(s.scale - c) < 1e-13 * c);
    CHECK(max_abs(s.rotation - r) < 1e-13);
    CHECK(max_abs(s.translation - t) < 1e-12);
    // The rigid alignment of the same data has the same rotation (Umeyama's R does not depend
    // on the scale) but scale 1.
    const Similarity3 rigid = align_rigid(x, y);
    CHECK(max_abs(rigid.rotation - s.rotation) < 1e-13);
    CHECK(rigid.scale == 1.0);
  }
}

TEST_CASE("Umeyama's scale equals ORB-SLAM's evaluate_ate_scale formula on noisy data",
          "[eval][alignment]") {
  std::mt19937 rng(5);
  const Eigen::Matrix3Xd x = random_points(rng, 50, 1.0);
  Eigen::Matrix3Xd y = ((0.37 * random_rotation(rng)) * x).colwise() + random_vector(rng, 2.0);
  y += random_points(rng, 50, 0.05);
  const Similarity3 s = align_similarity(x, y);
  const Eigen::Matrix3Xd xc = x.colwise() - x.rowwise().mean();
  const Eigen::Matrix3Xd yc = y.colwise() - y.rowwise().mean();
  const double orb_scale = (yc.array() * (s.rotation * xc).array()).sum() / xc.squaredNorm();
  CHECK(std::abs(s.scale - orb_scale) < 1e-13 * orb_scale);
}

TEST_CASE("a mirrored point set gets the best proper rotation, never a reflection",
          "[eval][alignment]") {
  const Eigen::Matrix3d mirror = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  SECTION("non-planar set: the reflection fix is needed and leaves a residual") {
    std::mt19937 rng(9);
    const Eigen::Matrix3Xd x = random_points(rng, 40, 1.0);
    const Eigen::Matrix3Xd y = mirror * x;
    // Without the fix, U·Vᵀ would be the mirror itself (det −1) with zero residual.
    for (const Similarity3& s : {align_rigid(x, y), align_similarity(x, y)}) {
      CHECK(std::abs(s.rotation.determinant() - 1.0) < 1e-13);
      CHECK(max_abs(s.rotation * s.rotation.transpose() - Eigen::Matrix3d::Identity()) < 1e-13);
      CHECK(cost(s, x, y) > 1.0);
      // Optimal among proper rotations: every small rotation away from it costs more.
      for (int k = 0; k < 50; ++k) {
        Similarity3 perturbed = s;
        perturbed.rotation =
            Eigen::AngleAxisd(1e-3, random_vector(rng, 1.0).normalized()) * s.rotation;
        perturbed.translation =
            y.rowwise().mean() - perturbed.scale * perturbed.rotation * x.rowwise().mean();
        CHECK(cost(perturbed, x, y) > cost(s, x, y));
      }
    }
  }
  SECTION("planar set: its mirror image is a rotation by 180 degrees, found exactly") {
    std::mt19937 rng(10);
    Eigen::Matrix3Xd x = random_points(rng, 40, 1.0);
    x.row(2).setZero();  // in the plane z = 0
    const Eigen::Matrix3d mirror_y = Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal();
    const Eigen::Matrix3Xd y = mirror_y * x;
    const Similarity3 s = align_rigid(x, y);
    CHECK(std::abs(s.rotation.determinant() - 1.0) < 1e-13);
    CHECK(std::sqrt(cost(s, x, y)) < 1e-12);
    CHECK(max_abs(s.rotation - Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal().toDenseMatrix()) <
          1e-13);
  }
}

TEST_CASE("alignment rejects unusable point sets", "[eval][alignment]") {
  const Eigen::Matrix3Xd two = Eigen::Matrix3Xd::Random(3, 2);
  const Eigen::Matrix3Xd three = Eigen::Matrix3Xd::Random(3, 3);
  CHECK_THROWS_WITH(align_rigid(two, three), Contains("differ in size: 2 vs 3"));
  CHECK_THROWS_WITH(align_rigid(two.leftCols(1), two.leftCols(1)),
                    Contains("at least 2 corresponding points, got 1"));
  Eigen::Matrix3Xd bad = three;
  bad(1, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(align_similarity(bad, three), Contains("finite"));
  const Eigen::Matrix3Xd same = Eigen::Vector3d(1, 2, 3).replicate(1, 4);
  CHECK_THROWS_WITH(align_similarity(same, Eigen::Matrix3Xd::Random(3, 4)),
                    Contains("all estimate points coincide"));
  // Coinciding but for rounding (a constant position written out and read back) is coinciding:
  // the fit gave a scale of 1e-28 and an RMSE of 0.
  Eigen::Matrix3Xd nearly = Eigen::Vector3d(1.38, 0.6185, 1.6972).replicate(1, 4);
  nearly(0, 2) = std::nextafter(nearly(0, 2), 2.0);
  CHECK_THROWS_WITH(align_similarity(Eigen::Matrix3Xd::Random(3, 4), nearly),
                    Contains("all ground-truth points coincide"));
  CHECK_THROWS_WITH(align_similarity(nearly, Eigen::Matrix3Xd::Random(3, 4)),
                    Contains("all estimate points coincide"));
  // Two points fix everything but the rotation about their line, which does not change the
  // residual: the scripts accept 2 pairs, so do we.
  const Similarity3 s = align_rigid(two, two);
  CHECK(std::sqrt(cost(s, two, two)) < 1e-14);
}
