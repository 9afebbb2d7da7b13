/// \file
/// The `Contamination` threshold alone: numpy's percentile of a score vector, as
/// `hbos::compute_threshold` takes it (the selection in hbos/detail/numpy.hpp), next to the
/// std::nth_element selection it replaced, in the same run. Results: docs/benchmarks.md.
///
/// - `threshold/<algo>/<data>/<scalar>/<n>`, algo in
///     compute   hbos::compute_threshold(scores, Contamination{0.1}, scratch): the library
///     nth_element  the previous code: the finiteness check, a copy of the scores,
///               std::nth_element, std::min_element, the lerp
///   data in
///     hbos      the default model's training scores of n x 2 N(0, 1) rows (few distinct
///               values, heavy ties: what HBOS().fit thresholds)
///     normal    n N(0, 1) values (continuous)
/// - `crossover/<algo>/<data>/<scalar>/<n>`: the selection itself at sizes around the
///   crossover, algo `radix` (forced, whatever the size) or `nth_element`.
///
/// Data from std::mt19937_64 seeded with 20240611; scratch grown before timing (no allocation).
///
///     bench_threshold --benchmark_min_time=0.01

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "hbos/detail/numpy.hpp"
#include "hbos/model.hpp"
#include "hbos/threshold.hpp"

namespace {

using Index = Eigen::Index;

template <class Scalar>
using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

template <class Scalar>
Vector<Scalar> scores_of(const std::string& data, Index n) {
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> normal;
  if (data == "normal") {
    Vector<Scalar> v(n);
    for (Index i = 0; i < n; ++i) v[i] = static_cast<Scalar>(normal(rng));
    return v;
  }
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> x(n, 2);
  for (Index i = 0; i < x.size(); ++i) x.data()[i] = static_cast<Scalar>(normal(rng));
  Vector<Scalar> scores(n);
  const auto model = hbos::Hbos<Scalar>::fit_and_score(x, scores, hbos::HbosParams{});
  benchmark::DoNotOptimize(&model);
  return scores;
}

/// The selection before the radix select: a copy, std::nth_element, std::min_element, the lerp.
template <class Scalar>
Scalar by_nth_element(const Vector<Scalar>& scores, double q, std::vector<Scalar>& scratch) {
  const auto n = static_cast<std::size_t>(scores.size());
  scratch.assign(scores.data(), scores.data() + n);
  const double v = static_cast<double>(n - 1) * q;
  const auto i = static_cast<std::size_t>(std::floor(v));
  if (i + 1 >= n) return *std::max_element(scratch.begin(), scratch.end());
  const auto k = static_cast<std::ptrdiff_t>(i);
  std::nth_element(scratch.begin(), scratch.begin() + k, scratch.end());
  const Scalar lo = scratch[i];
  const Scalar hi = *std::min_element(scratch.begin() + k + 1, scratch.end());
  return static_cast<Scalar>(hbos::detail::numpy_lerp(
      static_cast<double>(lo), static_cast<double>(hi), v - static_cast<double>(i)));
}

const double kQ = (100.0 * (1.0 - 0.1)) / 100.0;  // Contamination{0.1}, as compute_threshold

template <class Scalar>
void bm_threshold(benchmark::State& state, const std::string& algo, const std::string& data,
                  Index n) {
  const Vector<Scalar> scores = scores_of<Scalar>(data, n);
  std::vector<Scalar> scratch(static_cast<std::size_t>(2 * n));
  const hbos::ThresholdRule rule = hbos::Contamination{0.1};
  for (auto _ : state) {
    // The baseline also pays compute_threshold's checks (finite scores), as it did.
    const Scalar t = algo == "compute" ? hbos::compute_threshold(scores, rule, scratch)
                                       : (hbos::detail::require_finite_scores(scores),
                                          by_nth_element(scores, kQ, scratch));
    benchmark::DoNotOptimize(t);
  }
  state.SetItemsProcessed(state.iterations() * n);
}

template <class Scalar>
void bm_crossover(benchmark::State& state, const std::string& algo, const std::string& data,
                  Index n) {
  const Vector<Scalar> scores = scores_of<Scalar>(data, n);
  std::vector<Scalar> scratch(static_cast<std::size_t>(n));
  const auto m = static_cast<std::size_t>(n);
  const auto k = static_cast<std::size_t>(std::floor(static_cast<double>(m - 1) * kQ));
  for (auto _ : state) {
    if (algo == "radix") {
      const auto r = hbos::detail::radix_select_adjacent(scores.data(), m, k, scratch.data(), m, 0);
      benchmark::DoNotOptimize(r);
    } else {
      benchmark::DoNotOptimize(by_nth_element(scores, kQ, scratch));
    }
  }
  state.SetItemsProcessed(state.iterations() * n);
}

template <class Scalar>
const char* scalar_name() {
  return sizeof(Scalar) == 8 ? "double" : "float";
}

template <class Scalar>
void register_all() {
  for (const std::string data : {"hbos", "normal"}) {
    for (const Index n : {Index{1000}, Index{10000}, Index{100000}, Index{1000000}}) {
      for (const std::string algo : {"compute", "nth_element"}) {
        const std::string name = "threshold/" + algo + "/" + data + "/" + scalar_name<Scalar>() +
                                 "/" + std::to_string(n);
        benchmark::RegisterBenchmark(name.c_str(), [algo, data, n](benchmark::State& state) {
          bm_threshold<Scalar>(state, algo, data, n);
        })->Unit(benchmark::kMicrosecond);
      }
    }
    for (const Index n :
         {Index{2048}, Index{4096}, Index{8192}, Index{16384}, Index{32768}, Index{65536}}) {
      for (const std::string algo : {"radix", "nth_element"}) {
        const std::string name = "crossover/" + algo + "/" + data + "/" + scalar_name<Scalar>() +
                                 "/" + std::to_string(n);
        benchmark::RegisterBenchmark(name.c_str(), [algo, data, n](benchmark::State& state) {
          bm_crossover<Scalar>(state, algo, data, n);
        })->Unit(benchmark::kMicrosecond);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all<double>();
  register_all<float>();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
