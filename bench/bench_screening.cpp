// Per-frame reprojection screening time, every strategy side by side, n matches per frame.
// The screen is warmed up (reserve + one frame) before timing, so the timed loop allocates
// nothing (proven by tests/unit/test_screen_no_alloc.cpp). Frames: synthetic scenes with 5 %
// leaked dynamic matches, 3 % gross mismatches, a 1.5 px rough pose.
//
//   bench_screening --benchmark_min_time=0.01

#include <benchmark/benchmark.h>

#include <hbos/screening.hpp>

#include <map>
#include <string>
#include <type_traits>

#include "../tests/support/synthetic_scene.hpp"

namespace {

const hbos_test::Scene& scene_of(int n) {
  static std::map<int, hbos_test::Scene> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    hbos_test::SceneConfig c;
    c.seed = 42;
    c.n_matches = n;
    c.person_share = 0.035;
    c.edge_share = 0.0075;
    c.carried_share = 0.0075;
    c.gross_share = 0.03;
    c.pose_error_px = 1.5;
    it = cache.emplace(n, hbos_test::make_scene(c)).first;
  }
  return it->second;
}

void fill(const hbos_test::Scene& scene, hbos::Matchesd& m, int flag_every = 0) {
  m.clear();
  for (Eigen::Index i = 0; i < scene.size(); ++i)
    m.add(scene.predicted.col(i), scene.observed.col(i), scene.sigma(i),
          scene.on_dynamic_mask(i) || (flag_every > 0 && i % flag_every == 0));
}

/// The same frame in single precision, as ORB-SLAM2's float keypoints give it.
void fill(const hbos_test::Scene& scene, hbos::Matches<float>& m) {
  m.clear();
  for (Eigen::Index i = 0; i < scene.size(); ++i)
    m.add(scene.predicted.col(i).cast<float>(), scene.observed.col(i).cast<float>(),
          static_cast<float>(scene.sigma(i)), scene.on_dynamic_mask(i));
}

template <class Scalar = double>
void run_single(benchmark::State& state, const hbos::ScreenStrategy& strategy, int flag_every = 0) {
  const int n = static_cast<int>(state.range(0));
  const hbos_test::Scene& scene = scene_of(n);
  hbos::Matches<Scalar> matches;
  if constexpr (std::is_same_v<Scalar, double>) {
    fill(scene, matches, flag_every);
  } else {
    fill(scene, matches);
  }
  hbos::ReprojectionScreen<Scalar> screen(strategy);
  screen.reserve(n);
  screen.screen(matches);  // warm-up
  for (auto _ : state) {
    const auto& result = screen.screen(matches);
    benchmark::DoNotOptimize(result.n_inliers());
  }
  state.SetItemsProcessed(state.iterations() * n);
}

/// Screen -> Gauss-Newton refit -> re-screen, 4 rounds (the pose is reset to the rough one and
/// the predictions re-projected each iteration, as a tracker would per frame).
void run_iterated(benchmark::State& state, const hbos::ScreenStrategy& strategy,
                  const hbos::IteratedScreenOptions& options = {}) {
  const int n = static_cast<int>(state.range(0));
  const hbos_test::Scene& scene = scene_of(n);
  const hbos::PinholeCamerad camera;
  hbos::Matchesd matches;
  hbos::ReprojectionScreend screen(strategy);
  screen.reserve(n);
  for (auto _ : state) {
    hbos::project_matches(scene.points_world, scene.observed, scene.sigma, scene.on_dynamic_mask,
                          scene.T_cur_world_rough, camera, matches);
    Eigen::Isometry3d T = scene.T_cur_world_rough;
    const auto& result =
        hbos::screen_and_refine_pose(screen, scene.points_world, camera, T, matches, options);
    benchmark::DoNotOptimize(result.n_inliers());
  }
  state.SetItemsProcessed(state.iterations() * n);
}

/// Building the frame's Matches from the tracker's arrays (a streaming read: add per match into a
/// reused, cleared container, as a tracker does each frame), to set against the screens' times.
void BM_fill_matches(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const hbos_test::Scene& scene = scene_of(n);
  hbos::Matchesd matches;
  matches.reserve(n);
  fill(scene, matches);
  for (auto _ : state) {
    fill(scene, matches);
    benchmark::DoNotOptimize(matches.size());
  }
  state.SetItemsProcessed(state.iterations() * n);
}

