#pragma once
/// \file
/// Presenting an Evaluation: a readable table for people, JSON for scripts.

#include "eval/evaluate.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace hbos::slam {

/// A fixed-width table with one column per metric (ATE SE(3), ATE Sim(3) if computed, RPE
/// translation and rotation) and one row per statistic, each row labelled unambiguously (RMSE
/// vs mean, population std), followed by the settings that produced it and the share tracked.
/// Values are printed with 6 decimals, as the TUM scripts print them.
[[nodiscard]] std::string format_report(const Evaluation& evaluation);

/// The metrics as JSON, full precision. Key names follow the TUM reference vectors
/// (`compared_pose_pairs`, `rmse`, ..., `trans_m`, `rot_deg`, `rotation_est_to_gt`), so the
/// output diffs cleanly against them:
///   {"ate": {...}, "ate_sim3": {...} (if computed), "tracked": {...}, "rpe": {...} (if computed),
///    "settings": {...}}
[[nodiscard]] nlohmann::json to_json(const Evaluation& evaluation);

/// The name of a delta unit as the command line spells it: "s", "frames" or "m".
[[nodiscard]] const char* to_string(RpeDeltaUnit unit);

}  // namespace hbos::slam
