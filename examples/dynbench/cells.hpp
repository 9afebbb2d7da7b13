#pragma once
/// \file
/// The benchmark's grid: which scenarios, mask variants, seeds and screens are run, and the cells
/// they make. A cell is one run of the front end on one rendered sequence: (scenario, seed, mask,
/// screen). Runs without a mask do not depend on the mask variant, so they are one cell per
/// (scenario, seed), shared by every variant.

#include "frontend/config.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace hbos::dynbench {

/// Every setting of a benchmark run. Field defaults are the default subset (a few minutes on two
/// cores); full_grid() is `--full`.
struct BenchSettings {
  std::vector<std::string> scenarios = {"walking_xyz", "walking_rpy"};
  /// Mask variants (the renderer's masks/<variant>/ folders) run with a mask.
  std::vector<std::string> variants = {"eroded", "person_missed"};
  std::vector<std::uint64_t> seeds = {1, 2};
  int frames = 300;  ///< frames rendered and tracked per sequence; 0 = the whole trajectory
  /// People in each rendered scene, 1..3: the first N of the scenario's cast of three
  /// (examples/render/render/scenario.cpp); 0 = the scenario's own number, 2. The third is, in
  /// every scenario, one who walks along the back of the room.
  int people = 0;
  /// Screens run (names of screen_strategy_names(); `none` = refine on everything). Empty: all.
  std::vector<std::string> screens;
  /// Without a mask, run every selected screen, not only `none` and `default`: the comparison
  /// for a front end whose segmenter missed everyone.
  bool every_screen_unmasked = false;
  std::string out_dir = "out/dynbench";          ///< table, JSON, figures, cells/
  std::string cache_dir = "out/dynbench/cache";  ///< rendered sequences
  std::string renderer;                          ///< the hbos-render executable
  std::string camera = "tum3";                   ///< intrinsics of the rendered sequences
  int jobs = 2;                                  ///< cells run at once
  bool rerender = false;                         ///< render even when the cache has a sequence
  slam::Config base;                             ///< every front-end setting the grid does not set
};

/// `--full`: every scenario at its whole length, every mask variant, three seeds.
void use_full_grid(BenchSettings& settings);

/// Every scenario the renderer knows (walking_xyz, walking_static, walking_rpy,
/// walking_halfsphere, sitting_static, sitting_xyz).
[[nodiscard]] const std::vector<std::string>& all_scenarios();
/// Every mask variant the renderer writes (perfect, eroded, dilated, missing, delayed, boxes,
/// object_unmasked, person_missed).
[[nodiscard]] const std::vector<std::string>& all_variants();

/// The screens in table order: fixed, chi2, quantile, mad, paper, default, then any other name
/// screen_strategy_names() returns, and `none` first. `selected` empty = all; otherwise throws
/// hbos::InvalidArgument for a name the front end does not know.
[[nodiscard]] std::vector<std::string> screens_in_order(const std::vector<std::string>& selected);

/// One run of the front end.
struct Cell {
  std::string scenario;
  std::uint64_t seed = 0;
  std::string mask;    ///< a mask variant, or `none` (no mask)
  std::string screen;  ///< a screen strategy name, `none` = no screen

  /// Folder name under cells/: `<scenario>_s<seed>_<mask>_<screen>`.
  [[nodiscard]] std::string id() const;
};

/// The cells of `settings`, scenario by scenario and seed by seed: for each, `none` and (when
/// selected) `default` without a mask, then every variant with every selected screen. A screen
/// other than `none` and `default` is run only with a mask (the paper's setting), unless
/// `every_screen_unmasked`: then every selected screen runs without a mask too.
[[nodiscard]] std::vector<Cell> grid_cells(const BenchSettings& settings);

/// The rendered sequence's folder in the cache: `<scenario>_seed<S>_<N>f` (`full` for N = 0),
/// with `_<P>people` after it when `people` is set.
[[nodiscard]] std::string sequence_dir(const BenchSettings& settings, const std::string& scenario,
                                       std::uint64_t seed);

/// What makes a cell's result what it is: the cell, the frames, the front end's settings that
/// change results, hbos's version and a fingerprint of the sequence. A finished cell whose
/// stored settings equal these is not run again.
[[nodiscard]] nlohmann::json cell_settings(const BenchSettings& settings, const Cell& cell,
                                           const std::string& sequence_fingerprint);

}  // namespace hbos::dynbench
