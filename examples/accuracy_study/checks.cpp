#include "checks.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include "report.hpp"

namespace hbos::study {
namespace {

/// A CSV whose first column names the row and whose other cells are numbers.
struct NamedTable {
  std::vector<std::string> header;
  std::map<std::string, std::vector<double>> rows;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

NamedTable read_named_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  NamedTable table;
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> cells = split(line);
    if (table.header.empty()) {
      table.header = std::move(cells);
      continue;
    }
    if (cells.size() != table.header.size()) {
      throw std::runtime_error(fmt::format("{}:{}: {} cells, the header has {}", path, line_no,
                                           cells.size(), table.header.size()));
    }
    std::vector<double> values(cells.size(), 0.0);
    for (std::size_t j = 1; j < cells.size(); ++j) {
      const char* end = cells[j].data() + cells[j].size();
      const auto [ptr, ec] = std::from_chars(cells[j].data(), end, values[j]);
      if (ec != std::errc() || ptr != end) {
        throw std::runtime_error(
            fmt::format("{}:{}: cell {} (\"{}\") is not a number", path, line_no, j + 1, cells[j]));
      }
    }
    table.rows[cells[0]] = std::move(values);
  }
  if (table.header.empty()) throw std::runtime_error(path + ": empty file");
  return table;
}

std::size_t column_of(const NamedTable& table, const std::string& name, const std::string& path) {
  for (std::size_t j = 1; j < table.header.size(); ++j) {
    if (table.header[j] == name) return j;
  }
  throw std::runtime_error(path + ": no column \"" + name + "\"");
}

Eigen::Index dataset_index(const StudyResult& result, const std::string& name) {
  for (std::size_t s = 0; s < result.datasets.size(); ++s) {
    if (result.datasets[s] == name) return static_cast<Eigen::Index>(s);
  }
  return -1;
}

void check_expected(const StudyResult& result, const Targets& targets,
                    std::vector<std::string>& failures) {
  const NamedTable expected = read_named_table(targets.expected_csv);
  for (const auto& [name, values] : expected.rows) {
    const Eigen::Index s = dataset_index(result, name);
    if (s < 0) {
      if (targets.subset) continue;
      failures.push_back(fmt::format("{}: data set {} was not run", targets.expected_csv, name));
      continue;
    }
    for (std::size_t j = 4; j < expected.header.size();
         ++j) {  // after dataset,rows,features,outliers
      Eigen::Index m = 0;
      try {
        m = method_index(result, expected.header[j]);
      } catch (const std::out_of_range&) {
        failures.push_back(
            fmt::format("{}: method {} was not run", targets.expected_csv, expected.header[j]));
        continue;
      }
      const double got = result.auc(s, m);
      if (!(std::abs(got - values[j]) <= targets.tolerance)) {
        failures.push_back(fmt::format(
            "{} {}: AUC {:.17g}, expected {:.17g} (|diff| {:.3g} > {:.3g})", name,
            expected.header[j], got, values[j], std::abs(got - values[j]), targets.tolerance));
      }
    }
  }
}

void check_pyod_reference(const StudyResult& result, const Targets& targets,
                          std::vector<std::string>& failures) {
  const NamedTable reference = read_named_table(targets.pyod_reference_csv);
  const std::size_t column = column_of(reference, "roc_auc_default", targets.pyod_reference_csv);
  const Eigen::Index pyod = method_index(result, "pyod");
  for (const auto& [name, values] : reference.rows) {
    const Eigen::Index s = dataset_index(result, name);
    if (s < 0) {
      if (targets.subset) continue;
      failures.push_back(
          fmt::format("{}: data set {} was not run", targets.pyod_reference_csv, name));
      continue;
    }
    const double got = result.auc(s, pyod);
    if (!(std::abs(got - values[column]) <= targets.tolerance)) {
      failures.push_back(fmt::format("{} pyod: AUC {:.17g}, PyOD's own {:.17g} (|diff| {:.3g})",
                                     name, got, values[column], std::abs(got - values[column])));
    }
  }
}

void check_invariants(const StudyResult& result, std::vector<std::string>& failures) {
  const double mean_default = mean_auc(result, "default");
  const double mean_pyod = mean_auc(result, "pyod");
  if (!(mean_default >= mean_pyod)) {
    failures.push_back(fmt::format("mean default AUC {:.6f} is below the PyOD mode's {:.6f}",
                                   mean_default, mean_pyod));
  }
  const Eigen::Index def = method_index(result, "default");
  const Eigen::Index def_rescaled = method_index(result, "default_rescaled");
  const Eigen::Index pyod = method_index(result, "pyod");
  const Eigen::Index pyod_rescaled = method_index(result, "pyod_rescaled");
  double pyod_change = 0.0;
  for (std::size_t s = 0; s < result.datasets.size(); ++s) {
    const auto row = static_cast<Eigen::Index>(s);
    const double change = std::abs(result.auc(row, def) - result.auc(row, def_rescaled));
    if (!(change < 1e-12)) {
      failures.push_back(fmt::format("{}: the default mode's AUC changes by {:.3g} under rescaling",
                                     result.datasets[s], change));
    }
    pyod_change =
        std::max(pyod_change, std::abs(result.auc(row, pyod) - result.auc(row, pyod_rescaled)));
  }
  if (!(pyod_change > 1e-3)) {
    failures.push_back(fmt::format(
        "the PyOD mode's AUC changes by at most {:.3g} under rescaling: is the rescaling a no-op?",
        pyod_change));
  }
}

}  // namespace

std::vector<std::string> check_targets(const StudyResult& result, const Targets& targets) {
  std::vector<std::string> failures;
  if (!targets.expected_csv.empty()) check_expected(result, targets, failures);
  if (!targets.pyod_reference_csv.empty()) check_pyod_reference(result, targets, failures);
  if (targets.published_pyod_mean) {
    const double mean = mean_auc(result, "pyod");
    if (!(std::abs(mean - *targets.published_pyod_mean) <= 5e-5)) {
      failures.push_back(
          fmt::format("mean PyOD-mode AUC {:.6f} does not round to the published {:.4f}", mean,
                      *targets.published_pyod_mean));
    }
  }
  if (targets.invariants) check_invariants(result, failures);
  return failures;
}

}  // namespace hbos::study
