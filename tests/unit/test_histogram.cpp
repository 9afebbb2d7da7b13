// Tests of hbos/histogram.hpp: hand-computed golden cases (derivations in comments), the interval
// convention, tails, out-of-range rules, constant features, periodic features and shifted
// histograms.

#include <hbos/histogram.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using Vector = Eigen::VectorXd;

hbos::FeatureSpec plain(Eigen::Index bins) {
  hbos::FeatureSpec spec;
  spec.binning.bins = bins;
  return spec;
}

hbos::Histogram<double> fit(const Vector& x, const hbos::FeatureSpec& spec,
                            hbos::ScoringOptions options = {}) {
  hbos::Histogram<double> h;
  std::vector<double> scratch;
  h.refit(x, spec, options, scratch);
  return h;
}

Vector values(std::initializer_list<double> v) {
  Vector x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double e : v) x(i++) = e;
  return x;
}

}  // namespace

// Every member of the class template compiles for both scalar types.
template class hbos::Histogram<float>;
template class hbos::Histogram<double>;

TEST_CASE("golden: four equal-width bins by hand", "[histogram]") {
  // x = {0, 1,1, 2,2,2, 3,3,3,3}; lo = 0, hi = 3, width = 0.75, edges 0, .75, 1.5, 2.25, 3.
  // Bins [0,.75) {0} -> 1; [.75,1.5) {1,1} -> 2; [1.5,2.25) {2,2,2} -> 3; [2.25,3] {3 x4} -> 4.
  // Equal widths, so h_max / h_k = 4 / count_k: contributions log 4, log 2, log(4/3), 0.
  // cap = log(h_max * w_max / 0.5) = log(4 / 0.5) = log 8.
  const auto h = fit(values({0, 1, 1, 2, 2, 2, 3, 3, 3, 3}), plain(4));
  REQUIRE(h.bins() == 4);
  CHECK(h.counts() == std::vector<Eigen::Index>{1, 2, 3, 4});
  CHECK(h.edges()[1] == Approx(0.75));
  CHECK(h.bin_contributions()[0] == Approx(std::log(4.0)));
  CHECK(h.bin_contributions()[1] == Approx(std::log(2.0)));
  CHECK(h.bin_contributions()[2] == Approx(std::log(4.0 / 3.0)));
  CHECK(h.bin_contributions()[3] == 0.0);
  CHECK(h.cap() == Approx(std::log(8.0)));
  CHECK(h.mode() == 3);
  CHECK(h.contribution(1.0) == Approx(std::log(2.0)));
}

TEST_CASE("a value on an interior edge is counted and scored in the bin to its right",
          "[histogram]") {
  // x = {0,1,2,3,4}, 4 bins of width 1: edges exactly 0,1,2,3,4 -> counts {1,1,1,2}: the maximum 4
  // falls in the closed last bin. The value 1 sits on edge e_1: counted in bin 1 ([1,2)), and
  // scored from bin 1 too (PyOD would count it in bin 1 but score it from bin 0).
  const auto h = fit(values({0, 1, 2, 3, 4}), plain(4));
  CHECK(h.counts() == std::vector<Eigen::Index>{1, 1, 1, 2});
  for (double edge : {1.0, 2.0, 3.0}) {
    CHECK(h.bin_of(edge) == static_cast<Eigen::Index>(edge));
  }
  CHECK(h.bin_of(4.0) == 3);
  CHECK(h.contribution(1.0) == Approx(std::log(2.0)));
  CHECK(h.contribution(4.0) == 0.0);
}

TEST_CASE("every training value is scored from the bin it was counted in", "[histogram]") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> grid(0, 40);
  for (int trial = 0; trial < 20; ++trial) {
    // Integer-valued data hit the edges often (edges are multiples of 40 / k).
    Vector x(300);
    for (auto& v : x) v = grid(rng);
    for (Eigen::Index bins : {4, 5, 8, 10}) {
      const auto h = fit(x, plain(bins));
      std::vector<Eigen::Index> recount(static_cast<std::size_t>(h.bins()), 0);
      for (double v : x) {
        const auto b = h.bin_of(v);
        ++recount[static_cast<std::size_t>(b)];
        CHECK(h.contribution(v) == h.bin_contributions()[static_cast<std::size_t>(b)]);
      }
      CHECK(recount == h.counts());
    }
  }
}