/// The same frame from the same arrays in one call (Matches::assign: the columns checked and
/// copied whole).
void BM_fill_matches_assign(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const hbos_test::Scene& scene = scene_of(n);
  hbos::Matchesd matches;
  matches.reserve(n);
  matches.assign(scene.predicted, scene.observed, scene.sigma, scene.on_dynamic_mask);
  for (auto _ : state) {
    matches.assign(scene.predicted, scene.observed, scene.sigma, scene.on_dynamic_mask);
    benchmark::DoNotOptimize(matches.size());
  }
  state.SetItemsProcessed(state.iterations() * n);
}

void BM_hbos_default(benchmark::State& s) { run_single(s, hbos::HbosScreen{}); }
// The default and chi^2 in single precision (ReprojectionScreen<float>, the README's example).
void BM_hbos_default_float(benchmark::State& s) { run_single<float>(s, hbos::HbosScreen{}); }
void BM_chi2_float(benchmark::State& s) { run_single<float>(s, hbos::ChiSquareGate{}); }
// The default without its last pass (the affine field refitted on the matches that look static):
// what that pass costs (docs/benchmarks.md, stop 26; it is kept for its static loss).
void BM_hbos_norefit(benchmark::State& s) {
  hbos::HbosScreen h;
  h.field.refit_on_static = false;
  run_single(s, h);
}
// The map tracker's frames: a quarter of the matches are new points on probation, flagged and
// kept out of the fit (FlaggedPolicy::FitWithout, the default), spread over the image. With and
// without the flagged matches' own consensus (CoherenceEvidence::flagged_consensus, which the
// front end turns on for that tracker): what the option's second coherence pass costs.
void BM_hbos_probation(benchmark::State& s) { run_single(s, hbos::HbosScreen{}, 4); }
void BM_hbos_probation_consensus(benchmark::State& s) {
  hbos::HbosScreen h;
  h.coherence.flagged_consensus = true;
  run_single(s, h, 4);
}
void BM_hbos_paper(benchmark::State& s) { run_single(s, hbos::HbosScreen::paper()); }
void BM_chi2(benchmark::State& s) { run_single(s, hbos::ChiSquareGate{}); }
void BM_fixed(benchmark::State& s) { run_single(s, hbos::FixedPixelGate{}); }
void BM_quantile(benchmark::State& s) { run_single(s, hbos::QuantileGate{}); }
void BM_mad(benchmark::State& s) { run_single(s, hbos::MadGate{}); }
void BM_iterated_hbos_default(benchmark::State& s) { run_iterated(s, hbos::HbosScreen{}); }
/// The default with a rigid refit of its field in rounds 2-4, as the SLAM example's frame
/// tracker screens (its lower gate floor aside).
void BM_iterated_hbos_rigid(benchmark::State& s) {
  hbos::IteratedScreenOptions options;
  options.later_rigid_field = true;
  run_iterated(s, hbos::HbosScreen{}, options);
}
void BM_iterated_chi2(benchmark::State& s) { run_iterated(s, hbos::ChiSquareGate{}); }

#define HBOS_SIZES \
  ->Arg(100)->Arg(300)->Arg(1000)->Arg(2000)->Arg(5000)->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_fill_matches) HBOS_SIZES;
BENCHMARK(BM_fill_matches_assign) HBOS_SIZES;
BENCHMARK(BM_hbos_default) HBOS_SIZES;
BENCHMARK(BM_hbos_default_float) HBOS_SIZES;
BENCHMARK(BM_hbos_norefit) HBOS_SIZES;
BENCHMARK(BM_hbos_probation) HBOS_SIZES;
BENCHMARK(BM_hbos_probation_consensus) HBOS_SIZES;
BENCHMARK(BM_hbos_paper) HBOS_SIZES;
BENCHMARK(BM_chi2) HBOS_SIZES;
BENCHMARK(BM_chi2_float) HBOS_SIZES;
BENCHMARK(BM_fixed) HBOS_SIZES;
BENCHMARK(BM_quantile) HBOS_SIZES;
BENCHMARK(BM_mad) HBOS_SIZES;
BENCHMARK(BM_iterated_hbos_default) HBOS_SIZES;
BENCHMARK(BM_iterated_hbos_rigid) HBOS_SIZES;
BENCHMARK(BM_iterated_chi2) HBOS_SIZES;

}  // namespace

BENCHMARK_MAIN();
