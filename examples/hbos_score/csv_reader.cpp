#include "csv_reader.hpp"

#include "common/shown_text.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>
#include <utility>

#include "column_selector.hpp"

namespace hbos::cli {

CsvError::CsvError(const std::string& source, std::size_t line, std::size_t column,
                   const std::string& message)
    : std::runtime_error(line > 0 ? source + ":" + std::to_string(line) + ":" +
                                        std::to_string(column) + ": " + message
                                  : source + ": " + message),
      source_(source),
      line_(line),
      column_(column),
      message_(message) {}

namespace {

/// One cell of a line: its text between the delimiters, without surrounding blanks and quotes
/// (a quoted cell keeps its doubled `""`), and where it starts.
struct Cell {
  std::string_view text;
  std::size_t column = 0;  // 1-based byte column of the cell's first character
  bool quoted = false;
};

/// Blanks around a cell are ignored; a tab is a blank unless it is the delimiter (TSV).
bool is_blank(char c, char delimiter) { return c == ' ' || (c == '\t' && delimiter != '\t'); }

/// A cell's text as it should appear in a message: quoted, control bytes escaped, long text cut.
std::string shown(std::string_view text) { return hbos::examples::shown_text(text); }

/// A quoted cell's content with `""` turned back into `"`.
std::string unquote(const Cell& cell) {
  if (!cell.quoted) return std::string(cell.text);
  std::string out;
  out.reserve(cell.text.size());
  for (std::size_t i = 0; i < cell.text.size(); ++i) {
    out += cell.text[i];
    if (cell.text[i] == '"') ++i;  // the second quote of a doubled pair
  }
  return out;
}

enum class NumberStatus { Ok, Empty, NotANumber, NotFinite, OutOfRange };

/// Parses a whole cell as a finite double (see the file comment of csv_reader.hpp for the syntax).
NumberStatus parse_number(std::string_view text, double& value) {
  if (text.empty()) return NumberStatus::Empty;
  std::string_view digits = text;
  // from_chars rejects a leading '+', which spreadsheets sometimes write; "+-1" stays invalid.
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') {
    digits.remove_prefix(1);
  }
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
  if (ptr != end || ec == std::errc::invalid_argument) return NumberStatus::NotANumber;
  if (ec == std::errc::result_out_of_range) {
    // from_chars reports underflow and overflow alike; strtod tells them apart. Underflow gives
    // 0 or a subnormal, which is a faithful reading of the text; overflow has no double.
    const std::string copy(digits);
    errno = 0;
    value = std::strtod(copy.c_str(), nullptr);
    return std::isinf(value) ? NumberStatus::OutOfRange : NumberStatus::Ok;
  }
  return std::isfinite(value) ? NumberStatus::Ok : NumberStatus::NotFinite;
}

/// The cells of one line, one at a time (quote-aware; quotes cannot span lines), so that a line
/// of ten million cells costs no per-cell memory.
class CellCursor {
 public:
  CellCursor(std::string_view line, char delimiter, const std::string& source, std::size_t line_no)
      : line_(line),
        delimiter_(delimiter),
        has_quote_(line.find('"') != std::string_view::npos),
        source_(source),
        line_no_(line_no) {}

  /// The next cell, or false after the last one (a trailing delimiter yields a final empty cell).
  bool next(Cell& cell) {
    if (done_) return false;
    const std::string_view line = line_;
    std::size_t pos = pos_;
    while (pos < line.size() && is_blank(line[pos], delimiter_)) ++pos;
    cell = Cell{};
    cell.column = pos + 1;
    std::size_t after;  // index just past the cell's content (and closing quote)
    if (has_quote_ && pos < line.size() && line[pos] == '"') {
      cell.quoted = true;
      std::size_t close = pos + 1;
      while (true) {
        close = line.find('"', close);
        if (close == std::string_view::npos) {
          throw CsvError(source_, line_no_, pos + 1,
                         "unterminated quoted cell (a quoted cell cannot span lines)");
        }
        if (close + 1 < line.size() && line[close + 1] == '"') {
          close += 2;  // a doubled quote inside the cell
          continue;
        }
        break;
      }
      cell.text = line.substr(pos + 1, close - pos - 1);
      after = close + 1;
      while (after < line.size() && is_blank(line[after], delimiter_)) ++after;
      if (after < line.size() && line[after] != delimiter_) {
        throw CsvError(
            source_, line_no_, after + 1,
            "unexpected " + shown(line.substr(after, 1)) +
                " after a closing quote (expected the delimiter or the end of the line)");
      }
    } else {
      after = line.find(delimiter_, pos);
      if (after == std::string_view::npos) after = line.size();
      std::size_t stop = after;
      while (stop > pos && is_blank(line[stop - 1], delimiter_)) --stop;
      cell.text = line.substr(pos, stop - pos);
    }
    if (after >= line.size()) {
      done_ = true;
    } else {
      pos_ = after + 1;  // past the delimiter
    }
    return true;
  }

