// Tests of hbos/workspace.hpp: it agrees with the one-call API, and after warm-up it fits, scores
// and thresholds a frame without a single heap allocation (counted, not assumed).

#include <hbos/workspace.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "../support/alloc_counter.hpp"

template class hbos::Workspace<float>;
template class hbos::Workspace<double>;

namespace {

/// One frame of residual-like features: magnitude (px) and direction (rad).
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> residual_frame(std::mt19937& rng,
                                                                     Eigen::Index n) {
  std::normal_distribution<double> noise(0.0, 1.0);
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> x(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double dx = noise(rng) + (i % 10 == 0 ? 8.0 : 0.0);  // a coherent moving 10 %
    const double dy = noise(rng);
    x(i, 0) = static_cast<Scalar>(std::hypot(dx, dy));
    x(i, 1) = static_cast<Scalar>(std::atan2(dy, dx));
  }
  return x;
}

hbos::HbosParams residual_params() {
  hbos::HbosParams params;
  hbos::FeatureSpec magnitude;
  magnitude.binning.method = hbos::BinningMethod::FixedWidth;
  magnitude.binning.width = 0.5;  // [px]
  magnitude.binning.max_bins = 4096;
  magnitude.tail = hbos::Tail::Upper;
  params.features = {magnitude, hbos::angle_feature(16)};
  return params;
}

}  // namespace

TEST_CASE("the workspace agrees with fit + score + threshold_scores", "[workspace]") {
  std::mt19937 rng(2);
  for (const auto& params : {hbos::HbosParams{}, residual_params()}) {
    for (const hbos::ThresholdRule& rule : {hbos::ThresholdRule{hbos::AdaptiveRange{0.7}},
                                            hbos::ThresholdRule{hbos::Contamination{0.1}},
                                            hbos::ThresholdRule{hbos::MedianMad{3.0}}}) {
      hbos::Workspace<double> ws(params, rule);
      for (Eigen::Index n : {100, 1000, 37, 2000}) {
        const Eigen::MatrixXd x = residual_frame<double>(rng, n);
        const auto summary = ws.run(x);
        const auto model = hbos::Hbosd::fit(x, params);
        const Eigen::VectorXd scores = model.score(x);
        const auto expected = hbos::threshold_scores(scores, rule);
        CHECK((ws.scores() - scores).cwiseAbs().maxCoeff() < 1e-12);
        CHECK((ws.contributions() - model.contributions(x)).cwiseAbs().maxCoeff() < 1e-12);
        CHECK(summary.threshold == Approx(expected.threshold).epsilon(1e-12));
        CHECK(summary.n_inliers == expected.n_inliers);
        CHECK(summary.n_rows == n);
        CHECK((ws.inlier() == expected.inlier).all());
        CHECK(ws.histogram(0).bins() == model.histogram(0).bins());
      }
    }
  }
}

TEMPLATE_TEST_CASE("row-major frames give the column-major frame's results", "[workspace]", float,
                   double) {
  // The workspace records bin indices in 16 bits: a row-major frame of two few-bin features
  // takes the interleaved kernel and widens its bytes into them.
  using Scalar = TestType;
  using RowMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::mt19937 rng(5);
  hbos::HbosParams params;
  params.feature.binning.bins = 10;
  params.feature.binning.shifts = 1;
  hbos::Workspace<Scalar> by_columns(params, hbos::Contamination{0.1});
  hbos::Workspace<Scalar> by_rows(params, hbos::Contamination{0.1});
  for (const Eigen::Index n : {1, 17, 1000, 4081, 9000}) {
    const auto x = residual_frame<Scalar>(rng, n);
    const RowMajor rows = x;
    const auto expected = by_columns.run(x);
    const auto got = by_rows.run(rows);
    CHECK(got.threshold == expected.threshold);
    CHECK(got.n_inliers == expected.n_inliers);
    CHECK(by_rows.scores() == by_columns.scores());
    CHECK(by_rows.contributions() == by_columns.contributions());
    for (Eigen::Index j = 0; j < 2; ++j)
      CHECK(by_rows.histogram(j).counts() == by_columns.histogram(j).counts());
  }
}

TEMPLATE_TEST_CASE("no heap allocation after warm-up", "[workspace][alloc]", float, double) {
  std::mt19937 rng(3);
  for (const auto& params : {hbos::HbosParams{}, residual_params()}) {
    for (const hbos::ThresholdRule& rule : {hbos::ThresholdRule{hbos::AdaptiveRange{0.7}},
                                            hbos::ThresholdRule{hbos::Contamination{0.1}},
                                            hbos::ThresholdRule{hbos::MedianMad{3.0}}}) {
      hbos::Workspace<TestType> ws(params, rule);
      // Frames generated up front: only the workspace may run while counting.
      std::vector<Eigen::Matrix<TestType, Eigen::Dynamic, Eigen::Dynamic>> frames;
      for (Eigen::Index n : {1000, 300, 1000, 700, 999, 1000})
        frames.push_back(residual_frame<TestType>(rng, n));
      ws.run(frames[0]);  // warm-up: grows every buffer to the largest frame
      // A reserve() large enough for any bin count seen makes later frames allocation-free even
      // when their fixed-width range (and so their bin count) grows.
      ws.reserve(1000, 2, 4096);
      hbos_test::AllocationCounter counter;
      Eigen::Index inliers = 0;
      for (const auto& frame : frames) inliers += ws.run(frame).n_inliers;
      CHECK(counter.count() == 0);
      CHECK(inliers > 0);
    }
  }
}

TEST_CASE("the counting allocator does count", "[workspace][alloc]") {
  // Guards the tests above against a counter that never counts, on both routes to the heap.
  hbos_test::AllocationCounter counter;
  {
    std::vector<int> via_operator_new(100);
    hbos_test::escape(via_operator_new.data());
  }
  const std::size_t after_vector = counter.count();
  CHECK(after_vector >= 1);
  {
    Eigen::VectorXd via_eigen_malloc(100);  // Eigen's aligned_malloc calls std::malloc
    hbos_test::escape(via_eigen_malloc.data());
  }
  CHECK(counter.count() >= after_vector + 1);
}

TEST_CASE("reserve() makes even the first frame allocation-free", "[workspace][alloc]") {
  std::mt19937 rng(4);
  const Eigen::MatrixXd x = residual_frame<double>(rng, 1500);
  hbos::Workspace<double> ws(hbos::HbosParams{}, hbos::AdaptiveRange{0.7});
  ws.reserve(2000, 2);
  hbos_test::AllocationCounter counter;
  ws.run(x);
  CHECK(counter.count() == 0);
}

TEST_CASE("workspace bad input", "[workspace][errors]") {
  CHECK_THROWS_WITH((hbos::Workspace<double>(hbos::HbosParams{}, hbos::AdaptiveRange{1.5})),
                    Catch::Contains("range_alpha"));
  hbos::Workspace<double> ws;
  CHECK_THROWS_WITH(ws.run(Eigen::MatrixXd(0, 2)), Catch::Contains("empty"));
  ws.run(Eigen::MatrixXd::Identity(10, 2));
  CHECK_THROWS_WITH(ws.histogram(2), Catch::Contains("out of range"));
}
