// libFuzzer target: the library API (hbos/hbos.hpp and hbos/pyod.hpp) on a fuzzed matrix (NaN,
// +-inf, subnormals, huge values, constant columns) with fuzzed parameters for every binning
// method, bin-count rule, tail, periodic spec, threshold rule, API level and the PyOD mode.
//
// The promise checked: every call returns a result or throws hbos::InvalidArgument (anything
// else escapes and libFuzzer reports it, as it reports every ASan/UBSan finding), and a fit on
// finite data that succeeds scores finitely, bit for bit the same through every path.

#include <hbos/hbos.hpp>
#include <hbos/pyod.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using hbos::fuzz::FuzzInput;

/// Large legal sizes would only make the fuzzer slow, not find more: cap them (values beyond
/// the legal range are kept, so the validation is still exercised).
Eigen::Index capped(long long v, Eigen::Index legal_limit) {
  if (v > 4096 && v <= legal_limit) return 4096;
  return static_cast<Eigen::Index>(v);
}

hbos::FeatureSpec fuzz_spec(FuzzInput& in) {
  hbos::FeatureSpec spec;
  hbos::Binning& b = spec.binning;
  b.method = static_cast<hbos::BinningMethod>(in.byte() % 3);
  b.rule = static_cast<hbos::BinCountRule>(in.byte() % 6);
  b.bins = static_cast<Eigen::Index>(in.count(10));
  b.shifts = in.flag() ? 1 : static_cast<Eigen::Index>(in.count(5));
  b.max_bins = in.flag() ? 65536 : capped(in.count(64), hbos::kMaxBinsLimit);
  if (b.max_bins > 4096) b.max_bins = 4096;
  b.width = in.parameter(0.25);
  b.origin = in.flag() ? 0.0 : in.parameter(1.0);
  spec.tail = static_cast<hbos::Tail>(in.byte() % 3);
  spec.periodic = (in.byte() % 4) == 0;
  if (spec.periodic) {
    spec.period_start = in.flag() ? -3.14159265358979 : in.parameter(-3.0);
    spec.period = in.flag() ? 6.28318530717959 : in.parameter(6.0);
  }
  return spec;
}

hbos::ThresholdRule fuzz_rule(FuzzInput& in) {
  switch (in.byte() % 4) {
    case 0:
      return hbos::AdaptiveRange{in.parameter(0.7)};
    case 1:
      return hbos::Contamination{in.parameter(0.1)};
    case 2:
      return hbos::MedianMad{in.parameter(3.0), in.flag()};
    default:
      return hbos::FixedThreshold{in.parameter(1.5)};
  }
}

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
template <class Scalar>
using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

template <class Scalar>
Matrix<Scalar> fuzz_matrix(FuzzInput& in) {
  const auto n = static_cast<Eigen::Index>(1 + in.below(48));
  const auto d = static_cast<Eigen::Index>(1 + in.below(3));
  Matrix<Scalar> x(n, d);
  for (Eigen::Index j = 0; j < d; ++j) {
    const std::uint8_t style = in.byte() % 4;
    const double base = in.value();
    for (Eigen::Index i = 0; i < n; ++i) {
      double v = base;  // style 0: a constant column
      if (style == 1) v = in.value();
      if (style == 2) v = base + static_cast<double>(in.byte() % 8);  // ties near one value
      if (style == 3) v = base * std::ldexp(1.0, static_cast<int>(in.byte() % 16) - 8);
      // Values beyond Scalar's range become +-inf (a conversion there would itself be UB).
      x(i, j) = hbos::detail::saturate_cast<Scalar>(v) == v || std::isnan(v)
                    ? static_cast<Scalar>(v)
                    : (v > 0 ? std::numeric_limits<Scalar>::infinity()
                             : -std::numeric_limits<Scalar>::infinity());
    }
  }
  return x;
}

template <class Scalar>
void run_core(FuzzInput& in) {
  const Matrix<Scalar> x = fuzz_matrix<Scalar>(in);
  hbos::HbosParams params;
  params.feature = fuzz_spec(in);
  if (in.flag()) {
    // Per-feature specs, sometimes of the wrong count.
    const std::size_t count = static_cast<std::size_t>(x.cols()) + (in.byte() % 8 == 0 ? 1 : 0);
    for (std::size_t j = 0; j < count; ++j) params.features.push_back(fuzz_spec(in));
  }
  params.scoring.empty_bin_count = in.flag() ? 0.5 : in.parameter(0.5);
  params.scoring.range_tolerance = in.flag() ? 0.5 : in.parameter(0.5);
  const hbos::ThresholdRule rule = fuzz_rule(in);
  const bool finite = x.allFinite();
  const std::uint8_t api = in.byte() % 4;
  try {
    const auto model = hbos::Hbos<Scalar>::fit(x, params);
    check(finite);  // non-finite data must be rejected
    const Vector<Scalar> scores = model.score(x);
    check(scores.allFinite());
    check((scores.array() >= Scalar(0)).all());
    if (api == 0) {
      Vector<Scalar> training(x.rows());
      (void)hbos::Hbos<Scalar>::fit_and_score(x, training, params);
      check(training == scores);  // documented: bit for bit model.score(x)
    } else if (api == 1) {
      const Matrix<Scalar> c = model.contributions(x);
      check(c.allFinite());
    } else if (api == 2) {
      hbos::Workspace<Scalar> ws(params, rule);
      const auto summary = ws.run(x);
      check(ws.scores().allFinite());
      check(std::isfinite(summary.threshold));
      check(summary.n_inliers >= 0 && summary.n_inliers <= x.rows());
    } else {
      const auto t = hbos::threshold_scores(scores, rule);
      check(std::isfinite(t.threshold));
      // Scores of new data: the matrix shifted and scaled, still finite.
      const Matrix<Scalar> shifted = (x.array() * Scalar(3) + Scalar(1)).matrix();
      if (shifted.allFinite()) check(model.score(shifted).allFinite());
    }
  } catch (const hbos::InvalidArgument&) {
  }
}

template <class Scalar>
void run_pyod(FuzzInput& in) {
  const Matrix<Scalar> x = fuzz_matrix<Scalar>(in);
  hbos::PyodParams p;
  p.n_bins = capped(in.count(10), hbos::kMaxPyodBins);
  p.auto_bins = in.flag();
  p.alpha = in.flag() ? 0.1 : in.parameter(0.1);
  p.tol = in.flag() ? 0.5 : in.parameter(0.5);
  p.contamination = in.flag() ? 0.1 : in.parameter(0.1);
  const bool finite = x.allFinite();
  try {
    const auto model = hbos::PyodHbos<Scalar>::fit(x, p);
    check(finite);
    check(model.decision_scores().allFinite());
    check(std::isfinite(model.threshold()));
    const Vector<Scalar> again = model.decision_function(x);
    check(again == model.decision_scores());
    const Matrix<Scalar> shifted = (x.array() * Scalar(2) - Scalar(1)).matrix();
    if (shifted.allFinite()) check(model.decision_function(shifted).allFinite());
  } catch (const hbos::InvalidArgument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  switch (in.byte() % 4) {
    case 0:
      run_core<double>(in);
      break;
    case 1:
      run_core<float>(in);
      break;
    case 2:
      run_pyod<double>(in);
      break;
    default:
      run_pyod<float>(in);
      break;
  }
  return 0;
}
