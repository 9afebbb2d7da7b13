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

TEST_CASE("Birgé–Rozenblac: the O(n) search equals a brute-force count", "[binning]") {
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

TEST_CASE("Birgé–Rozenblac's edge counter is exact for every candidate and edge", "[binning]") {
  // The counter compares only the values of the edge's own cell unless the edge sits within
  // 1e-4 of a cell boundary. Data with values exactly on candidate edges and on cell boundaries
  // (integer grids, whose range makes k/b land on values and on cell edges alike), heavy ties and
  // extreme outliers probe exactly those cases; every (b, k) is checked against a direct count.
  std::vector<Eigen::VectorXd> sets;
  sets.push_back(linear_grid(720));                             // 719 = range: many exact hits
  sets.push_back(linear_grid(1025));                            // range 1024: powers of two
  sets.push_back(Eigen::VectorXd::LinSpaced(4096, -1.0, 1.0));  // cells of exactly 4 values
  Eigen::VectorXd ties(3000);
  for (Eigen::Index i = 0; i < ties.size(); ++i) ties(i) = static_cast<double>(i % 7) * 0.125;
  sets.push_back(ties);
  std::mt19937 rng(9);
  std::normal_distribution<double> normal;
  Eigen::VectorXd outlier(2500);
  for (Eigen::Index i = 0; i < outlier.size(); ++i) outlier(i) = normal(rng);
  outlier(17) = 1e6;  // squeezes every other value into the first cells
  sets.push_back(outlier);
  // Every edge k/b itself and its two floating-point neighbours, on [0, 1]: here the rounding of
  // u M and u b can disagree, which is what the boundary rule guards (without it: 44 mismatches).
  std::vector<double> fractions{0.0, 1.0};
  for (int b = 2; b <= 80; ++b) {
    for (int k = 1; k < b; ++k) {
      const double e = static_cast<double>(k) / static_cast<double>(b);
      fractions.insert(fractions.end(), {e, std::nextafter(e, 0.0), std::nextafter(e, 2.0)});
    }
  }
  sets.push_back(Eigen::Map<const Eigen::VectorXd>(fractions.data(),
                                                   static_cast<Eigen::Index>(fractions.size())));

  std::vector<double> values;
  std::vector<std::uint32_t> index;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const Eigen::VectorXd& x = sets[s];
    const double lo = x.minCoeff(), hi = x.maxCoeff();
    const double inv_range = 1.0 / (hi - lo);
    hbos::detail::EdgeCounter counter(x.data(), x.size(), 1, lo, hi, values, index);
    const auto b_max = static_cast<Eigen::Index>(std::sqrt(static_cast<double>(x.size())));
    auto direct = [&](Eigen::Index b, Eigen::Index k) {
      std::uint32_t count = 0;
      for (const double v : x)
        count += (v - lo) * inv_range * static_cast<double>(b) < static_cast<double>(k) ? 1U : 0U;
      return count;
    };
    // Single queries.
    std::size_t mismatches = 0;
    for (Eigen::Index b = 2; b <= b_max; ++b)
      for (Eigen::Index k = 1; k < b; ++k)
        if (counter.below(static_cast<double>(b), static_cast<double>(k)) != direct(b, k))
          ++mismatches;
    // The sweep: every (b, k) exactly once, each b in increasing k, with the same counts.
    std::vector<Eigen::Index> last_k(static_cast<std::size_t>(b_max) + 1, 0);
    std::size_t visits = 0, out_of_order = 0, sweep_mismatches = 0;
    counter.for_each_edge(b_max, [&](std::uint32_t b, std::uint32_t k, std::uint32_t below) {
      ++visits;
      if (static_cast<Eigen::Index>(k) != last_k[b] + 1) ++out_of_order;
      last_k[b] = k;
      if (below != direct(b, k)) ++sweep_mismatches;
    });
    INFO("data set " << s);
    CHECK(mismatches == 0);
    CHECK(sweep_mismatches == 0);
    CHECK(out_of_order == 0);
    CHECK(visits == static_cast<std::size_t>((b_max - 1) * b_max / 2));
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
