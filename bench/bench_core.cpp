/// \file
/// Core throughput of `hbos::Hbos` on standard normal data, with a memory-bound baseline measured
/// in the same run. Results and the ratios drawn from them: docs/benchmarks.md.
///
/// Benchmarks (items = matrix entries, n * d per iteration, so items/s compare across rows):
/// - `stream/sum/<scalar>/<n>/<d>`: one pass summing every entry of the matrix (the floor:
///   any fit must read the data at least once).
/// - `core/<op>/<spec>/<scalar>/<n>/<d>`, op in
///     fit        `Hbos::fit`
///     score      `Hbos::score_into` a preallocated vector (model fitted outside the loop)
///     fitscore   fit, then score_into the same rows (two independent calls)
///     fit_and_score  `Hbos::fit_and_score`: fit and the training rows' scores in one sweep,
///                  each value scored from the bin it was counted in (PyOD's `fit`, which
///                  computes `decision_scores_`; the "fit+score" of the targets)
///     fit_and_score_alloc  the same, the score vector allocated inside the loop (as PyOD's
///                  time includes allocating its output; the headline figure)
///     fit_and_score_rows  fit_and_score_alloc on a row-major copy of the data (numpy's default
///                  C order; headline only)
///     fitscorethr  fit_and_score + Contamination{0.1} threshold + inlier mask (PyOD's `fit`
///                  also takes this percentile and sets `labels_`)
///   and spec in
///     static10   EqualWidth, 10 bins, 1 shift (classic HBOS static bins, PyOD's default job)
///     default    hbos::default_feature(): EqualWidth, 5 bins x 5 shifts (ASH)
///     dynamic10  EqualFrequency, 10 bins (Goldstein & Dengel's dynamic bins; sorts each column)
///     auto       EqualWidth, BinCountRule::BirgeRozenblac (sorts each column)
///   for n in {1e2, 1e3, 1e4, 1e5, 1e6} x d in {1, 2, 8}, float and double.
/// - `headline/...`: the 1e6 x 2 cases the targets are stated on, registered a second time so that
///   they can be run alone with more time and repetitions; `fitscore_alloc` uses the allocating
///   `Hbos::score` (what a user writes in one line) instead of `score_into`.
///
/// Data: column-major `Eigen::Matrix<Scalar, -1, -1>`, N(0, 1) from std::mt19937_64 seeded with
/// 20240611, drawn in double (float runs use the same values rounded), one matrix per (n, d)
/// shared by every benchmark of that shape.
///
///     bench_core --benchmark_filter='^(stream|core)/' --benchmark_min_time=0.01
///     bench_core --benchmark_filter='^headline/' --benchmark_min_time=0.2
///         --benchmark_repetitions=5 --benchmark_report_aggregates_only=true   (one line)

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/model.hpp"
#include "hbos/threshold.hpp"

#include "bench_specs.hpp"

