#pragma once
/// \file
/// The default screen against the others, run by run. A run is one (scenario, mask variant,
/// seed); every screen ran on the same rendered frames, so their ATEs pair up. Over the runs
/// with a mask, and apart over those without:
/// - each screen's mean rank by ATE (1 = lowest; Demsar, "Statistical comparisons of
///   classifiers over multiple data sets", JMLR 2006): one number per screen that a single
///   failed run cannot dominate, as it does a mean;
/// - the default against each other screen: on how many runs its ATE is lower, higher or equal,
///   the median difference, and the Wilcoxon signed-rank p-value (paired_statistics.hpp).
/// And per (scenario, mask): the default's verdict against the screen with the lowest mean ATE,
/// by the variant grid's rule (best; tied: the gap within the larger of the two screens'
/// standard deviations over the seeds; behind).

#include "dynbench/summary.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace hbos::dynbench {

struct PairedAgainst {
  std::string screen;
  int runs = 0, lower = 0, higher = 0, equal = 0;  ///< the default's ATE against this screen's
  double median_difference_cm = 0.0;               ///< default minus this screen
  double wilcoxon_p = 0.0;                         ///< NaN: no run differs
};

/// The runs with a mask (`masked`) or without.
struct ScreenRanking {
  bool masked = true;
  int runs = 0;  ///< runs on which every screen of `mean_rank` ran
  std::vector<std::pair<std::string, double>> mean_rank;  ///< lowest (best) first
  std::vector<PairedAgainst> paired;                      ///< the default against each screen
};

struct RowVerdict {
  std::string scenario, mask;
  std::string best_other;  ///< the other screen with the lowest mean ATE
  double best_other_cm = 0.0, default_cm = 0.0, spread_cm = 0.0;
  std::string verdict;  ///< "best", "tied" or "behind"
};

/// [cm] a run whose ATE exceeds this has lost the room, not merely drifted (the rendered
/// scenes' working runs and their spread: docs/results.md): listed by name, as means hide which.
inline constexpr double kFailedRunAteCm = 5.0;

struct ScreenComparison {
  std::vector<ScreenRanking> rankings;   ///< masked, then without a mask (where any ran)
  std::vector<RowVerdict> verdicts;      ///< rows where the default and another screen ran
  std::vector<std::string> failed_runs;  ///< "<cell id>: <ATE> cm" above kFailedRunAteCm
};

/// Compares every screen that ran on every run of a group (`none`, no screen, included when it
/// did). Empty when the default did not run.
[[nodiscard]] ScreenComparison compare_screens(const std::vector<CellOutcome>& outcomes,
                                               const std::vector<TableRow>& rows);

[[nodiscard]] std::string comparison_markdown(const ScreenComparison& comparison);
[[nodiscard]] nlohmann::json comparison_json(const ScreenComparison& comparison);

}  // namespace hbos::dynbench
