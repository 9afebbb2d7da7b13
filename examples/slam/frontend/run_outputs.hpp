#pragma once
/// \file
/// The files a run leaves in its output folder, each written atomically (temporary + rename):
/// trajectory.txt (TUM format), stats.csv (per frame), summary.json, and the PNGs
/// matches.png, residual_histogram.png plus the evaluator's top_view.png, ate_over_time.png,
/// rpe_over_time.png when there is ground truth.

#include "eval/trajectory.hpp"
#include "frontend/config.hpp"
#include "frontend/sequence_run.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hbos::slam {

/// stats.csv: a header row and one row per frame.
[[nodiscard]] std::string stats_csv(const std::vector<FrameStats>& stats);

/// The numbers of summary.json: settings, totals and (with ground truth) ATE and RPE.
[[nodiscard]] nlohmann::json summary_json(const RunResult& run, const Config& config,
                                          const std::string& camera_name);

/// "static" or "person", the scenario's name in tables and files.
[[nodiscard]] const char* scenario_name(const ScenarioConfig& scenario);

/// Writes every output of `run` into `dir` (created if needed) and returns the paths written.
/// `groundtruth` may be null. Throws std::runtime_error when a file cannot be written.
std::vector<std::string> write_run_outputs(const std::string& dir, const RunResult& run,
                                           const Config& config, const std::string& camera_name,
                                           const Trajectory* groundtruth);

/// Removes from `dir` the outputs a run of hbos-slam can write (figures, plots, the map's
/// reports) that are not among `written`: left from an earlier run into the same folder, they
/// would sit beside this run's results as though they were its own. Returns the paths removed.
std::vector<std::string> remove_stale_outputs(const std::string& dir,
                                              const std::vector<std::string>& written);

}  // namespace hbos::slam
