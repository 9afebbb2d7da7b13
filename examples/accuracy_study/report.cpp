#include "report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace hbos::study {

Eigen::Index method_index(const StudyResult& result, const std::string& key) {
  for (std::size_t m = 0; m < result.methods.size(); ++m) {
    if (result.methods[m].key == key) return static_cast<Eigen::Index>(m);
  }
  throw std::out_of_range("the study has no method \"" + key + "\"");
}

double mean_auc(const StudyResult& result, const std::string& key) {
  return result.auc.col(method_index(result, key)).mean();
}

namespace {

/// One Markdown table: a row per data set, the given method columns, a mean row.
void put_table(fmt::memory_buffer& out, const StudyResult& result,
               const std::vector<Eigen::Index>& columns, bool sizes) {
  auto put = std::back_inserter(out);
  fmt::format_to(put, "| data set |{}", sizes ? " n | d | outliers |" : "");
  for (const Eigen::Index m : columns)
    fmt::format_to(put, " {} |", result.methods[static_cast<std::size_t>(m)].title);
  fmt::format_to(put, "\n|---|{}", sizes ? "--:|--:|--:|" : "");
  for (std::size_t m = 0; m < columns.size(); ++m) fmt::format_to(put, "--:|");
  fmt::format_to(put, "\n");
  for (std::size_t s = 0; s < result.datasets.size(); ++s) {
    const auto row = static_cast<Eigen::Index>(s);
    fmt::format_to(put, "| {} |", result.datasets[s]);
    if (sizes)
      fmt::format_to(put, " {} | {} | {} |", result.rows[s], result.features[s],
                     result.outliers[s]);
    for (const Eigen::Index m : columns) fmt::format_to(put, " {:.4f} |", result.auc(row, m));
    fmt::format_to(put, "\n");
  }
  fmt::format_to(put, "| **mean** |{}", sizes ? " | | |" : "");
  for (const Eigen::Index m : columns)
    fmt::format_to(put, " **{:.4f}** |", result.auc.col(m).mean());
  fmt::format_to(put, "\n\n");
}

/// "largest |change| 0.0016 (cardio), mean |change| 0.0001": how far a transform moves a method.
std::string describe_change(const StudyResult& result, const std::string& before,
                            const std::string& after) {
  const Eigen::VectorXd change =
      (result.auc.col(method_index(result, before)) - result.auc.col(method_index(result, after)))
          .cwiseAbs();
  Eigen::Index worst = 0;
  const double largest = change.maxCoeff(&worst);
  if (largest == 0.0) return "every per-set AUC bit-identical";
  return fmt::format(
      "largest |change| of a per-set AUC {:.2g} ({}), mean |change| {:.2g}, mean AUC {:.4f} -> "
      "{:.4f}",
      largest, result.datasets[static_cast<std::size_t>(worst)], change.mean(),
      mean_auc(result, before), mean_auc(result, after));
}

}  // namespace

std::string format_markdown(const StudyResult& result, std::uint64_t seed) {
  fmt::memory_buffer out;
  auto put = std::back_inserter(out);
  std::vector<Eigen::Index> main_columns;
  std::vector<Eigen::Index> other_columns{method_index(result, "default")};
  for (std::size_t m = 0; m < result.methods.size(); ++m) {
    (result.methods[m].main ? main_columns : other_columns).push_back(static_cast<Eigen::Index>(m));
  }
  put_table(out, result, main_columns, true);
  fmt::format_to(put, "Other binnings (same protocol):\n\n");
  put_table(out, result, other_columns, false);

  for (const Method& m : result.methods)
    fmt::format_to(put, "- **{}**: {}\n", m.title, m.description);
  fmt::format_to(put,
                 "\nThe random factors and shifts come from mt19937_64 seeded with {} + the FNV-1a "
                 "hash of the "
                 "data set's name.\n\n",
                 seed);

  const Eigen::Index def = method_index(result, "default");
  const Eigen::Index pyod = method_index(result, "pyod");
  const double mean_default = mean_auc(result, "default");
  const double mean_pyod = mean_auc(result, "pyod");
  fmt::format_to(put, "- Default mean {:.4f} vs PyOD mode mean {:.4f}: {}.\n", mean_default,
                 mean_pyod, mean_default >= mean_pyod ? "target met" : "target NOT met");
  std::string losses;
  for (std::size_t s = 0; s < result.datasets.size(); ++s) {
    const auto row = static_cast<Eigen::Index>(s);
    if (result.auc(row, def) < result.auc(row, pyod)) {
      losses += fmt::format("{}{} ({:+.4f})", losses.empty() ? "" : ", ", result.datasets[s],
                            result.auc(row, def) - result.auc(row, pyod));
    }
  }
  fmt::format_to(put, "- Data sets where the default mode is below the PyOD mode: {}.\n",
                 losses.empty() ? std::string("none") : losses);
  fmt::format_to(put, "- Rescaled by powers of two, default mode: {}.\n",
                 describe_change(result, "default", "default_rescaled"));
  fmt::format_to(put, "- Rescaled by powers of two, PyOD mode: {}.\n",
                 describe_change(result, "pyod", "pyod_rescaled"));
  fmt::format_to(put, "- Units changed, default mode: {}.\n",
                 describe_change(result, "default", "default_units"));
  fmt::format_to(put, "- Units changed, PyOD mode: {}.\n",
                 describe_change(result, "pyod", "pyod_units"));
  return fmt::to_string(out);
}

std::string format_csv(const StudyResult& result) {
  fmt::memory_buffer out;
  auto put = std::back_inserter(out);
  fmt::format_to(put, "dataset,rows,features,outliers");
  for (const Method& m : result.methods) fmt::format_to(put, ",{}", m.key);
  fmt::format_to(put, "\n");
  for (std::size_t s = 0; s < result.datasets.size(); ++s) {
    fmt::format_to(put, "{},{},{},{}", result.datasets[s], result.rows[s], result.features[s],
                   result.outliers[s]);
    for (Eigen::Index m = 0; m < result.auc.cols(); ++m) {
      fmt::format_to(put, ",{:.17g}", result.auc(static_cast<Eigen::Index>(s), m));
    }
    fmt::format_to(put, "\n");
  }
  return fmt::to_string(out);
}

}  // namespace hbos::study
