// Tests of hbos/binning.hpp: bin-count rules against hand-computed values and an independent
// brute-force Birgé–Rozenblac, plus every invalid spec.

#include <hbos/binning.hpp>
#include <hbos/histogram.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

namespace {

Eigen::Index bins_for(const Eigen::VectorXd& x, hbos::BinCountRule rule) {
  hbos::FeatureSpec spec;
  spec.binning.rule = rule;
  hbos::Histogram<double> h;
  std::vector<double> scratch;
  h.refit(x, spec, {}, scratch);
  return h.bins();
}

Eigen::VectorXd linear_grid(Eigen::Index n) {
  return Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1));
}

// Birgé–Rozenblac by brute force: every candidate histogram counted value by value with the
// floor formula floor(u b), u = (v - lo) * (1 / (hi - lo)), no sorting, no binary search, and the
// likelihood summed term by term; `penalty_times_b` switches to PyOD's variant.
Eigen::Index brute_force_birge(const Eigen::VectorXd& x, bool penalty_times_b = false) {
  const double lo = x.minCoeff(), hi = x.maxCoeff();
  const double inv_range = 1.0 / (hi - lo);
  const auto n = static_cast<double>(x.size());
  Eigen::Index best = 1;
  double best_l = -1e300;
  for (Eigen::Index b = 1; b <= static_cast<Eigen::Index>(std::sqrt(n)); ++b) {
    std::vector<double> counts(static_cast<std::size_t>(b), 0.0);
    for (double v : x) {
      auto k = static_cast<Eigen::Index>((v - lo) * inv_range * static_cast<double>(b));
      ++counts[static_cast<std::size_t>(std::min(k, b - 1))];
    }
    const double db = static_cast<double>(b);
    double l = 0.0;
    for (double c : counts)
      if (c > 0) l += c * std::log(db * c / n);
    const double penalty = db - 1.0 + std::pow(std::log(db), 2.5);
    l -= penalty_times_b ? db * penalty : penalty;
    if (l > best_l) {
      best_l = l;
      best = b;
    }
  }
  return best;
}

}  // namespace

TEST_CASE("bin-count rules by hand", "[binning]") {
  // sqrt(100) = 10; Sturges: ceil(log2(1000) + 1) = ceil(10.97) = 11.
  CHECK(bins_for(linear_grid(100), hbos::BinCountRule::Sqrt) == 10);
  CHECK(bins_for(linear_grid(101), hbos::BinCountRule::Sqrt) == 11);
  CHECK(bins_for(linear_grid(1000), hbos::BinCountRule::Sturges) == 11);
  // Freedman–Diaconis on 0..99: IQR = 74.25 - 24.75 = 49.5, h = 99 / cbrt(100) = 21.33,
  // range 99 -> ceil(4.64) = 5.
  CHECK(bins_for(linear_grid(100), hbos::BinCountRule::FreedmanDiaconis) == 5);
  // Scott on 0..99: std = sqrt((100^2 - 1) / 12) = 28.866, h = cbrt(24 sqrt(pi) / 100) * std
  // = 0.75180 * 28.866 = 21.702, range 99 -> ceil(4.56) = 5.
  CHECK(bins_for(linear_grid(100), hbos::BinCountRule::Scott) == 5);
}

TEST_CASE("width rules fall back to Sturges when the width degenerates", "[binning]") {
  // 90 % ties: IQR = 0, so Freedman–Diaconis has no width; Sturges(100) = ceil(7.64) = 8.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(100);
  for (Eigen::Index i = 0; i < 10; ++i) x(i) = static_cast<double>(i + 1);
  CHECK(bins_for(x, hbos::BinCountRule::FreedmanDiaconis) == 8);
}

TEST_CASE("Birgé–Rozenblac: the O(n log n) search equals a brute-force count", "[binning]") {
  std::mt19937 rng(42);
  std::normal_distribution<double> normal;
  std::exponential_distribution<double> expo(1.0);
  for (int trial = 0; trial < 25; ++trial) {
    const auto n = static_cast<Eigen::Index>(50 + 97 * trial);
    Eigen::VectorXd x(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      // Mixtures of shapes: normal, bimodal, skewed.
      const double v = trial % 3 == 0   ? normal(rng)
                       : trial % 3 == 1 ? normal(rng) + (i % 2 == 0 ? 6.0 : 0.0)
                                        : expo(rng);
      x(i) = v;
    }
    INFO("trial " << trial << ", n = " << n);
    const auto ours = bins_for(x, hbos::BinCountRule::BirgeRozenblac);
    CHECK(ours == brute_force_birge(x));
  }
}

TEST_CASE("Birgé–Rozenblac counts its penalty once, as published", "[binning]") {
  // On a clearly bimodal sample the published criterion keeps many bins while PyOD's variant,
  // which subtracts the penalty b times, collapses to very few: the two must differ.
  std::mt19937 rng(1);
  std::normal_distribution<double> normal(0.0, 0.3);
  Eigen::VectorXd x(2000);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = normal(rng) + (i % 2 == 0 ? 4.0 : 0.0);
  const auto ours = bins_for(x, hbos::BinCountRule::BirgeRozenblac);
  CHECK(ours == brute_force_birge(x, false));
  CHECK(ours > brute_force_birge(x, true));
  CHECK(ours >= 8);
}

TEST_CASE("invalid binning specs are rejected with a message", "[binning][errors]") {
  auto reject = [](hbos::FeatureSpec spec, const char* what) {
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(10, 0.0, 1.0);
    hbos::Histogram<double> h;
    std::vector<double> scratch;
    INFO(what);
    CHECK_THROWS_AS(hbos::detail::validate(spec, 3), hbos::InvalidArgument);
    CHECK_THROWS_WITH(hbos::detail::validate(spec, 3),
                      Catch::Contains("feature 3") && Catch::Contains(what));
  };
  hbos::FeatureSpec spec;
  spec.binning.bins = 0;
  reject(spec, "bin count must be >= 1");
  spec = {};
  spec.binning.bins = 100;
  spec.binning.max_bins = 10;
  reject(spec, "exceeds max_bins");
  spec = {};
  spec.binning.method = hbos::BinningMethod::FixedWidth;
  spec.binning.width = 0.0;
  reject(spec, "width must be finite and > 0");
  spec.binning.width = std::nan("");
  reject(spec, "width must be finite and > 0");
  spec = {};
  spec.binning.shifts = 0;
  reject(spec, "shifts must be >= 1");
  spec = hbos::angle_feature();
  spec.tail = hbos::Tail::Upper;
  reject(spec, "periodic feature has no upper or lower tail");
  spec = hbos::angle_feature();
  spec.binning.method = hbos::BinningMethod::EqualFrequency;
  reject(spec, "not defined on a circle");
  spec = hbos::angle_feature();
  spec.period = -1.0;
  reject(spec, "period must be finite and > 0");
}