namespace {

using Index = Eigen::Index;

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// The N(0, 1) matrix of shape n x d, generated once and kept for the whole run.
template <class Scalar>
const Matrix<Scalar>& normal_data(Index n, Index d) {
  static std::map<std::pair<Index, Index>, std::unique_ptr<Matrix<Scalar>>> cache;
  auto& slot = cache[{n, d}];
  if (!slot) {
    std::mt19937_64 rng(20240611);
    std::normal_distribution<double> normal(0.0, 1.0);
    slot = std::make_unique<Matrix<Scalar>>(n, d);
    for (Index j = 0; j < d; ++j)
      for (Index i = 0; i < n; ++i) (*slot)(i, j) = static_cast<Scalar>(normal(rng));
  }
  return *slot;
}

enum class Spec { Static10, Default, Dynamic10, Auto };
enum class Op {
  Fit,
  Score,
  FitScore,
  FitAndScore,
  FitAndScoreAlloc,
  FitAndScoreRows,
  FitScoreAlloc,
  FitScoreThreshold
};

const char* name_of(Spec spec) {
  switch (spec) {
    case Spec::Static10:
      return "static10";
    case Spec::Default:
      return "default";
    case Spec::Dynamic10:
      return "dynamic10";
    case Spec::Auto:
      return "auto";
  }
  return "?";
}

const char* name_of(Op op) {
  switch (op) {
    case Op::Fit:
      return "fit";
    case Op::Score:
      return "score";
    case Op::FitScore:
      return "fitscore";
    case Op::FitAndScore:
      return "fit_and_score";
    case Op::FitAndScoreAlloc:
      return "fit_and_score_alloc";
    case Op::FitAndScoreRows:
      return "fit_and_score_rows";
    case Op::FitScoreAlloc:
      return "fitscore_alloc";
    case Op::FitScoreThreshold:
      return "fitscorethr";
  }
  return "?";
}

using hbos_bench::scalar_name;

hbos::HbosParams params_of(Spec spec) {
  switch (spec) {
    case Spec::Static10:
      return hbos_bench::static_bins(10);
    case Spec::Default:
      return hbos::HbosParams{};  // hbos::default_feature() for every feature
    case Spec::Dynamic10:
      return hbos_bench::equal_frequency_bins(10);
    case Spec::Auto:
      return hbos_bench::birge_rozenblac_bins();
  }
  return {};
}

template <class Scalar>
void bm_stream_sum(benchmark::State& state, Index n, Index d) {
  const Matrix<Scalar>& x = normal_data<Scalar>(n, d);
  for (auto _ : state) {
    Scalar sum = x.sum();
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * n * d);
}

template <class Scalar>
void bm_core(benchmark::State& state, Op op, Spec spec, Index n, Index d) {
  using Model = hbos::Hbos<Scalar>;
  const Matrix<Scalar>& x = normal_data<Scalar>(n, d);
  const hbos::HbosParams params = params_of(spec);
  const hbos::ThresholdRule rule = hbos::Contamination{0.1};
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> scores(n);
  Eigen::Array<bool, Eigen::Dynamic, 1> inlier(n);
  std::vector<Scalar> threshold_scratch(static_cast<std::size_t>(n));
  std::optional<Model> fitted;  // only the score-only benchmark needs a model fitted beforehand
  if (op == Op::Score) fitted.emplace(Model::fit(x, params));
  // The same values row by row (numpy's default C order), for the row-major benchmark only.
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows;
  if (op == Op::FitAndScoreRows) rows = x;

  for (auto _ : state) {
    switch (op) {
      case Op::Fit: {
        Model model = Model::fit(x, params);
        benchmark::DoNotOptimize(model);
        break;
      }
      case Op::Score:
        fitted->score_into(x, scores);
        benchmark::DoNotOptimize(scores.data());
        break;
      case Op::FitScore: {
        const Model model = Model::fit(x, params);
        model.score_into(x, scores);
        benchmark::DoNotOptimize(scores.data());
        break;
      }
      case Op::FitAndScore: {
        const Model model = Model::fit_and_score(x, scores, params);
        benchmark::DoNotOptimize(scores.data());
        benchmark::DoNotOptimize(model);
        break;
      }
      case Op::FitAndScoreAlloc: {
        typename Model::Vector out(x.rows());
        const Model model = Model::fit_and_score(x, out, params);
        benchmark::DoNotOptimize(out.data());
        benchmark::DoNotOptimize(model);
        break;
      }
      case Op::FitAndScoreRows: {
        typename Model::Vector out(x.rows());
        const Model model = Model::fit_and_score(rows, out, params);
        benchmark::DoNotOptimize(out.data());
        benchmark::DoNotOptimize(model);
        break;
      }
      case Op::FitScoreAlloc: {
        const Model model = Model::fit(x, params);
        auto out = model.score(x);
        benchmark::DoNotOptimize(out.data());
        break;
      }
      case Op::FitScoreThreshold: {
        const Model model = Model::fit_and_score(x, scores, params);
        const Scalar threshold = hbos::compute_threshold(scores, rule, threshold_scratch);
        Index kept = hbos::apply_threshold(scores, threshold, inlier);
        benchmark::DoNotOptimize(kept);
        break;
      }
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n * d);
}

/// "/<n>/<d>", Google Benchmark's convention for arguments (CI's smoke run selects "/100/").
std::string shape(Index n, Index d) { return "/" + std::to_string(n) + "/" + std::to_string(d); }

template <class Scalar>
void register_stream(const std::string& prefix, Index n, Index d) {
  const std::string name = prefix + "/sum/" + scalar_name<Scalar>() + shape(n, d);
  benchmark::RegisterBenchmark(name.c_str(), [n, d](benchmark::State& state) {
    bm_stream_sum<Scalar>(state, n, d);
  })->Unit(benchmark::kMicrosecond);
}

template <class Scalar>
void register_core(const std::string& prefix, Op op, Spec spec, Index n, Index d) {
  const std::string name =
      prefix + "/" + name_of(op) + "/" + name_of(spec) + "/" + scalar_name<Scalar>() + shape(n, d);
  benchmark::RegisterBenchmark(name.c_str(), [op, spec, n, d](benchmark::State& state) {
    bm_core<Scalar>(state, op, spec, n, d);
  })->Unit(benchmark::kMicrosecond);
}

template <class Scalar>
void register_grid() {
  const Spec specs[] = {Spec::Static10, Spec::Default, Spec::Dynamic10, Spec::Auto};
  const Op ops[] = {Op::Fit, Op::Score, Op::FitScore, Op::FitAndScore, Op::FitScoreThreshold};
  for (const Index n : {Index{100}, Index{1000}, Index{10000}, Index{100000}, Index{1000000}}) {
    for (const Index d : {Index{1}, Index{2}, Index{8}}) {
      register_stream<Scalar>("stream", n, d);
      for (const Spec spec : specs)
        for (const Op op : ops) register_core<Scalar>("core", op, spec, n, d);
    }
  }
}

/// 1e6 x 2: the streaming pass next to every fit+score variant the targets mention.
template <class Scalar>
void register_headline() {
  const Index n = 1000000, d = 2;
  register_stream<Scalar>("headline/stream", n, d);
  register_core<Scalar>("headline", Op::FitAndScore, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::FitScore, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::FitAndScoreAlloc, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::FitAndScoreRows, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::FitScoreAlloc, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::Fit, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::Score, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::FitScoreThreshold, Spec::Static10, n, d);
  register_core<Scalar>("headline", Op::FitAndScore, Spec::Default, n, d);
  register_core<Scalar>("headline", Op::FitAndScore, Spec::Dynamic10, n, d);
  register_core<Scalar>("headline", Op::FitAndScore, Spec::Auto, n, d);
}

}  // namespace

int main(int argc, char** argv) {
  register_headline<double>();
  register_headline<float>();
  register_grid<double>();
  register_grid<float>();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
