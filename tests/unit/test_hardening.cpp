// Regression tests of issue 11 (hardening): every parameter value the library accepts gives a
// result, and everything it cannot compute gives hbos::InvalidArgument naming the value. Each
// case below crashed, hung, invoked undefined behaviour or returned a silently wrong answer
// before the fix (the comment says which). docs/parameters.md documents the ranges checked here.

#include <hbos/hbos.hpp>
#include <hbos/pyod.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace {

using Catch::Contains;
using hbos::InvalidArgument;

hbos::HbosParams params_with(const hbos::FeatureSpec& spec) {
  hbos::HbosParams p;
  p.feature = spec;
  return p;
}

hbos::FeatureSpec equal_width(Eigen::Index bins, Eigen::Index shifts = 1) {
  hbos::FeatureSpec spec;
  spec.binning.bins = bins;
  spec.binning.shifts = shifts;
  return spec;
}

hbos::FeatureSpec fixed_width(double width, double origin = 0.0) {
  hbos::FeatureSpec spec;
  spec.binning.method = hbos::BinningMethod::FixedWidth;
  spec.binning.width = width;
  spec.binning.origin = origin;
  return spec;
}

/// `n` copies of `common` followed by one `rare`: the last row is the outlier.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> cluster_and_outlier(Scalar common, Scalar rare,
                                                             Eigen::Index n = 20) {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> x(n + 1);
  x.head(n).setConstant(common);
  x(n) = rare;
  return x;
}

/// Every bin index the histogram gives the values lies in [0, bins), every contribution is
/// finite and >= 0.
template <class Scalar>
void check_sane(const hbos::Histogram<Scalar>& h,
                const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const Eigen::Index b = h.bin_of(x(i));
    CHECK(b >= 0);
    CHECK(b < h.bins());
    const Scalar c = h.contribution(x(i));
    CHECK(std::isfinite(c));
    CHECK(c >= Scalar(0));
  }
  CHECK(std::isfinite(h.cap()));
}

template <class Scalar>
hbos::Histogram<Scalar> fit_histogram(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& x,
                                      const hbos::FeatureSpec& spec,
                                      const hbos::ScoringOptions& options = {}) {
  hbos::Histogram<Scalar> h;
  std::vector<Scalar> scratch;
  h.refit(x, spec, options, scratch);
  return h;
}

/// Index of the largest entry.
template <class Vector>
Eigen::Index argmax(const Vector& v) {
  Eigen::Index i = 0;
  v.maxCoeff(&i);
  return i;
}

}  // namespace

// ---- shifts x bins -----------------------------------------------------------------------------

TEST_CASE("hardening: shifts whose product with the bins overflows are rejected", "[hardening]") {
  // Was: 4 x 2^62 wrapped, the max_bins check passed, 0 bins, a fault in count().
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(50, 1);
  auto p = params_with(equal_width(4, Eigen::Index{1} << 62));
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x, p), Contains("shifts 4611686018427387904 exceeds"));
  Eigen::VectorXd scores(50);
  CHECK_THROWS_AS(hbos::Hbosd::fit_and_score(x, scores, p), InvalidArgument);
  p.feature.binning.shifts = 20000;  // legal alone, 4 x 20000 > max_bins
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x, p), Contains("exceed max_bins"));
}

TEST_CASE("hardening: fit_and_score with a spec list of the wrong size throws", "[hardening]") {
  // Was: the fast-path test read params.features[1] and [2] of a one-element vector.
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(30, 3);
  hbos::HbosParams p;
  p.features.resize(1);
  Eigen::VectorXd scores(30);
  CHECK_THROWS_WITH(hbos::Hbosd::fit_and_score(x, scores, p), Contains("has 1 specs"));
}

TEST_CASE("hardening: max_bins has an upper bound", "[hardening]") {
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(10, 1);
  auto p = params_with(equal_width(10));
  p.feature.binning.max_bins = hbos::kMaxBinsLimit + 1;
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x, p), Contains("max_bins must lie in [1, 16777216]"));
  p.feature.binning.max_bins = hbos::kMaxBinsLimit;
  CHECK_NOTHROW(hbos::Hbosd::fit(x, p));
}

// ---- fixed width far from the origin -----------------------------------------------------------

