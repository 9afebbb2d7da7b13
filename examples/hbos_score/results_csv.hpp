#pragma once
/// \file
/// hbos-score's output: one CSV line per input row, in input order.

#include <functional>
#include <string>
#include <string_view>

#include "csv_reader.hpp"
#include "scoring.hpp"

namespace hbos::cli {

/// Receives the result text piece by piece (about 1 MiB at a time).
using TextSink = std::function<void(std::string_view)>;

/// The result table as CSV text, handed to `sink` in pieces so that it is never held whole:
/// header `score,label`, plus `contrib_<feature>` per feature when
/// `contributions` is set; `label` is 1 for an outlier (score > threshold), else 0. Numbers are
/// written in the shortest form that reads back to the same double. A feature name that needs it
/// is quoted (RFC 4180).
void format_results(const ScoredTable& scored, const CsvLayout& layout, bool contributions,
                    const TextSink& sink);

}  // namespace hbos::cli
