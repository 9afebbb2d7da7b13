#pragma once
/// \file
/// The variant grid's tables: per mask x screen the mean and spread over the semi-real variants,
/// per mask whether the default screen is best or tied within that spread, and how many person
/// matches each screen keeps in the parallax-hidden frames (parallax.hpp) against the others.
///
/// The rule for "tied" (fixed before the first result): the default's mean exceeds the best
/// screen's mean by no more than the larger of the two screens' standard deviations over the
/// variants. The paired comparison (the default against the best on each variant) is reported
/// beside it, because the variants shift every screen together.

#include "frontend/grid/grid_run.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hbos::slam {

struct Spread {
  double mean = 0.0;
  double sd = 0.0;  ///< sample standard deviation (n - 1); 0 for one value
  int n = 0;        ///< values that were finite
};

/// One mask x screen over the variants.
struct GridCell {
  std::string mask;
  std::string screen;
  Spread ate_cm;
  Spread rpe_mm;
  long person_matches = 0, person_survivors = 0;
  long static_matches = 0, static_dropped = 0;
  /// Person matches in the parallax-hidden frames and in the others, summed over variants.
  long hidden_matches = 0, hidden_survivors = 0;
  long other_matches = 0, other_survivors = 0;
};

/// Per mask and metric: the best screen other than the default, and where the default stands.
struct GridVerdict {
  std::string mask;
  std::string metric;  ///< ATE | RPE
  std::string best_screen;
  double best_mean = 0.0, default_mean = 0.0;
  double spread = 0.0;  ///< max(sd of the default, sd of the best)
  std::string verdict;  ///< frontend/standing.hpp: best | tied | behind ("not met" before stop 31)
  Spread paired_gap;    ///< default - best other screen, on each variant
  int default_lower = 0;
};

[[nodiscard]] std::vector<GridCell> grid_cells(const GridResult& grid);
[[nodiscard]] std::vector<GridVerdict> grid_verdicts(const GridResult& grid,
                                                     const std::vector<GridCell>& cells);

[[nodiscard]] std::string grid_markdown(const GridResult& grid, const std::string& settings);
[[nodiscard]] nlohmann::json grid_json(const GridResult& grid, const std::string& settings);

}  // namespace hbos::slam
