#include "results_csv.hpp"

#include <fmt/format.h>

#include <iterator>

namespace hbos::cli {
namespace {

/// A CSV cell holding `text`, quoted when a reader would otherwise split or trim it.
std::string csv_cell(const std::string& text) {
  const bool plain = text.find_first_of(",\"\r\n") == std::string::npos && !text.empty() &&
                     text.front() != ' ' && text.back() != ' ';
  if (plain) return text;
  std::string out = "\"";
  for (const char c : text) {
    out += c;
    if (c == '"') out += '"';
  }
  return out + "\"";
}

}  // namespace

std::string format_results(const ScoredTable& scored, const CsvTable& table, bool contributions) {
  fmt::memory_buffer out;
  auto put = std::back_inserter(out);
  fmt::format_to(put, "score,label");
  const Eigen::Index d = table.features.cols();
  if (contributions) {
    for (Eigen::Index j = 0; j < d; ++j)
      fmt::format_to(put, ",{}", csv_cell("contrib_" + table.feature_name(j)));
  }
  fmt::format_to(put, "\n");
  for (Eigen::Index i = 0; i < scored.scores.size(); ++i) {
    // fmt's default for double is the shortest representation that round-trips; adding +0.0
    // turns a negative zero (PyOD's -log2(1)) into "0".
    fmt::format_to(put, "{},{}", scored.scores[i] + 0.0, scored.outlier[i]);
    if (contributions) {
      for (Eigen::Index j = 0; j < d; ++j)
        fmt::format_to(put, ",{}", scored.contributions(i, j) + 0.0);
    }
    fmt::format_to(put, "\n");
  }
  return fmt::to_string(out);
}

}  // namespace hbos::cli