TEST_CASE("hardening: fixed-width bins where (v - origin) / width >= 2^53", "[hardening]") {
  // Was: floor(q) + 1 == floor(q) gave 0 bins and a fault (1e17 with width 0.01).
  const Eigen::VectorXd x = cluster_and_outlier(1e17, 1e17 + 64.0);
  const auto h = fit_histogram(x, fixed_width(0.01));
  REQUIRE(h.bins() >= 1);
  check_sane(h, x);
  CHECK(h.contribution(1e17 + 64.0) > h.contribution(1e17));
  // The constant column at 1e17 alone.
  const Eigen::VectorXd constant = Eigen::VectorXd::Constant(10, 1e17);
  const auto hc = fit_histogram(constant, fixed_width(0.01));
  check_sane(hc, constant);
  CHECK(hc.contribution(1e17) == 0.0);
}

TEST_CASE("hardening: a fixed-width origin out of reach of the data", "[hardening]") {
  // Was: (0 - 1e308) / 0.01 = -inf, "needs -nan bins".
  const Eigen::VectorXd x = cluster_and_outlier(0.0, 0.5);
  const auto h = fit_histogram(x, fixed_width(0.01, 1e308));
  check_sane(h, x);
  CHECK(h.contribution(0.5) > h.contribution(0.0));
}

// ---- tiny bin widths ---------------------------------------------------------------------------

TEST_CASE("hardening: an equal-width column of subnormal range", "[hardening]") {
  // Was: width 1e-308 / 25 is subnormal, 1 / width = inf, (x - lo) * inf = NaN, UB cast, fault.
  const Eigen::MatrixXd x = cluster_and_outlier(0.0, 1e-308);
  const auto model = hbos::Hbosd::fit(x);
  const Eigen::VectorXd scores = model.score(x);
  CHECK(scores.allFinite());
  CHECK(argmax(scores) == x.rows() - 1);
  CHECK(scores(x.rows() - 1) > scores(0));
  const Eigen::MatrixXd smallest = cluster_and_outlier(0.0, 4.9e-324);
  const Eigen::VectorXd s2 = hbos::Hbosd::fit(smallest).score(smallest);
  CHECK(s2.allFinite());
  CHECK(argmax(s2) == smallest.rows() - 1);
}

TEST_CASE("hardening: a float column of subnormal range", "[hardening]") {
  // Was: a bin width below FLT_MIN gave 1 / width = inf in float.
  const Eigen::MatrixXf x = cluster_and_outlier(0.0f, 1e-40f);
  const Eigen::VectorXf scores = hbos::Hbosf::fit(x).score(x);
  CHECK(scores.allFinite());
  CHECK(argmax(scores) == x.rows() - 1);
}

TEST_CASE("hardening: a float model rejects a fixed width below FLT_MIN", "[hardening]") {
  // Was: 1e-40 is legal as a double; as a float it is subnormal, 1 / width = inf, UB cast.
  const Eigen::MatrixXf x = cluster_and_outlier(0.0f, 1.0f);
  CHECK_THROWS_WITH(hbos::Hbosf::fit(x, params_with(fixed_width(1e-40))),
                    Contains("below the smallest normal float"));
  // The same spec through a bare Histogram (the screen's path) is refused the same way.
  hbos::Histogram<float> h;
  std::vector<float> scratch;
  CHECK_THROWS_AS(h.refit(Eigen::VectorXf(x.col(0)), fixed_width(1e-40), {}, scratch),
                  InvalidArgument);
  // A double model accepts it (and bins the range [0, 1] into too many bins: max_bins).
  CHECK_THROWS_WITH(hbos::Hbosd::fit(x.cast<double>().eval(), params_with(fixed_width(1e-40))),
                    Contains("more than max_bins"));
}

// ---- periodic features -------------------------------------------------------------------------

TEST_CASE("hardening: periodic values far from period_start stay inside the period",
          "[hardening]") {
  // Was: t - period * floor(t / period) returned offsets outside [0, period): bin -20, an
  // out-of-bounds write.
  const hbos::FeatureSpec spec = hbos::angle_feature(16);
  Eigen::VectorXd x(40);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = 6e16 + 8.0 * static_cast<double>(i);
  const auto h = fit_histogram(x, spec);
  check_sane(h, x);
  Eigen::Index total = 0;
  for (const Eigen::Index c : h.counts()) total += c;
  CHECK(total == x.size());
}

TEST_CASE("hardening: a period_start far from the data still separates the values", "[hardening]") {
  // Was: x - 1e300 rounds to -1e300 for every x: every row scored the same.
  hbos::FeatureSpec spec = hbos::angle_feature(8);
  spec.period_start = 1e300;
  Eigen::MatrixXd x = cluster_and_outlier(0.1, 3.0);
  for (Eigen::Index i = 0; i < 20; ++i) x(i) = 0.1 + 0.001 * static_cast<double>(i);
  const Eigen::VectorXd scores = hbos::Hbosd::fit(x, params_with(spec)).score(x);
  CHECK(scores.allFinite());
  CHECK(argmax(scores) == x.rows() - 1);
  CHECK(scores(x.rows() - 1) > scores(0));
}

