#pragma once
/// \file
/// The benchmark's one table: cells grouped by (scenario, mask, screen) over seeds, every metric
/// as mean ± sample standard deviation over the seeds, as Markdown and JSON; and the per-stage
/// times in the form of the HBOS paper's Table III.

#include "dynbench/cell_run.hpp"
#include "dynbench/cells.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hbos::dynbench {

/// A metric over seeds. NaN values (a share without its denominator, a time not measured) are
/// left out; `n` counts the rest.
struct Spread {
  double mean = 0.0;
  double sd = 0.0;  ///< sample standard deviation (n - 1); 0 for n = 1
  int n = 0;
  std::vector<double> values;
};

[[nodiscard]] Spread spread_of(const std::vector<double>& values);

struct TableRow {
  std::string scenario, mask, screen;
  std::vector<std::uint64_t> seeds;
  Spread ate_cm, rpe_mm, dynamic_kept_pct, static_dropped_pct, tracked_pct;
  Spread mask_ms, motion_ms, screen_ms;
  long dynamic_matches = 0;  ///< summed over seeds
};

/// A finished cell and what it measured.
struct CellOutcome {
  Cell cell;
  CellMetrics metrics;
};

/// Rows in the cells' order (first appearance of each (scenario, mask, screen)).
[[nodiscard]] std::vector<TableRow> table_rows(const std::vector<CellOutcome>& outcomes);

/// The Markdown: a line on the settings, the main table, then Table III (mean ms per frame by
/// stage, per screen, over every row with that screen).
[[nodiscard]] std::string table_markdown(const std::vector<TableRow>& rows,
                                         const BenchSettings& settings);

/// The JSON: settings, rows (every metric with mean, sd, n and the per-seed values) and cells.
[[nodiscard]] nlohmann::json table_json(const std::vector<TableRow>& rows,
                                        const std::vector<CellOutcome>& outcomes,
                                        const BenchSettings& settings);

}  // namespace hbos::dynbench
