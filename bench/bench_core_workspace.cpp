/// \file
/// The SLAM hot path: one frame of 1000 matches x 2 features through `hbos::Workspace::run`
/// (fit + score + AdaptiveRange{0.7} threshold + inlier mask), in the steady state after a
/// warm-up frame, so no iteration allocates. Results: docs/benchmarks.md.
///
/// Benchmarks (time per iteration = time per frame; items = n * d per frame):
/// - `frame/workspace/<spec>/<data>/<scalar>/1000/2` with spec in
///     static10   EqualWidth, 10 bins, 1 shift
///     default    hbos::default_feature() (EqualWidth, 5 bins x 5 shifts)
///     fixed0.5   FixedWidth, width 0.5 px, origin 0 (bin edges anchored in pixel units)
///   and data in
///     normal     N(0, 1) in both columns
///     residual   reprojection-residual-like (du, dv) [px]: 80 % N(0, 1 px) per component,
///                20 % uniform in [-20, 20] px (gross mismatches); FixedWidth 0.5 px then has about
///                80 bins
/// - `frame/model_alloc/static10/normal/<scalar>/1000/2`: the same job through the allocating
///   one-call API (`Hbos::fit`, `Hbos::score`, `threshold_scores`), for comparison.
///
/// Each benchmark cycles through 16 frames drawn with different seeds, so branch predictors
/// cannot learn one frame. Data: std::mt19937_64 seeded with 20240611 + frame index.
///
///     bench_core_workspace --benchmark_min_time=0.2 --benchmark_repetitions=5
///         --benchmark_report_aggregates_only=true   (one line)

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/model.hpp"
#include "hbos/threshold.hpp"
#include "hbos/workspace.hpp"

#include "bench_specs.hpp"

namespace {

using Index = Eigen::Index;

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

constexpr int kFrames = 16;
constexpr Index kRows = 1000;  // matches per frame
constexpr Index kCols = 2;     // features per match

enum class Data { Normal, Residual };
enum class Spec { Static10, Default, Fixed05 };

template <class Scalar>
std::vector<Matrix<Scalar>> make_frames(Data data, Index n, Index d) {
  std::vector<Matrix<Scalar>> frames;
  for (int f = 0; f < kFrames; ++f) {
    std::mt19937_64 rng(20240611u + static_cast<std::uint64_t>(f));
    std::normal_distribution<double> normal(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(-20.0, 20.0);
    std::bernoulli_distribution gross(0.2);
    Matrix<Scalar> x(n, d);
    for (Index i = 0; i < n; ++i) {
      const bool outlier = data == Data::Residual && gross(rng);
      for (Index j = 0; j < d; ++j)
        x(i, j) = static_cast<Scalar>(outlier ? uniform(rng) : normal(rng));
    }
    frames.push_back(std::move(x));
  }
  return frames;
}

hbos::HbosParams params_of(Spec spec) {
  switch (spec) {
    case Spec::Static10:
      return hbos_bench::static_bins(10);
    case Spec::Default:
      return hbos::HbosParams{};  // hbos::default_feature() for every feature
    case Spec::Fixed05:
      return hbos_bench::fixed_width_bins(0.5);  // [px]
  }
  return {};
}

template <class Scalar>
void bm_workspace(benchmark::State& state, Spec spec, Data data, Index n, Index d) {
  const std::vector<Matrix<Scalar>> frames = make_frames<Scalar>(data, n, d);
  hbos::Workspace<Scalar> workspace(params_of(spec), hbos::AdaptiveRange{0.7});
  for (const auto& frame : frames) workspace.run(frame);  // warm-up: buffers reach their size
  std::size_t f = 0;
  Index outliers = 0;
  for (auto _ : state) {
    const hbos::FrameSummary<Scalar> summary = workspace.run(frames[f]);
    outliers += summary.n_outliers();
    benchmark::DoNotOptimize(summary);
    f = (f + 1) % frames.size();
  }
  benchmark::DoNotOptimize(outliers);
  state.SetItemsProcessed(state.iterations() * n * d);
}

template <class Scalar>
void bm_model_alloc(benchmark::State& state, Spec spec, Data data, Index n, Index d) {
  const std::vector<Matrix<Scalar>> frames = make_frames<Scalar>(data, n, d);
  const hbos::HbosParams params = params_of(spec);
  const hbos::ThresholdRule rule = hbos::AdaptiveRange{0.7};
  std::size_t f = 0;
  for (auto _ : state) {
    const auto model = hbos::Hbos<Scalar>::fit(frames[f], params);
    const auto scores = model.score(frames[f]);
    const auto result = hbos::threshold_scores(scores, rule);
    benchmark::DoNotOptimize(result.n_inliers);
    f = (f + 1) % frames.size();
  }
  state.SetItemsProcessed(state.iterations() * n * d);
}

const char* name_of(Spec spec) {
  switch (spec) {
    case Spec::Static10:
      return "static10";
    case Spec::Default:
      return "default";
    case Spec::Fixed05:
      return "fixed0.5";
  }
  return "?";
}

const char* name_of(Data data) { return data == Data::Normal ? "normal" : "residual"; }

template <class Scalar>
std::string case_name(const char* prefix, Spec spec, Data data, Index n, Index d) {
  return std::string(prefix) + "/" + name_of(spec) + "/" + name_of(data) + "/" +
         (sizeof(Scalar) == sizeof(float) ? "float" : "double") + "/" + std::to_string(n) + "/" +
         std::to_string(d);
}

template <class Scalar>
void register_all() {
  const struct {
    Spec spec;
    Data data;
  } cases[] = {{Spec::Static10, Data::Normal},
               {Spec::Default, Data::Normal},
               {Spec::Static10, Data::Residual},
               {Spec::Default, Data::Residual},
               {Spec::Fixed05, Data::Residual}};
  for (const auto& c : cases) {
    const Spec spec = c.spec;
    const Data data = c.data;
    benchmark::RegisterBenchmark(
        case_name<Scalar>("frame/workspace", spec, data, kRows, kCols).c_str(),
        [spec, data](benchmark::State& state) {
          bm_workspace<Scalar>(state, spec, data, kRows, kCols);
        })
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark(
      case_name<Scalar>("frame/model_alloc", Spec::Static10, Data::Normal, kRows, kCols).c_str(),
      [](benchmark::State& state) {
        bm_model_alloc<Scalar>(state, Spec::Static10, Data::Normal, kRows, kCols);
      })
      ->Unit(benchmark::kMicrosecond);
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
