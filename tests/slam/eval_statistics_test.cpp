// ErrorStatistics: numpy's conventions (median of an even count, population std) and the
// radians-to-degrees conversion after the statistic.
#include "eval/statistics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using Catch::Matchers::Contains;
using hbos::slam::compute_statistics;
using hbos::slam::ErrorStatistics;

TEST_CASE("statistics follow numpy: mean of the middle two, population std", "[eval][stats]") {
  Eigen::VectorXd even(4);
  even << 4.0, 1.0, 3.0, 2.0;
  const ErrorStatistics s = compute_statistics(even);
  CHECK(s.count == 4);
  CHECK(s.median == 2.5);
  CHECK(s.mean == 2.5);
  CHECK(s.rmse == Approx(std::sqrt(30.0 / 4.0)).epsilon(1e-15));
  // Population (ddof = 0): sqrt(5/4) = 1.118..., not the sample value sqrt(5/3) = 1.29...
  CHECK(s.std_dev == Approx(std::sqrt(1.25)).epsilon(1e-15));
  CHECK(s.min == 1.0);
  CHECK(s.max == 4.0);

  Eigen::VectorXd odd(5);
  odd << 9.0, -1.0, 7.0, 3.0, 5.0;
  CHECK(compute_statistics(odd).median == 5.0);
  Eigen::VectorXd one(1);
  one << 0.25;
  const ErrorStatistics single = compute_statistics(one);
  CHECK(single.median == 0.25);
  CHECK(single.std_dev == 0.0);
  CHECK(single.rmse == 0.25);
}

TEST_CASE("statistics: RMSE² = mean² + std² for any errors", "[eval][stats]") {
  std::mt19937 rng(3);
  std::gamma_distribution<double> errors(2.0, 0.01);
  for (int n : {2, 3, 10, 786, 1001}) {
    Eigen::VectorXd e(n);
    for (Eigen::Index i = 0; i < n; ++i) e(i) = errors(rng);
    const ErrorStatistics s = compute_statistics(e);
    CHECK(s.rmse * s.rmse == Approx(s.mean * s.mean + s.std_dev * s.std_dev).epsilon(1e-12));
    CHECK(s.min <= s.median);
    CHECK(s.median <= s.max);
    CHECK(s.mean <= s.rmse);
  }
}

TEST_CASE("rotation statistics are converted to degrees after the statistic", "[eval][stats]") {
  Eigen::VectorXd rad(3);
  rad << 3.141592653589793, 0.0, 3.141592653589793 / 2.0;
  const ErrorStatistics deg = compute_statistics(rad).radians_to_degrees();
  CHECK(deg.max == 180.0);
  CHECK(deg.min == 0.0);
  CHECK(deg.median == 90.0);
  CHECK(deg.mean == Approx(90.0).epsilon(1e-15));
  CHECK(deg.count == 3);
}

TEST_CASE("statistics reject empty or non-finite errors", "[eval][stats]") {
  CHECK_THROWS_WITH(compute_statistics(Eigen::VectorXd()), Contains("no errors"));
  Eigen::VectorXd e(2);
  e << 1.0, INFINITY;
  CHECK_THROWS_WITH(compute_statistics(e), Contains("finite"));
}
