#pragma once
/// \file
/// One cell of the benchmark: the front end (frontend/sequence_run.hpp) on one rendered
/// sequence with one mask variant and one screen, evaluated against the sequence's ground truth
/// and its per-pixel object ids. A finished cell leaves `cells/<id>/` with the front end's usual
/// outputs (trajectory, stats.csv, summary.json, figures) and `cell.json`, written last and
/// atomically: a cell without cell.json did not finish.

#include "dynbench/cells.hpp"

#include <nlohmann/json.hpp>

#include <csignal>
#include <optional>
#include <string>

namespace hbos::dynbench {

/// What a cell measured. Shares are in [0, 1]; times are per frame.
struct CellMetrics {
  double ate_rmse_m = 0.0;
  double rpe_trans_m = 0.0;  ///< RMSE per frame (delta 1 frame)
  double rpe_rot_deg = 0.0;  ///< RMSE per frame
  long dynamic_matches = 0;  ///< matches with a keypoint on a dynamic object (objects/ ids)
  long dynamic_kept = 0;
  long static_matches = 0;
  long static_dropped = 0;
  int frames = 0;
  int frames_tracked = 0;
  /// Table III's stages [ms per frame, median over frames]: the mask (here: reading the mask
  /// file), motion estimation (ORB, matching, rough pose, refinement: the whole track() call
  /// less the screen; NaN where the tracker does not time it), and dynamic point detection and
  /// removal (the screen).
  double mask_ms = 0.0;
  double motion_ms = 0.0;
  double screen_ms = 0.0;
  double wall_s = 0.0;  ///< [s] the cell, reading and writing included

  /// dynamic_kept / dynamic_matches; nullopt without dynamic matches.
  [[nodiscard]] std::optional<double> dynamic_kept_share() const;
  [[nodiscard]] double static_dropped_share() const;
  [[nodiscard]] double tracked_share() const;
};

[[nodiscard]] nlohmann::json to_json(const CellMetrics& m);
/// Throws nlohmann::json::exception on a missing field.
[[nodiscard]] CellMetrics metrics_from_json(const nlohmann::json& j);

/// A cell's folder: `<out_dir>/cells/<id>`.
[[nodiscard]] std::string cell_dir(const BenchSettings& settings, const Cell& cell);

/// The stored metrics of a finished cell whose settings equal `expected`, else nullopt (never
/// run, interrupted, other settings, or an unreadable cell.json).
[[nodiscard]] std::optional<CellMetrics> load_finished_cell(const BenchSettings& settings,
                                                            const Cell& cell,
                                                            const nlohmann::json& expected);

/// Runs `cell` on the sequence in `sequence_dir` and writes its folder. Returns nullopt when
/// `stop` became non-zero during the run (nothing is written then). Throws
/// hbos::InvalidArgument on bad input (a missing mask, a sequence without ground truth) and
/// std::runtime_error when an output cannot be written.
std::optional<CellMetrics> run_cell(const BenchSettings& settings, const Cell& cell,
                                    const std::string& sequence_dir,
                                    const nlohmann::json& cell_settings,
                                    const volatile std::sig_atomic_t* stop);

}  // namespace hbos::dynbench
