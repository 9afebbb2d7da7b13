#include "score_input.hpp"

#include <stdexcept>
#include <utility>
#include <vector>

namespace hbos::cli {

ScoreInput read_score_input(const std::string& path, const CsvOptions& options) {
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
