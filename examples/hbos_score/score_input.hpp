#pragma once
/// \file
/// A CSV file read for scoring, row by row, into the least memory that holds it: the layout,
/// one row-major buffer of values (8 bytes each) and the labels. Rows are on consecutive lines
/// (the reader allows no blank line or comment between rows), so no per-row line is stored.
/// A `.npy` file (npy_reader.hpp) gives the same, with columns x<j> and no labels.
///
/// This is also the entry point for other commands that read a whole CSV file of features
/// (e.g. fitting a model); a command that can work in one pass should call read_csv_rows
/// (csv_reader.hpp) with its own row callback instead.

#include <Eigen/Core>
#include <cstddef>
#include <string>

#include "csv_reader.hpp"
#include "row_store.hpp"

namespace hbos::cli {

struct ScoreInput : CsvLayout {
  /// rows x n_features(), row-major (score_table consumes it; rows() stays valid)
  RowStore values;
  Eigen::Index n_rows = 0;         ///< rows read
  Eigen::VectorXi labels;          ///< one per row with a label column, else empty
  std::size_t first_row_line = 0;  ///< 1-based line of row 0 (CSV)
  bool npy = false;  ///< read from a .npy file: rows are named by their 0-based index, not a line

  [[nodiscard]] Eigen::Index rows() const { return n_rows; }
  /// The 1-based line row i was read from.
  [[nodiscard]] std::size_t line_of(Eigen::Index i) const {
    return first_row_line + static_cast<std::size_t>(i);
  }
};

/// Reads `path` (`-`: standard input) with read_csv_rows, or with read_npy_rows when it names a
/// `.npy` file. \throws as read_csv or read_npy_rows.
[[nodiscard]] ScoreInput read_score_input(const std::string& path, const CsvOptions& options);

}  // namespace hbos::cli