 private:
  std::string_view line_;
  char delimiter_;
  bool has_quote_;
  const std::string& source_;
  std::size_t line_no_;
  std::size_t pos_ = 0;
  bool done_ = false;
};

/// Reads CSV lines one at a time and hands out the layout and the rows; one instance per input.
class Parser {
 public:
  Parser(const std::string& source, const CsvOptions& options, const CsvHandlers& handlers)
      : source_(source), options_(options), handlers_(handlers) {
    const char delimiter = options_.delimiter;
    if (delimiter == '"' || delimiter == ' ' || delimiter == '\n' || delimiter == '\r' ||
        delimiter == '\0') {
      throw std::invalid_argument(
          "the CSV delimiter cannot be a quote, a space, a line break or NUL");
    }
  }

  /// One line without its line break (a final '\r' is removed here).
  void feed(std::string_view line) {
    ++line_no_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const char delimiter = options_.delimiter;
    if (line.find_first_not_of(delimiter == '\t' ? " " : " \t") == std::string_view::npos) {
      if (blank_line_ == 0) blank_line_ = line_no_;
      return;
    }
    if (blank_line_ != 0) {
      throw CsvError(source_, blank_line_, 1,
                     "blank line between rows (only blank lines at the end are ignored)");
    }
    if (first_) {
      // A file whose lines end in CR alone reads as one line with the rows inside it, and was
      // then reported as "no data rows after the header".
      if (const auto cr = line.find('\r');
          cr != std::string_view::npos && line.find('"') == std::string_view::npos) {
        throw CsvError(source_, line_no_, cr + 1,
                       "a carriage return inside the first line: lines that end in CR alone (as "
                       "classic Mac OS wrote them) are not read; convert them to LF or CRLF");
      }
      first_ = false;
      if (start_table(line)) return;
    }
    add_row(line);
  }

  /// After the last line.
  void finish() {
    if (first_) throw CsvError(source_, 1, 1, "empty input: no header and no data rows");
    if (rows_ == 0) throw CsvError(source_, line_no_ + 1, 1, "no data rows after the header");
    if (handlers_.on_finish) handlers_.on_finish(std::move(layout_));
  }

 private:
  /// Sets up columns from the first line; returns true when that line is a header.
  bool start_table(std::string_view line) {
    std::size_t n_columns = 0;
    bool header = options_.header == HeaderMode::Present;
    {
      CellCursor cells(line, options_.delimiter, source_, line_no_);
      Cell cell;
      while (cells.next(cell)) {
        ++n_columns;
        if (options_.header != HeaderMode::Auto) continue;
        double value = 0.0;
        const NumberStatus status = parse_number(cell.text, value);
        if (cell.quoted || status == NumberStatus::NotANumber) {
          header = true;
        } else if (status == NumberStatus::Ok) {
          layout_.numeric_header_cells.push_back(n_columns);
        }
      }
    }
    if (!header) layout_.numeric_header_cells.clear();
    layout_.has_header = header;
    const bool names = header || options_.default_names || !options_.label_column.empty() ||
                       !options_.ignore_columns.empty();
    if (names) {
      layout_.column_names.resize(n_columns);
      CellCursor cells(line, options_.delimiter, source_, line_no_);
      Cell cell;
      for (std::size_t j = 0; j < n_columns && cells.next(cell); ++j) {
        std::string name = header ? unquote(cell) : std::string();
        layout_.column_names[j] = name.empty() ? "x" + std::to_string(j) : std::move(name);
      }
    }
    if (!options_.label_column.empty()) {
      try {
        layout_.label_column = select_column(options_.label_column, layout_.column_names);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(source_ + ": label column: " + e.what());
      }
    }
    ignored_.assign(n_columns, false);
    for (const std::string& selector : options_.ignore_columns) {
      std::size_t j = 0;
      try {
        j = select_column(selector, layout_.column_names);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(source_ + ": ignored column: " + e.what());
      }
      if (layout_.label_column == j) {
        throw std::invalid_argument(source_ + ": column \"" + layout_.column_names[j] +
                                    "\" cannot be both the label column and ignored");
      }
      ignored_[j] = true;
      layout_.ignored_columns.push_back(j);
    }
    for (std::size_t j = 0; j < n_columns; ++j) {
      if (layout_.label_column != j && !ignored_[j]) layout_.feature_columns.push_back(j);
    }
    if (layout_.feature_columns.empty()) {
      throw CsvError(source_, line_no_, 1,
                     "no feature columns left (every column is the label column or ignored)");
    }
    n_columns_ = n_columns;
    first_line_ = line_no_;
    values_.resize(layout_.feature_columns.size());
    if (handlers_.on_layout) handlers_.on_layout(layout_);
    return header;
  }