TEST_CASE("hardening: a float model rejects a period beyond FLT_MAX", "[hardening]") {
  hbos::FeatureSpec spec = hbos::angle_feature(8);
  spec.period = 1e39;
  const Eigen::MatrixXf x = cluster_and_outlier(0.0f, 1.0f);
  CHECK_THROWS_WITH(hbos::Hbosf::fit(x, params_with(spec)),
                    Contains("period 1e+39 exceeds the largest float"));
  spec = hbos::angle_feature(8);
  spec.period_start = -1e39;
  CHECK_THROWS_WITH(hbos::Hbosf::fit(x, params_with(spec)), Contains("period_start -1e+39"));
}

// ---- empty_bin_count ---------------------------------------------------------------------------

TEST_CASE("hardening: a tiny empty_bin_count keeps the cap finite", "[hardening]") {
  // Was: h_max * w_max / 1e-308 = inf: unseen values scored inf and the workspace threw on its
  // own training data.
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(200, 2);
  hbos::HbosParams p;
  p.scoring.empty_bin_count = 1e-308;
  const auto model = hbos::Hbosd::fit(x, p);
  CHECK(std::isfinite(model.histogram(0).cap()));
  Eigen::MatrixXd far(1, 2);
  far << 100.0, 100.0;
  CHECK(model.score(far).allFinite());
  hbos::Workspace<double> ws(p);
  CHECK_NOTHROW(ws.run(x));
  CHECK(ws.scores().allFinite());
  // A constant feature's cap log(n / empty_bin_count) too.
  const Eigen::MatrixXd constant = Eigen::MatrixXd::Constant(50, 1, 3.0);
  p.scoring.empty_bin_count = 5e-324;
  CHECK(std::isfinite(hbos::Hbosd::fit(constant, p).histogram(0).cap()));
}

// ---- ranges that overflow a double -------------------------------------------------------------

TEST_CASE("hardening: a column spanning -1e308 to 1e308 is binned in scaled form", "[hardening]") {
  // Was: hi - lo = inf, every value in bin 0: exit 0 and the extremes were not the top scores.
  Eigen::MatrixXd x(42, 1);
  for (Eigen::Index i = 0; i < 40; ++i) x(i) = static_cast<double>(i % 7) - 3.0;
  x(40) = -1e308;
  x(41) = 1e308;
  for (const auto& spec : {hbos::default_feature(), equal_width(10)}) {
    const auto model = hbos::Hbosd::fit(x, params_with(spec));
    const Eigen::VectorXd scores = model.score(x);
    REQUIRE(scores.allFinite());
    const double inner = scores.head(40).maxCoeff();
    CHECK(scores(40) > inner);
    CHECK(scores(41) > inner);
    Eigen::VectorXd training(42);
    (void)hbos::Hbosd::fit_and_score(x, training, params_with(spec));
    CHECK(training == scores);
  }
  // Float: -3e38 to 3e38 overflows a float the same way.
  const Eigen::MatrixXf xf = x.cast<float>().cwiseMax(-3e38f).cwiseMin(3e38f);
  const Eigen::VectorXf sf = hbos::Hbosf::fit(xf).score(xf);
  REQUIRE(sf.allFinite());
  CHECK(sf(40) > sf.head(40).maxCoeff());
  CHECK(sf(41) > sf.head(40).maxCoeff());
}

TEST_CASE("hardening: the bin-count rules on extreme ranges", "[hardening]") {
  // Was: Scott's mean of 1e308s overflowed to inf (one bin), Birgé–Rozenblac's 1 / (hi - lo) was 0
  // or inf and its cell index a UB cast.
  Eigen::MatrixXd x(60, 1);
  for (Eigen::Index i = 0; i < 60; ++i) x(i) = 1e307 * static_cast<double>(i % 10) - 4e307;
  x(59) = 1.7e308;
  x(58) = -1.7e308;
  Eigen::MatrixXd tiny = x * 1e-308 * 1e-307;  // a subnormal range
  for (const auto rule :
       {hbos::BinCountRule::Sqrt, hbos::BinCountRule::Sturges, hbos::BinCountRule::Scott,
        hbos::BinCountRule::FreedmanDiaconis, hbos::BinCountRule::BirgeRozenblac}) {
    for (const auto method :
         {hbos::BinningMethod::EqualWidth, hbos::BinningMethod::EqualFrequency}) {
      hbos::FeatureSpec spec;
      spec.binning.rule = rule;
      spec.binning.method = method;
      for (const Eigen::MatrixXd* data : {&x, &tiny}) {
        const auto model = hbos::Hbosd::fit(*data, params_with(spec));
        const Eigen::VectorXd scores = model.score(*data);
        CHECK(scores.allFinite());
        CHECK(model.histogram(0).bins() >= 1);
      }
    }
  }
  // Scott's rule gives the same bin count whatever power-of-two scale the data has.
  hbos::FeatureSpec scott;
  scott.binning.rule = hbos::BinCountRule::Scott;
  const Eigen::MatrixXd ordinary = x * 1e-307;
  CHECK(hbos::Hbosd::fit(x, params_with(scott)).histogram(0).bins() ==
        hbos::Hbosd::fit(ordinary, params_with(scott)).histogram(0).bins());
}

