#pragma once
/// \file
/// The benchmark's figures, assembled from the cells' own (frontend/figures.hpp and the
/// evaluator's eval/plot.hpp draw them per cell): the trajectories of four ways of running
/// against the ground truth side by side, and for the first mask variant the residual histogram
/// with the screen's cut and the frame with kept and rejected matches, with and without a mask.

#include "dynbench/cells.hpp"

#include <string>
#include <vector>

namespace hbos::dynbench {

/// Writes into `<out_dir>/figures/` (each atomically) from the finished cells of the first
/// scenario, seed and variant: `trajectories.png` (top views of none, default alone, mask only,
/// mask + default, labelled), `residual_histogram.png` and `matches.png` (default alone),
/// `residual_histogram_mask.png` and `matches_mask.png` (mask + default). A figure whose cells
/// are not in the grid is skipped. Returns the paths written; throws std::runtime_error when a
/// file cannot be written.
std::vector<std::string> write_bench_figures(const BenchSettings& settings);

}  // namespace hbos::dynbench