  /// Parses `line` as one data row and hands it on.
  void add_row(std::string_view line) {
    // First the cell count, so that a row of the wrong width is reported as such even when one
    // of its cells is also bad (as a reader counting fields first would).
    std::size_t count = 0;
    std::size_t extra_column = 0;  // where the first cell beyond n_columns_ starts
    {
      CellCursor cells(line, options_.delimiter, source_, line_no_);
      Cell cell;
      while (cells.next(cell)) {
        if (count == n_columns_) extra_column = cell.column;
        ++count;
      }
    }
    if (count != n_columns_) {
      const std::size_t column = count > n_columns_ ? extra_column : line.size() + 1;
      throw CsvError(source_, line_no_, column,
                     "row has " + std::to_string(count) + " cells but line " +
                         std::to_string(first_line_) + " has " + std::to_string(n_columns_));
    }
    CellCursor cells(line, options_.delimiter, source_, line_no_);
    Cell cell;
    CsvRow row;
    row.line = line_no_;
    std::size_t feature = 0;
    for (std::size_t j = 0; j < n_columns_ && cells.next(cell); ++j) {
      if (ignored_[j]) continue;  // e.g. an ID column: not even required to be a number
      double value = 0.0;
      const NumberStatus status =
          cell.quoted ? parse_number(unquote(cell), value) : parse_number(cell.text, value);
      if (status != NumberStatus::Ok) fail_cell(cell, j, status);
      if (layout_.label_column == j) {
        if (value != 0.0 && value != 1.0) {
          throw CsvError(source_, line_no_, cell.column,
                         "label " + shown(cell.text) + " is neither 0 nor 1 (" + where(j) +
                             "; 1 marks an outlier)");
        }
        row.label = value == 1.0 ? 1 : 0;
      } else {
        values_[feature++] = value;
      }
    }
    row.features = values_.data();
    ++rows_;
    if (handlers_.on_row) handlers_.on_row(row);
  }

  /// "field 3, \"x2\"": which cell, for messages.
  std::string where(std::size_t j) const {
    const std::string name =
        layout_.column_names.empty() ? "x" + std::to_string(j) : layout_.column_names[j];
    return "field " + std::to_string(j + 1) + ", \"" + name + "\"";
  }

  [[noreturn]] void fail_cell(const Cell& cell, std::size_t j, NumberStatus status) const {
    std::string message;
    switch (status) {
      case NumberStatus::Empty:
        message = "empty cell (" + where(j) + "); missing values are not supported";
        break;
      case NumberStatus::NotFinite:
        message = shown(cell.text) + " is not a finite number (" + where(j) +
                  "); NaN and infinity are not allowed";
        break;
      case NumberStatus::OutOfRange:
        message = shown(cell.text) + " is beyond the range of a double (" + where(j) + ")";
        break;
      default:
        message = shown(cell.text) + " is not a number (" + where(j) + ")";
        break;
    }
    throw CsvError(source_, line_no_, cell.column, message);
  }

