#pragma once
/// \file
/// Running the variant grid: every screen under the masks none, degraded and detector on every
/// semi-real variant (variants.hpp), with the tracker of `base`. Each finished run is kept as a
/// small JSON file in a cache folder, so an interrupted grid resumes where it stopped.

#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/dataset.hpp"
#include "frontend/grid/variants.hpp"
#include "frontend/residual_screen.hpp"

#include <csignal>
#include <iosfwd>
#include <string>
#include <vector>

namespace hbos::slam {

/// What one (variant, mask, screen) run measured.
struct GridRun {
  std::string tracker;  ///< frame | map
  std::string variant;  ///< PersonVariant::name
  std::string mask;
  std::string screen;
  double ate_rmse_m = 0.0;        ///< NaN when the run could not be evaluated
  double rpe_trans_rmse_m = 0.0;  ///< per frame
  int frames = 0;
  int frames_tracked = 0;
  long matches = 0;
  long person_matches = 0;
  long person_survivors = 0;
  long static_matches = 0;
  long static_dropped = 0;
  std::vector<int> frame_person_matches;    ///< per frame
  std::vector<int> frame_person_survivors;  ///< per frame
};

/// A variant and the per-frame parallax residual of its person (parallax.hpp).
struct GridVariant {
  PersonVariant variant;
  std::vector<double> parallax_px;
};

struct GridResult {
  std::string tracker;
  int frames = 0;
  std::vector<GridVariant> variants;
  std::vector<std::string> masks;
  std::vector<std::string> screens;
  std::vector<GridRun> runs;  ///< finished runs (all of them unless interrupted)
  int reused = 0;             ///< of them, read back from the cache
  bool complete = false;
};

/// The masks of the grid: none, degraded, detector.
[[nodiscard]] std::vector<MaskSource> grid_masks();

/// Runs (or reuses from `cache_dir`) every run of the grid, for `screens` (by default every
/// strategy, screen_strategy_names()). With `progress`, one line per run;
/// when `stop` becomes non-zero, returns after the run in progress with `complete` false.
/// Throws hbos::InvalidArgument when the sequence has no ground truth.
[[nodiscard]] GridResult run_variant_grid(
    const Config& base, const RgbdSequence& sequence, const CameraModel& camera,
    const std::string& cache_dir, std::ostream* progress, const volatile std::sig_atomic_t* stop,
    const std::vector<std::string>& screens = screen_strategy_names());

}  // namespace hbos::slam
