// Tests of hbos/threshold.hpp: each rule against hand-computed values, numpy's percentile
// convention, the strict outlier rule and bad parameters.

#include <hbos/threshold.hpp>

#include <catch2/catch.hpp>
#include <limits>
#include <random>

namespace {
Eigen::VectorXd one_to_ten() { return Eigen::VectorXd::LinSpaced(10, 1.0, 10.0); }
}  // namespace

TEST_CASE("adaptive range threshold is the paper's eq. 6", "[threshold]") {
  // delta = 0.7 * (10 - 1) + 1 = 7.3: scores 8, 9, 10 are outliers.
  const auto t = hbos::threshold_scores(one_to_ten(), hbos::AdaptiveRange{0.7});
  CHECK(t.threshold == Approx(7.3));
  CHECK(t.n_inliers == 7);
  CHECK(t.n_outliers() == 3);
  CHECK(t.inlier(6));
  CHECK_FALSE(t.inlier(7));
}

TEST_CASE("a score equal to the threshold is an inlier (strict outlier rule)", "[threshold]") {
  Eigen::VectorXd s(3);
  s << 0.0, 5.0, 10.0;
  const auto t = hbos::threshold_scores(s, hbos::AdaptiveRange{0.5});
  CHECK(t.threshold == 5.0);
  CHECK(t.inlier(1));
  CHECK_FALSE(t.inlier(2));
}

TEST_CASE("contamination threshold follows numpy.percentile(linear)", "[threshold]") {
  // q = 0.9, n = 10: v = 9 * 0.9 = 8.1, i = 8, g = 0.1 -> a[8] + (a[9] - a[8]) * 0.1 = 9.1.
  CHECK(hbos::threshold_scores(one_to_ten(), hbos::Contamination{0.1}).threshold == Approx(9.1));
  // q = 0.75, n = 10: v = 6.75, i = 6, g = 0.75 >= 0.5 -> numpy evaluates from the upper end:
  // a[7] - (a[7] - a[6]) * 0.25 = 8 - 0.25 = 7.75.
  CHECK(hbos::threshold_scores(one_to_ten(), hbos::Contamination{0.25}).threshold == 7.75);
  // The order of the input does not matter.
  Eigen::VectorXd shuffled(10);
  shuffled << 7, 3, 10, 1, 9, 2, 8, 4, 6, 5;
  CHECK(hbos::threshold_scores(shuffled, hbos::Contamination{0.1}).threshold == Approx(9.1));
}

TEST_CASE("median + k MAD", "[threshold]") {
  // {1,2,3,4,100}: median 3, |x - 3| = {2,1,0,1,97}, MAD = 1 -> 3 + 3 * 1.4826 * 1 = 7.4478.
  Eigen::VectorXd s(5);
  s << 1, 2, 3, 4, 100;
  const auto t = hbos::threshold_scores(s, hbos::MedianMad{3.0});
  CHECK(t.threshold == Approx(7.4478));
  CHECK(t.n_outliers() == 1);
  CHECK(hbos::threshold_scores(s, hbos::MedianMad{3.0, false}).threshold == Approx(6.0));
  // Even count: numpy's median averages the two middle values.
  Eigen::VectorXd even(4);
  even << 4, 1, 3, 2;
  CHECK(hbos::threshold_scores(even, hbos::MedianMad{1.0, false}).threshold == Approx(2.5 + 1.0));
}

TEST_CASE("fixed threshold", "[threshold]") {
  const auto t = hbos::threshold_scores(one_to_ten(), hbos::FixedThreshold{4.0});
  CHECK(t.threshold == 4.0);
  CHECK(t.n_inliers == 4);
}

TEST_CASE("float scores work with every rule", "[threshold]") {
  const Eigen::VectorXf s = one_to_ten().cast<float>();
  CHECK(hbos::threshold_scores(s, hbos::AdaptiveRange{0.7}).threshold == Approx(7.3f));
  CHECK(hbos::threshold_scores(s, hbos::Contamination{0.1}).threshold == Approx(9.1f));
}

TEST_CASE("threshold properties on random scores", "[threshold][property]") {
  std::mt19937 rng(17);
  std::lognormal_distribution<double> dist;
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::VectorXd s(20 + trial * 13);
    for (auto& v : s) v = dist(rng);
    for (const hbos::ThresholdRule& rule : {hbos::ThresholdRule{hbos::AdaptiveRange{0.3}},
                                            hbos::ThresholdRule{hbos::Contamination{0.2}},
                                            hbos::ThresholdRule{hbos::MedianMad{2.0}}}) {
      const auto t = hbos::threshold_scores(s, rule);
      Eigen::Index inliers = 0;
      for (Eigen::Index i = 0; i < s.size(); ++i) {
        CHECK(t.inlier(i) == (s(i) <= t.threshold));
        inliers += t.inlier(i) ? 1 : 0;
      }
      CHECK(inliers == t.n_inliers);
      // Every rule keeps the minimum and, on these skewed scores, drops the maximum.
      CHECK(t.threshold >= s.minCoeff());
    }
    // Contamination c rejects at most ceil(c n) samples (strict rule, interpolated threshold).
    const auto t = hbos::threshold_scores(s, hbos::Contamination{0.2});
    CHECK(static_cast<double>(t.n_outliers()) <= std::ceil(0.2 * static_cast<double>(s.size())));
  }
}

TEST_CASE("bad threshold input is rejected", "[threshold][errors]") {
  const Eigen::VectorXd s = one_to_ten();
  CHECK_THROWS_WITH(hbos::threshold_scores(s, hbos::AdaptiveRange{1.0}),
                    Catch::Contains("range_alpha must lie in the open interval (0, 1), got 1"));
  CHECK_THROWS_WITH(hbos::threshold_scores(s, hbos::AdaptiveRange{0.0}),
                    Catch::Contains("range_alpha"));
  CHECK_THROWS_WITH(hbos::threshold_scores(s, hbos::Contamination{0.6}),
                    Catch::Contains("contamination must lie in (0, 0.5], got 0.6"));
  CHECK_THROWS_WITH(hbos::threshold_scores(s, hbos::MedianMad{-1.0}),
                    Catch::Contains("MedianMad k"));
  CHECK_THROWS_WITH(hbos::threshold_scores(s, hbos::FixedThreshold{std::nan("")}),
                    Catch::Contains("finite"));
  CHECK_THROWS_WITH(hbos::threshold_scores(Eigen::VectorXd(0), hbos::AdaptiveRange{}),
                    Catch::Contains("empty score vector"));
  Eigen::VectorXd nan = s;
  nan(4) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(hbos::threshold_scores(nan, hbos::AdaptiveRange{}),
                    Catch::Contains("score 4 is not finite"));
  Eigen::Array<bool, Eigen::Dynamic, 1> mask(3);
  CHECK_THROWS_WITH(hbos::apply_threshold(s, 1.0, mask), Catch::Contains("3 entries"));
}