  const std::string& source_;
  const CsvOptions& options_;
  const CsvHandlers& handlers_;
  CsvLayout layout_;
  std::vector<bool> ignored_;  // per column of the file
  std::size_t line_no_ = 0;
  std::size_t blank_line_ = 0;  // the first blank line after the last row, if any
  bool first_ = true;
  std::size_t n_columns_ = 0;
  std::size_t first_line_ = 0;
  std::size_t rows_ = 0;
  std::vector<double> values_;  // the current row's features
};

constexpr std::string_view kBom = "\xEF\xBB\xBF";

/// Feeds every line of `text` (a complete input) to `parser`.
void feed_text(std::string_view text, Parser& parser) {
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t newline = text.find('\n', pos);
    const std::size_t end = newline == std::string_view::npos ? text.size() : newline;
    parser.feed(text.substr(pos, end - pos));
    pos = newline == std::string_view::npos ? text.size() : newline + 1;
  }
  parser.finish();
}

/// Collects streamed rows into a CsvTable.
struct TableCollector {
  CsvTable& table;
  std::vector<double> values;  // row-major
  std::vector<int> labels;

  CsvHandlers handlers() {
    return {[this](const CsvLayout& layout) { static_cast<CsvLayout&>(table) = layout; },
            [this](const CsvRow& row) {
              values.insert(values.end(), row.features, row.features + table.n_features());
              if (table.label_column) labels.push_back(row.label);
              table.row_lines.push_back(row.line);
            },
            {}};
  }

  /// Moves the row-major values into the column-major feature matrix.
  void finish() {
    const auto rows = static_cast<Eigen::Index>(table.row_lines.size());
    const auto cols = table.n_features();
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    table.features = Eigen::Map<const RowMajor>(values.data(), rows, cols);
    if (table.label_column) table.labels = Eigen::Map<const Eigen::VectorXi>(labels.data(), rows);
  }
};

}  // namespace

void parse_csv_rows(std::string_view text, const std::string& source, const CsvOptions& options,
                    const CsvHandlers& handlers) {
  Parser parser(source, options, handlers);
  feed_text(text, parser);
}

void read_csv_rows(const std::string& path, const CsvOptions& options,
                   const CsvHandlers& handlers) {
  const bool from_stdin = path == "-";
  const std::string source = from_stdin ? "<stdin>" : path;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> owned(nullptr, &std::fclose);
  std::FILE* file = stdin;
  if (!from_stdin) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
      throw CsvError(source, 0, 0, "is a directory, not a CSV file");
    }
    owned.reset(std::fopen(path.c_str(), "rb"));
    if (!owned) {
      throw CsvError(source, 0, 0, "cannot open: " + std::generic_category().message(errno));
    }
    file = owned.get();
  }
  Parser parser(source, options, handlers);
  std::string carry;  // the unfinished last line of the blocks read so far
  std::vector<char> buffer(std::size_t{1} << 20);
  bool start = true;
  while (true) {
    const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), file);
    std::string_view block(buffer.data(), got);
    if (start && got > 0) {
      // The BOM may straddle blocks only in a file shorter than 3 bytes: then it is no BOM.
      if (block.substr(0, kBom.size()) == kBom) block.remove_prefix(kBom.size());
      start = false;
    }
    std::size_t pos = 0;
    while (true) {
      const std::size_t newline = block.find('\n', pos);
      if (newline == std::string_view::npos) break;
      if (carry.empty()) {
        parser.feed(block.substr(pos, newline - pos));
      } else {
        carry.append(block.substr(pos, newline - pos));
        parser.feed(carry);
        carry.clear();
      }
      pos = newline + 1;
    }
    carry.append(block.substr(pos));
    if (got < buffer.size()) break;
  }
  if (std::ferror(file)) {
    throw CsvError(source, 0, 0, "cannot read: " + std::generic_category().message(errno));
  }
  if (!carry.empty()) parser.feed(carry);
  parser.finish();
}

CsvTable parse_csv(std::string_view text, const std::string& source, const CsvOptions& options) {
  CsvTable table;
  TableCollector collector{table, {}, {}};
  const CsvHandlers handlers = collector.handlers();
  parse_csv_rows(text, source, options, handlers);
  collector.finish();
  return table;
}

CsvTable read_csv(const std::string& path, const CsvOptions& options) {
  CsvTable table;
  TableCollector collector{table, {}, {}};
  const CsvHandlers handlers = collector.handlers();
  read_csv_rows(path, options, handlers);
  collector.finish();
  return table;
}

}  // namespace hbos::cli