TEST_CASE("hardening: equal-frequency bins between adjacent doubles have positive width",
          "[hardening]") {
  // Was: midpoints of adjacent doubles round onto a neighbour, giving zero-width bins and
  // NaN or infinite heights; the midpoint of -1e308 and 1e308 overflowed to inf.
  Eigen::VectorXd x(64);
  double v = 1.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    x(i) = v;
    v = std::nextafter(v, 2.0);
  }
  hbos::FeatureSpec spec;
  spec.binning.method = hbos::BinningMethod::EqualFrequency;
  spec.binning.bins = 32;
  const auto h = fit_histogram(x, spec);
  for (std::size_t k = 0; k + 1 < h.edges().size(); ++k) CHECK(h.edges()[k] < h.edges()[k + 1]);
  check_sane(h, x);
  const Eigen::VectorXd wide = cluster_and_outlier(-1e308, 1e308);
  const auto hw = fit_histogram(wide, spec);
  for (std::size_t k = 0; k + 1 < hw.edges().size(); ++k) CHECK(hw.edges()[k] < hw.edges()[k + 1]);
  check_sane(hw, wide);
}

// ---- averaged shifted histograms ---------------------------------------------------------------

TEST_CASE("hardening: many shifts cost linear time and give the triangular masses", "[hardening]") {
  // Was: O(bins x shifts^2): 5 bins x 13107 shifts ran for minutes.
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(2000, 1);
  const auto start = std::chrono::steady_clock::now();
  const auto model = hbos::Hbosd::fit(x, params_with(equal_width(5, 13107)));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(seconds < 5.0);  // linear: milliseconds (sanitised builds included)
  CHECK(model.score(x).allFinite());

  // The prefix-sum masses equal the definition m_i = sum_{|d|<m} (1 - |d|/m) c_{i+d}; both
  // periodic (wrapping) and not. 4 x 600 = 2400 fine bins x 600 shifts > 2^20 takes that path.
  for (const bool periodic : {false, true}) {
    hbos::FeatureSpec spec = equal_width(4, 600);
    if (periodic) {
      spec.periodic = true;
      spec.period_start = -1.0;
      spec.period = 2.0;
    }
    const auto h = fit_histogram(Eigen::VectorXd(x.col(0)), spec);
    const auto k = static_cast<std::ptrdiff_t>(h.bins());
    const std::ptrdiff_t m = 600;
    std::vector<double> mass(static_cast<std::size_t>(k), 0.0);
    double h_max = 0.0;
    for (std::ptrdiff_t i = 0; i < k; ++i) {
      for (std::ptrdiff_t d = 1 - m; d < m; ++d) {
        std::ptrdiff_t j = i + d;
        if (periodic) j = ((j % k) + k) % k;
        if (j < 0 || j >= k) continue;
        mass[static_cast<std::size_t>(i)] +=
            (1.0 - static_cast<double>(std::abs(d)) / static_cast<double>(m)) *
            static_cast<double>(h.counts()[static_cast<std::size_t>(j)]);
      }
      h_max = std::max(h_max, mass[static_cast<std::size_t>(i)]);
    }
    for (std::ptrdiff_t i = 0; i < k; i += 37) {
      const double mi = mass[static_cast<std::size_t>(i)];
      const double expected = std::max(0.0, std::log(h_max / (mi > 0.0 ? mi : 0.5)));
      CHECK(h.bin_contributions()[static_cast<std::size_t>(i)] == Approx(expected).margin(1e-9));
    }
  }
}

// ---- thresholds --------------------------------------------------------------------------------

