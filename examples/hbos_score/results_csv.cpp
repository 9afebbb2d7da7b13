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

void format_results(const ScoredTable& scored, const CsvLayout& layout, bool contributions,
                    const TextSink& sink) {
  constexpr std::size_t kPiece = std::size_t{1} << 20;
  fmt::memory_buffer out;
  auto put = std::back_inserter(out);
  fmt::format_to(put, "score,label");
  const Eigen::Index d = layout.n_features();
  if (contributions) {
    for (Eigen::Index j = 0; j < d; ++j)
      fmt::format_to(put, ",{}", csv_cell("contrib_" + layout.feature_name(j)));
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
    if (out.size() >= kPiece) {
      sink(std::string_view(out.data(), out.size()));
      out.clear();
    }
  }
  sink(std::string_view(out.data(), out.size()));
}

}  // namespace hbos::cli
