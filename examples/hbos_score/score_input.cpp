#include "score_input.hpp"

#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "npy_reader.hpp"

namespace hbos::cli {

namespace {

ScoreInput read_npy_input(const std::string& path, const CsvOptions& options) {
  ScoreInput input;
  input.npy = true;
  input.values = read_npy_rows(path, options);
  input.n_rows = input.values.rows();
  const auto d = static_cast<std::size_t>(input.values.cols());
  input.feature_columns.resize(d);
  std::iota(input.feature_columns.begin(), input.feature_columns.end(), std::size_t{0});
  // Names only where columns are chosen by name (--periodic-columns), as for a CSV file without
  // a header: messages make x<j> when they print it.
  if (options.default_names) {
    input.column_names.reserve(d);
    for (std::size_t j = 0; j < d; ++j) input.column_names.push_back("x" + std::to_string(j));
  }
  return input;
}

}  // namespace

ScoreInput read_score_input(const std::string& path, const CsvOptions& options) {
  if (is_npy_path(path)) return read_npy_input(path, options);
  ScoreInput input;
  std::vector<int> labels;
  CsvHandlers handlers;
  bool labelled = false;
  handlers.on_layout = [&](const CsvLayout& layout) {
    input.values = RowStore(layout.n_features());
    labelled = layout.label_column.has_value();
  };
  handlers.on_finish = [&](CsvLayout&& layout) {
    static_cast<CsvLayout&>(input) = std::move(layout);
  };
  handlers.on_row = [&](const CsvRow& row) {
    if (input.n_rows == 0) input.first_row_line = row.line;
    if (row.line != input.line_of(input.n_rows)) {
      throw std::logic_error("read_score_input: rows are not on consecutive lines");
    }
    input.values.append(row.features);
    ++input.n_rows;
    if (labelled) labels.push_back(row.label);
  };
  read_csv_rows(path, options, handlers);
  if (input.label_column) {
    input.labels =
        Eigen::Map<const Eigen::VectorXi>(labels.data(), static_cast<Eigen::Index>(labels.size()));
  }
  return input;
}

}  // namespace hbos::cli