TEST_CASE("hardening: thresholds of extreme score vectors are finite", "[hardening]") {
  // Was: max - min = inf gave an infinite adaptive threshold (every score an inlier); a
  // threshold beyond FLT_MAX converted to float was undefined behaviour.
  Eigen::VectorXd s(3);
  s << -1e308, 0.0, 1e308;
  std::vector<double> scratch;
  const double t = hbos::compute_threshold(s, hbos::AdaptiveRange{0.7}, scratch);
  CHECK(std::isfinite(t));
  CHECK(t == Approx(0.4e308));
  CHECK(std::isfinite(hbos::compute_threshold(s, hbos::MedianMad{3.0}, scratch)));
  Eigen::VectorXd two(2);
  two << -1e308, 1e308;
  // The median of -1e308 and 1e308 is 0 (numpy's lerp overflowed to inf), the MAD 1e308.
  CHECK(hbos::compute_threshold(two, hbos::MedianMad{1.0, false}, scratch) == 1e308);
  CHECK(hbos::compute_threshold(two, hbos::MedianMad{10.0, false}, scratch) ==
        std::numeric_limits<double>::max());
  Eigen::VectorXf f(3);
  f << 0.0f, 1.0f, 2.0f;
  std::vector<float> fscratch;
  CHECK(hbos::compute_threshold(f, hbos::FixedThreshold{1e300}, fscratch) ==
        std::numeric_limits<float>::max());
  CHECK(hbos::compute_threshold(f, hbos::MedianMad{1e300}, fscratch) ==
        std::numeric_limits<float>::max());
  CHECK(hbos::threshold_scores(f, hbos::FixedThreshold{1e300}).n_inliers == 3);
  // Found by fuzz_library: k * 1.4826 overflows to inf, and inf * (MAD = 0) was NaN.
  Eigen::VectorXf ties = Eigen::VectorXf::Constant(5, 2.0f);
  CHECK(hbos::compute_threshold(ties, hbos::MedianMad{1.7e308}, fscratch) == 2.0f);
}

// ---- shapes ------------------------------------------------------------------------------------

TEST_CASE("hardening: negative shapes are rejected", "[hardening]") {
  const double data[4] = {1, 2, 3, 4};
  CHECK_THROWS_WITH(hbos::Hbosd::fit_row_major(data, -2, -2), Contains("non-negative"));
  hbos::Workspace<double> ws;
  CHECK_THROWS_AS(ws.reserve(-1, 2), InvalidArgument);
  hbos::Histogram<double> h;
  CHECK_THROWS_AS(h.reserve(-5), InvalidArgument);
}

// ---- PyOD mode ---------------------------------------------------------------------------------

TEST_CASE("hardening: PyOD auto bins on a range that overflows a double", "[hardening][pyod]") {
  // Was: the auto search bucketed an infinite range: a negative cell count, std::length_error.
  Eigen::MatrixXd x = Eigen::MatrixXd::Random(30, 1);
  x(0) = -1e308;
  x(1) = 1e308;
  hbos::PyodParams p;
  p.auto_bins = true;
  CHECK_THROWS_WITH(hbos::PyodHbosd::fit(x, p), Contains("overflows a double"));
  p.auto_bins = false;
  CHECK_THROWS_WITH(hbos::PyodHbosd::fit(x, p), Contains("overflows a double"));
}

TEST_CASE("hardening: PyOD n_bins has an upper bound", "[hardening][pyod]") {
  // Was: 2^32 bins allocated 34 GB.
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(30, 1);
  hbos::PyodParams p;
  p.n_bins = Eigen::Index{1} << 32;
  CHECK_THROWS_WITH(hbos::PyodHbosd::fit(x, p), Contains("n_bins must be <= 16777216"));
  p.n_bins = hbos::kMaxPyodBins + 1;
  CHECK_THROWS_AS(hbos::PyodHbosd::fit(x, p), InvalidArgument);
  p.n_bins = 3;  // the lower edge, as PyOD
  CHECK_NOTHROW(hbos::PyodHbosd::fit(x, p));
  p.n_bins = 2;
  CHECK_THROWS_AS(hbos::PyodHbosd::fit(x, p), InvalidArgument);
}

TEST_CASE("hardening: PyOD mode on a subnormal range throws instead of scoring -inf",
          "[hardening][pyod]") {
  // Was: count / (subnormal width) = inf density, log2(inf) and a score of -inf.
  const Eigen::MatrixXd x = cluster_and_outlier(0.0, 1e-310);
  CHECK_THROWS_WITH(hbos::PyodHbosd::fit(x), Contains("overflows a double (PyOD would score"));
  // Small but normal widths still work and are finite.
  const Eigen::MatrixXd small = cluster_and_outlier(0.0, 1e-300);
  CHECK(hbos::PyodHbosd::fit(small).decision_scores().allFinite());
}
