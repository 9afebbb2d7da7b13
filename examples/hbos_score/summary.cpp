#include "summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <numeric>
#include <vector>

#include "roc_auc.hpp"

namespace hbos::cli {
namespace {

std::string describe_input(const ScoreOptions& options, const ScoreInput& table) {
  const std::string source = options.input == "-" ? "<stdin>" : options.input;
  std::string header;
  if (table.npy) {
    header = ".npy array";
  } else if (table.has_header) {
    header = options.csv.header == HeaderMode::Auto ? "header detected" : "header";
  } else {
    header = options.csv.header == HeaderMode::Auto
                 ? "no header (the first line is numeric; pass --header if it names the columns)"
                 : "no header";
  }
  std::string label;
  if (table.label_column) {
    label = fmt::format("; label column \"{}\" excluded", table.column_names[*table.label_column]);
  }
  if (!table.ignored_columns.empty()) {
    label += "; ignored:";
    for (std::size_t k = 0; k < table.ignored_columns.size(); ++k) {
      label +=
          fmt::format("{} \"{}\"", k > 0 ? "," : "", table.column_names[table.ignored_columns[k]]);
    }
  }
  return fmt::format("{}: {} rows x {} features ({}{})\n", source, table.rows(), table.n_features(),
                     header, label);
}

/// "5 for every feature", or the first few per feature with the range.
std::string describe_bins(const ScoreInput& table, const std::vector<Eigen::Index>& bins) {
  const auto [lo, hi] = std::minmax_element(bins.begin(), bins.end());
  if (*lo == *hi) return fmt::format("{} for every feature", *lo);
  constexpr std::size_t kShown = 8;
  std::string out;
  for (std::size_t j = 0; j < bins.size() && j < kShown; ++j) {
    out += fmt::format("{}{} {}", j > 0 ? ", " : "",
                       table.feature_name(static_cast<Eigen::Index>(j)), bins[j]);
  }
  if (bins.size() > kShown) out += ", ...";
  return out + fmt::format(" (min {}, max {})", *lo, *hi);
}

std::string describe_auc(const ScoreInput& table, const ScoredTable& scored) {
  if (!table.label_column) return "";
  const std::string& name = table.column_names[*table.label_column];
  const Eigen::Index labelled = table.labels.sum();
  const auto auc = roc_auc(scored.scores, table.labels);
  if (!auc) {
    return fmt::format("ROC-AUC against \"{}\": undefined (the labels hold one class only)\n",
                       name);
  }
  const Eigen::Index hits = (table.labels.array() * scored.outlier.array()).sum();
  return fmt::format(
      "ROC-AUC against \"{}\": {:.4f} ({} labelled outliers; {} of the {} flagged rows are "
      "labelled "
      "outliers)\n",
      name, *auc, labelled, hits, scored.n_outliers);
}

/// The top rows by score with their two largest contributions.
std::string describe_top(const ScoreOptions& options, const ScoreInput& table,
                         const ScoredTable& scored) {
  const auto n = static_cast<std::size_t>(scored.scores.size());
  const std::size_t k =
      std::min(n, static_cast<std::size_t>(std::max<Eigen::Index>(0, options.top)));
  if (k == 0) return "";
  std::vector<Eigen::Index> order(n);
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  // Highest score first; ties keep file order.
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k), order.end(),
                    [&](Eigen::Index a, Eigen::Index b) {
                      return scored.scores[a] > scored.scores[b] ||
                             (scored.scores[a] == scored.scores[b] && a < b);
                    });
  std::string out = fmt::format("top {} rows by score:\n", k);
  const Eigen::Index d = scored.contributions.cols();
  for (std::size_t r = 0; r < k; ++r) {
    const Eigen::Index i = order[r];
    std::vector<Eigen::Index> features(static_cast<std::size_t>(d));
    std::iota(features.begin(), features.end(), Eigen::Index{0});
    const std::size_t shown = std::min<std::size_t>(2, features.size());
    std::partial_sort(features.begin(), features.begin() + static_cast<std::ptrdiff_t>(shown),
                      features.end(), [&](Eigen::Index a, Eigen::Index b) {
                        return scored.contributions(i, a) > scored.contributions(i, b);
                      });
    std::string why;
    for (std::size_t f = 0; f < shown; ++f) {
      why += fmt::format("{}{} {:.3g}", f > 0 ? ", " : "", table.feature_name(features[f]),
                         scored.contributions(i, features[f]));
    }
    const std::string truth =
        table.label_column ? fmt::format("  labelled {}", table.labels[i]) : "";
    // A .npy row by its index, as numpy would address it; a CSV row by its line.
    const std::string where =
        table.npy ? fmt::format("row {:<8}", i) : fmt::format("line {:<7}", table.line_of(i));
    out += fmt::format("  {} score {:<10.4g} flagged {}{}  largest contributions: {}\n", where,
                       scored.scores[i], scored.outlier[i], truth, why);
  }
  return out;
}

}  // namespace

std::string format_summary(const ScoreOptions& options, const ScoreInput& table,
                           const ScoredTable& scored) {
  std::string out = describe_input(options, table);
  if (table.has_header && !table.numeric_header_cells.empty()) {
    // The header is always the first line (a blank line before it is an error).
    out += fmt::format(
        "warning: the first line was taken as a header although {} of its cells look numeric; "
        "pass --header or --no-header to decide\n",
        table.numeric_header_cells.size());
  }
  out += "model: " + scored.model + "\n";
  out += "bins per feature: " + describe_bins(table, scored.bins) + "\n";
  const double lo = scored.scores.minCoeff();
  const double hi = scored.scores.maxCoeff();
  out += fmt::format("threshold: {} -> {:.6g} (scores from {:.6g} to {:.6g})\n",
                     to_string(options.threshold), scored.threshold, lo, hi);
  out += fmt::format(
      "outliers: {} of {} rows ({:.1f} %)\n", scored.n_outliers, table.rows(),
      100.0 * static_cast<double>(scored.n_outliers) / static_cast<double>(table.rows()));
  out += describe_auc(table, scored);
  out += describe_top(options, table, scored);
  return out;
}

}  // namespace hbos::cli