TEST_CASE("out-of-range values: tolerance band, then the cap", "[histogram]") {
  hbos::ScoringOptions options;
  options.range_tolerance = 0.5;
  const auto h = fit(values({0, 1, 1, 2, 2, 2, 3, 3, 3, 3}), plain(4), options);
  const double w = 0.75;
  CHECK(h.contribution(3.0 + 0.4 * w) == h.bin_contributions().back());
  CHECK(h.contribution(3.0 + 0.6 * w) == h.cap());
  CHECK(h.contribution(0.0 - 0.4 * w) == h.bin_contributions().front());
  CHECK(h.contribution(-0.6 * w) == h.cap());
  CHECK(h.contribution(1e300) == h.cap());
  // The cap bounds every contribution.
  for (double c : h.bin_contributions()) CHECK(c <= h.cap());
}

TEST_CASE("empty bins score as empty_bin_count samples", "[histogram]") {
  // x = {0,0,0,0, 10}, 5 bins of width 2: counts {4,0,0,0,1}.
  // Empty bin: log(h_max * w / 0.5) = log(4 / 0.5) = log 8; the bin holding 10: log 4.
  const auto h = fit(values({0, 0, 0, 0, 10}), plain(5));
  CHECK(h.counts() == std::vector<Eigen::Index>{4, 0, 0, 0, 1});
  CHECK(h.contribution(5.0) == Approx(std::log(8.0)));
  CHECK(h.contribution(10.0) == Approx(std::log(4.0)));
  hbos::ScoringOptions one;
  one.empty_bin_count = 1.0;
  CHECK(fit(values({0, 0, 0, 0, 10}), plain(5), one).contribution(5.0) == Approx(std::log(4.0)));
}

TEST_CASE("Tail::Upper: nothing below the mode scores, the score never decreases above it",
          "[histogram]") {
  std::mt19937 rng(3);
  std::gamma_distribution<double> residual(2.0, 1.0);  // skewed like residual magnitudes
  Vector x(2000);
  for (auto& v : x) v = residual(rng);
  x(0) = 40.0;  // a gross outlier: a lone bin far in the tail
  hbos::FeatureSpec spec = plain(50);
  spec.tail = hbos::Tail::Upper;
  const auto h = fit(x, spec);
  const auto& c = h.bin_contributions();
  for (Eigen::Index b = 0; b <= h.mode(); ++b) CHECK(c[static_cast<std::size_t>(b)] == 0.0);
  for (std::size_t b = 1; b < c.size(); ++b) CHECK(c[b] >= c[b - 1]);
  // The lone outlier's bin is dense relative to its empty neighbours but cannot score lower than
  // the sparse bins before it.
  CHECK(h.contribution(40.0) >= h.contribution(20.0));
  CHECK(h.contribution(-5.0) == 0.0);        // better than anything seen: never penalised
  CHECK(h.contribution(1000.0) == h.cap());  // far beyond the range
}

TEST_CASE("Tail::Lower mirrors Tail::Upper", "[histogram]") {
  Vector x(5000);
  std::mt19937 rng(11);
  std::gamma_distribution<double> skewed(3.0, 1.0);
  for (auto& v : x) v = skewed(rng);
  hbos::FeatureSpec upper = plain(20);
  upper.tail = hbos::Tail::Upper;
  hbos::FeatureSpec lower = plain(20);
  lower.tail = hbos::Tail::Lower;
  const auto hu = fit(x, upper);
  const auto hl = fit(-x, lower);
  // The mirror image is exact only when the mode is unique (ties pick the first bin).
  const auto& counts = hu.counts();
  REQUIRE(std::count(counts.begin(), counts.end(),
                     *std::max_element(counts.begin(), counts.end())) == 1);
  for (double v : {-3.0, 0.3, 1.1, 2.0, 4.1, 7.7, 12.3, 100.0}) {
    CHECK(hl.contribution(-v) == Approx(hu.contribution(v)).margin(1e-12));
  }
}

TEST_CASE("a constant feature contributes 0 at its value and the cap elsewhere", "[histogram]") {
  const auto h = fit(Vector::Constant(8, 2.5), plain(10));
  CHECK(h.bins() == 1);
  CHECK(h.contribution(2.5) == 0.0);
  CHECK(h.cap() == Approx(std::log(8.0 / 0.5)));
  CHECK(h.contribution(2.6) == h.cap());
  CHECK(h.contribution(2.4) == h.cap());
}

