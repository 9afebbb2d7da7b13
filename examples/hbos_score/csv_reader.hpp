#pragma once
/// \file
/// A strict, fast reader for numeric CSV files (rows = samples), as the command-line tools need.
///
/// Accepted format:
/// - Cells separated by one delimiter character (default `,`); lines end in `\n` or `\r\n`; the
///   last line may or may not end in a line break; blank lines at the very end are ignored.
///   A UTF-8 byte-order mark at the start is skipped.
/// - An optional header line. In `HeaderMode::Auto` the first line is a header when at least one
///   of its cells is not a number; a header made only of numbers (`0,1,2`) must be requested
///   with `HeaderMode::Present`.
/// - Spaces and tabs around a cell are ignored (tabs only when the delimiter is not a tab). Any
///   cell may be double-quoted (RFC 4180, `""` for a quote inside); a quoted cell may not span
///   lines. A quoted data cell must still hold a number.
/// - Data cells are decimal floating-point numbers as `std::from_chars` reads them (`1`, `-2.5`,
///   `3e-7`, `.5`; a leading `+` is accepted too). Values too small for a double read as 0 or a
///   subnormal, as strtod does.
///
/// Rejected, with the file, line and column of the offending cell (`data.csv:7:13: ...`): an
/// empty input, a header without data rows, a row with more or fewer cells than the first line,
/// an empty cell, a cell that is not a number, NaN or infinity, a number beyond the range of a
/// double, a blank line between rows, an unterminated quote. Columns count bytes from 1, as
/// compilers do, and point at the start of the cell.
///
/// An optional label column (0/1 ground truth, 1 = outlier) is split off the features and
/// optional ignored columns (IDs) are skipped, so the feature matrix holds only what the model
/// should see.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace hbos::cli {

/// Whether the first line names the columns.
enum class HeaderMode {
  Auto,     ///< a header when at least one cell of the first line is not a number
  Present,  ///< the first line is a header
  Absent    ///< every line is data
};

/// How to read a CSV file.
struct CsvOptions {
  HeaderMode header = HeaderMode::Auto;  ///< header detection
  char delimiter = ',';                  ///< cell separator; not `"`, a space, a line break or NUL
  /// The column holding 0/1 ground-truth labels (1 = outlier), removed from the features: a
  /// column name, a 0-based index, or `last`. Empty: no label column.
  std::string label_column{};
  /// Columns to skip entirely (IDs, timestamps, an index column written by pandas), as
  /// selectors like `label_column`; their cells need not be numbers.
  std::vector<std::string> ignore_columns{};
  /// Whether CsvLayout::column_names is filled for a file without a header (`x<j>`). Readers
  /// that need only the values set it false: a file of 1e7 columns then saves 320 MB of names
  /// (messages still name column j `x<j>`; the names are made anyway when a label or ignored
  /// column is selected).
  bool default_names = true;
};

/// What the first line of a CSV file says about its columns (the part of a table that does not
/// grow with its rows).
struct CsvLayout {
  /// Names of every column of the file, in file order (`x<j>` where the file has no header or
  /// an empty header cell, j counting from 0). Empty for a file without a header read with
  /// CsvOptions::default_names false.
  std::vector<std::string> column_names;
  /// For each feature (a column that is neither the label nor ignored), its index among
  /// `column_names`.
  std::vector<std::size_t> feature_columns;
  /// Index of the label column among `column_names`, if one was requested.
  std::optional<std::size_t> label_column;
  /// Indices of the ignored columns among `column_names`, in the order they were requested.
  std::vector<std::size_t> ignored_columns;
  /// Whether the first line was taken as a header.
  bool has_header = false;
  /// Auto mode only: cells of the header line that look like numbers (a hint that the first line
  /// may be a corrupt data row rather than a header).
  std::vector<std::size_t> numeric_header_cells;

  [[nodiscard]] Eigen::Index n_features() const {
    return static_cast<Eigen::Index>(feature_columns.size());
  }
  /// Name of feature j (`x<j>` made up here when `column_names` was left empty).
  [[nodiscard]] std::string feature_name(Eigen::Index j) const {
    const std::size_t column = feature_columns[static_cast<std::size_t>(j)];
    return column_names.empty() ? "x" + std::to_string(column) : column_names[column];
  }
};

/// A numeric table read from CSV, whole.
struct CsvTable : CsvLayout {
  /// Rows = samples, columns = features (the label column removed), column-major.
  Eigen::MatrixXd features;
  /// The labels (0 or 1, 1 = outlier), one per row; empty without a label column.
  Eigen::VectorXi labels;
  /// The line each row was read from (1-based), for messages about rows.
  std::vector<std::size_t> row_lines;

  [[nodiscard]] Eigen::Index rows() const { return features.rows(); }
};

/// One data row as the streaming reader delivers it; valid only during the callback.
struct CsvRow {
  std::size_t line = 0;              ///< 1-based line of the file
  const double* features = nullptr;  ///< CsvLayout::n_features() values, in feature order
  int label = -1;                    ///< 0 or 1 with a label column, else -1
};

/// A malformed input: where it is and what is wrong. `what()` reads `source:line:column: message`
/// (or `source: message` when no position applies, e.g. a file that cannot be opened).
class CsvError : public std::runtime_error {
 public:
  CsvError(const std::string& source, std::size_t line, std::size_t column,
           const std::string& message);

  [[nodiscard]] const std::string& source() const { return source_; }
  /// 1-based line, 0 when no position applies.
  [[nodiscard]] std::size_t line() const { return line_; }
  /// 1-based byte column within the line, 0 when no position applies.
  [[nodiscard]] std::size_t column() const { return column_; }
  /// The message without the position prefix.
  [[nodiscard]] const std::string& message() const { return message_; }

 private:
  std::string source_;
  std::size_t line_;
  std::size_t column_;
  std::string message_;
};

/// The streaming reader's callbacks: `on_layout` once, after the first line, then `on_row` for
/// every data row in file order. Either may throw to stop the reading (the exception escapes).
struct CsvHandlers {
  std::function<void(const CsvLayout&)> on_layout;
  std::function<void(const CsvRow&)> on_row;
  /// Optional: after the last row, the layout is moved out (so that a caller keeping it need not
  /// hold a second copy of the names of millions of columns while reading).
  std::function<void(CsvLayout&&)> on_finish;
};

/// Streams CSV text row by row, with exactly the checks and messages of parse_csv. Memory: one
/// row of doubles and the layout, whatever the number of rows.
void parse_csv_rows(std::string_view text, const std::string& source, const CsvOptions& options,
                    const CsvHandlers& handlers);

/// Streams a file (`-`: standard input) row by row, reading it in 1 MiB blocks: the file is never
/// held in memory whole. A line may be as long as memory allows. Errors as read_csv.
void read_csv_rows(const std::string& path, const CsvOptions& options, const CsvHandlers& handlers);

/// Parses CSV text. `source` names the input in error messages.
/// \throws CsvError on malformed input; std::invalid_argument when `options.label_column` or
///         `options.ignore_columns` name no column, or `options.delimiter` is unusable.
[[nodiscard]] CsvTable parse_csv(std::string_view text, const std::string& source,
                                 const CsvOptions& options = {});

/// Reads and parses a file; `-` reads standard input (named `<stdin>` in messages).
/// \throws as parse_csv, and CsvError (without position) when the file cannot be read, does not
/// exist or is a directory.
[[nodiscard]] CsvTable read_csv(const std::string& path, const CsvOptions& options = {});

}  // namespace hbos::cli
