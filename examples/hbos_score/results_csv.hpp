#pragma once
/// \file
/// hbos-score's output: one CSV line per input row, in input order.

#include <string>

#include "csv_reader.hpp"
#include "scoring.hpp"

namespace hbos::cli {

/// The result table as CSV text: header `score,label`, plus `contrib_<feature>` per feature when
/// `contributions` is set; `label` is 1 for an outlier (score > threshold), else 0. Numbers are
/// written in the shortest form that reads back to the same double. A feature name that needs it
/// is quoted (RFC 4180).
[[nodiscard]] std::string format_results(const ScoredTable& scored, const CsvTable& table,
                                         bool contributions);

}  // namespace hbos::cli