TEST_CASE("fixed-width bins are anchored at the origin", "[histogram]") {
  // width 0.5 anchored at 0 over [0.1, 2.3]: bins [0, .5) ... [2, 2.5) -> 5 bins.
  hbos::FeatureSpec spec;
  spec.binning.method = hbos::BinningMethod::FixedWidth;
  spec.binning.width = 0.5;
  const auto h = fit(values({0.1, 0.2, 0.7, 1.2, 2.3}), spec);
  CHECK(h.bins() == 5);
  CHECK(h.lower() == 0.0);
  CHECK(h.upper() == 2.5);
  CHECK(h.counts() == std::vector<Eigen::Index>{2, 1, 1, 0, 1});
  // A gross value does not stretch the bins: the width stays 0.5.
  const auto stretched = fit(values({0.1, 0.2, 0.7, 1.2, 2.3, 300.0}), spec);
  CHECK(stretched.edges()[1] - stretched.edges()[0] == 0.5);
  CHECK(stretched.counts()[0] == 2);
  spec.binning.max_bins = 100;
  CHECK_THROWS_WITH(fit(values({0.1, 300.0}), spec), Catch::Contains("max_bins"));
}

TEST_CASE("equal-frequency bins hold about n/k values and never split a run of ties",
          "[histogram]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  Vector x(1000);
  for (auto& v : x) v = normal(rng);
  hbos::FeatureSpec spec = plain(10);
  spec.binning.method = hbos::BinningMethod::EqualFrequency;
  const auto h = fit(x, spec);
  REQUIRE(h.bins() == 10);
  for (auto c : h.counts()) CHECK(c == 100);

  // 600 copies of one value must stay in one bin even though n/k = 100.
  Vector tied(1000);
  for (Eigen::Index i = 0; i < 1000; ++i) tied(i) = i < 600 ? 1.0 : normal(rng) + 5.0;
  const auto ht = fit(tied, spec);
  CHECK(ht.counts()[static_cast<std::size_t>(ht.bin_of(1.0))] == 600);
  // Densities: the tied bin is the mode and contributes 0.
  CHECK(ht.contribution(1.0) == 0.0);
}

TEST_CASE("shifted histograms: golden smoothing with two shifts", "[histogram]") {
  // x = {0, 1, 1, 3} (range 3), 2 coarse bins x 2 shifts = 4 fine bins of width 0.75:
  // fine counts {1, 2, 0, 1}; mass_i = c_i + (c_{i-1} + c_{i+1}) / 2 = {2, 2.5, 1.5, 1}.
  // Contributions log(2.5 / mass_i) = {log 1.25, 0, log(5/3), log 2.5}.
  hbos::FeatureSpec spec = plain(2);
  spec.binning.shifts = 2;
  const auto h = fit(values({0, 1, 1, 3}), spec);
  REQUIRE(h.bins() == 4);
  CHECK(h.counts() == std::vector<Eigen::Index>{1, 2, 0, 1});
  CHECK(h.bin_contributions()[0] == Approx(std::log(1.25)));
  CHECK(h.bin_contributions()[1] == 0.0);
  CHECK(h.bin_contributions()[2] == Approx(std::log(5.0 / 3.0)));
  CHECK(h.bin_contributions()[3] == Approx(std::log(2.5)));
}

TEST_CASE("periodic features have no seam at +-pi", "[histogram][periodic]") {
  const double pi = 3.14159265358979323846;
  std::mt19937 rng(9);
  std::normal_distribution<double> spread(0.0, 0.2);
  // A cluster straddling the seam: half just below +pi, half just above -pi.
  Vector x(400);
  for (auto& v : x) v = std::remainder(pi + spread(rng), 2 * pi);
  hbos::FeatureSpec spec = hbos::angle_feature(16);
  const auto h = fit(x, spec);
  // Both sides of the seam are dense and score alike; the opposite side of the circle is sparse.
  CHECK(h.contribution(pi - 0.05) < 1.0);
  CHECK(h.contribution(-pi + 0.05) < 1.0);
  CHECK(h.contribution(0.0) > 3.0);
  // theta and theta + 2 pi k fall in the same bin.
  std::uniform_real_distribution<double> angle(-pi, pi);
  for (int i = 0; i < 200; ++i) {
    const double t = angle(rng);
    CHECK(h.contribution(t + 2 * pi) == h.contribution(t));
    CHECK(h.contribution(t - 4 * pi) == h.contribution(t));
  }
  // Rotating the data by whole bins rotates the histogram: the same contributions.
  Vector rotated = x;
  const double bin = 2 * pi / 16;
  for (auto& v : rotated) v = v + 5 * bin;
  const auto hr = fit(rotated, spec);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    CHECK(hr.contribution(rotated(i)) == Approx(h.contribution(x(i))).margin(1e-9));
  }
}

TEST_CASE("periodic shifted histograms smooth across the seam", "[histogram][periodic]") {
  const double pi = 3.14159265358979323846;
  // All mass in the last bin; with 2 shifts the first fine bin (its neighbour across the seam)
  // gets half of it and scores log 2, not as an empty bin.
  hbos::FeatureSpec spec = hbos::angle_feature(4);
  spec.binning.shifts = 2;
  const auto h = fit(values({pi - 0.1, pi - 0.1, pi - 0.2}), spec);
  REQUIRE(h.bins() == 8);
  CHECK(h.contribution(-pi + 0.1) == Approx(std::log(2.0)));
  CHECK(h.contribution(0.0) == h.cap());
}

TEST_CASE("column scoring equals contribution() value by value, in and out of range",
          "[histogram][property]") {
  // contributions_into scores whole blocks by table loads when every value lies in [lo, hi) and
  // falls back to contribution() otherwise; both must agree bit for bit wherever either applies.
  // Columns mix in-range values with lo, hi, their floating-point neighbours, values inside and
  // beyond the tolerance band, for every tail, with and without shifts and tolerance.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(3.0, 2.0);
  for (int trial = 0; trial < 24; ++trial) {
    Vector train(500);
    for (Eigen::Index i = 0; i < train.size(); ++i) train(i) = normal(rng);
    hbos::FeatureSpec spec = plain(3 + trial % 7);
    spec.binning.shifts = 1 + trial % 3;
    spec.tail = trial % 3 == 0   ? hbos::Tail::Both
                : trial % 3 == 1 ? hbos::Tail::Upper
                                 : hbos::Tail::Lower;
    hbos::ScoringOptions options;
    options.range_tolerance = trial % 2 == 0 ? 0.0 : 0.5;
    const auto h = fit(train, spec, options);
    const double lo = h.lower(), hi = h.upper(), w = hi - lo;
    const double specials[] = {lo,
                               hi,
                               std::nextafter(lo, -1e9),
                               std::nextafter(hi, 1e9),
                               std::nextafter(hi, -1e9),
                               lo - 0.01 * w,
                               hi + 0.01 * w,
                               lo - 5 * w,
                               hi + 5 * w};
    // Long enough for several blocks, mostly clean (the fast path) with specials sprinkled in
    // some blocks only.
    Vector x(3000);
    std::uniform_real_distribution<double> inside(lo, hi);
    for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = inside(rng);
    for (Eigen::Index i = 0; i < 9; ++i) x(700 + 37 * i) = specials[i];
    Vector out(x.size());
    h.contributions_into({x.data(), x.size(), 1}, out.data(), false);
    std::size_t mismatches = 0;
    for (Eigen::Index i = 0; i < x.size(); ++i)
      if (out(i) != h.contribution(x(i))) ++mismatches;
    INFO("trial " << trial);
    CHECK(mismatches == 0);
    // Accumulating adds exactly the same values.
    Vector acc = Vector::Constant(x.size(), 0.25);
    h.contributions_into({x.data(), x.size(), 1}, acc.data(), true);
    CHECK((acc.array() == out.array() + 0.25).all());
  }
}

TEST_CASE("column scoring names the first non-finite value, wherever its block is",
          "[histogram][errors]") {
  const auto h = fit(values({0, 1, 1, 2, 3}), plain(4));
  Vector x = Vector::Constant(1000, 1.5);
  x(613) = std::numeric_limits<double>::quiet_NaN();
  Vector out(x.size());
  CHECK_THROWS_WITH(h.contributions_into({x.data(), x.size(), 1}, out.data(), false, 4),
                    Catch::Contains("X(613, 4) is not finite"));
  x(613) = 1.5;
  x(999) = -std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(h.contributions_into({x.data(), x.size(), 1}, out.data(), false, 4),
                    Catch::Contains("X(999, 4) is not finite"));
}
