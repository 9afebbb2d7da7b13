#include "csv_reader.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <system_error>

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
std::string shown(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\r') {
      out += "\\r";
    } else if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned>(c));
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > kMax) out += "...";
  return out + "\"";
}

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

/// Reads CSV text line by line; one instance per parse.
class Parser {
 public:
  Parser(std::string_view text, const std::string& source, const CsvOptions& options)
      : text_(text), source_(source), options_(options) {}

  CsvTable run() {
    const char delimiter = options_.delimiter;
    if (delimiter == '"' || delimiter == ' ' || delimiter == '\n' || delimiter == '\r' ||
        delimiter == '\0') {
      throw std::invalid_argument(
          "the CSV delimiter cannot be a quote, a space, a line break or NUL");
    }
    static constexpr std::string_view kBom = "\xEF\xBB\xBF";
    if (text_.substr(0, kBom.size()) == kBom) text_.remove_prefix(kBom.size());

    CsvTable table;
    std::size_t pos = 0;
    std::size_t line_no = 0;
    std::size_t blank_line = 0;  // the first blank line after the last row, if any
    bool first = true;
    while (pos < text_.size()) {
      ++line_no;
      const std::size_t newline = text_.find('\n', pos);
      const std::size_t next = newline == std::string_view::npos ? text_.size() : newline + 1;
      std::size_t end = newline == std::string_view::npos ? text_.size() : newline;
      if (end > pos && text_[end - 1] == '\r') --end;
      const std::string_view line = text_.substr(pos, end - pos);
      pos = next;

      if (line.find_first_not_of(delimiter == '\t' ? " " : " \t") == std::string_view::npos) {
        if (blank_line == 0) blank_line = line_no;
        continue;
      }
      if (blank_line != 0) {
        throw CsvError(source_, blank_line, 1,
                       "blank line between rows (only blank lines at the end are ignored)");
      }
      split(line, line_no);
      if (first) {
        first = false;
        if (start_table(table, line_no)) continue;
      }
      add_row(table, line_no);
    }
    if (first) throw CsvError(source_, 1, 1, "empty input: no header and no data rows");
    if (table.row_lines.empty()) {
      throw CsvError(source_, line_no + 1, 1, "no data rows after the header");
    }
    finish(table);
    return table;
  }

 private:
  /// Splits `line` into cells_ (quote-aware; quotes cannot span lines).
  void split(std::string_view line, std::size_t line_no) {
    cells_.clear();
    const char delimiter = options_.delimiter;
    const bool has_quote = line.find('"') != std::string_view::npos;
    std::size_t pos = 0;
    while (true) {
      while (pos < line.size() && is_blank(line[pos], delimiter)) ++pos;
      Cell cell;
      cell.column = pos + 1;
      std::size_t after;  // index just past the cell's content (and closing quote)
      if (has_quote && pos < line.size() && line[pos] == '"') {
        cell.quoted = true;
        std::size_t close = pos + 1;
        while (true) {
          close = line.find('"', close);
          if (close == std::string_view::npos) {
            throw CsvError(source_, line_no, pos + 1,
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
        while (after < line.size() && is_blank(line[after], delimiter)) ++after;
        if (after < line.size() && line[after] != delimiter) {
          throw CsvError(
              source_, line_no, after + 1,
              "unexpected " + shown(line.substr(after, 1)) +
                  " after a closing quote (expected the delimiter or the end of the line)");
        }
      } else {
        after = line.find(delimiter, pos);
        if (after == std::string_view::npos) after = line.size();
        std::size_t stop = after;
        while (stop > pos && is_blank(line[stop - 1], delimiter)) --stop;
        cell.text = line.substr(pos, stop - pos);
      }
      cells_.push_back(cell);
      if (after >= line.size()) break;
      pos = after + 1;  // past the delimiter; a trailing delimiter yields a final empty cell
    }
    line_length_ = line.size();
  }

  /// Sets up columns from the first line's cells; returns true when that line is a header.
  bool start_table(CsvTable& table, std::size_t line_no) {
    const std::size_t n_columns = cells_.size();
    bool header = options_.header == HeaderMode::Present;
    if (options_.header == HeaderMode::Auto) {
      for (std::size_t j = 0; j < n_columns; ++j) {
        double value = 0.0;
        const NumberStatus status = parse_number(cells_[j].text, value);
        if (cells_[j].quoted || status == NumberStatus::NotANumber) {
          header = true;
        } else if (status == NumberStatus::Ok) {
          table.numeric_header_cells.push_back(j + 1);
        }
      }
      if (!header) table.numeric_header_cells.clear();
    }
    table.has_header = header;
    table.column_names.resize(n_columns);
    for (std::size_t j = 0; j < n_columns; ++j) {
      std::string name = header ? unquote(cells_[j]) : std::string();
      table.column_names[j] = name.empty() ? "x" + std::to_string(j) : std::move(name);
    }
    if (!options_.label_column.empty()) {
      try {
        table.label_column = select_column(options_.label_column, table.column_names);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(source_ + ": label column: " + e.what());
      }
    }
    ignored_.assign(n_columns, false);
    for (const std::string& selector : options_.ignore_columns) {
      std::size_t j = 0;
      try {
        j = select_column(selector, table.column_names);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(source_ + ": ignored column: " + e.what());
      }
      if (table.label_column == j) {
        throw std::invalid_argument(source_ + ": column \"" + table.column_names[j] +
                                    "\" cannot be both the label column and ignored");
      }
      ignored_[j] = true;
      table.ignored_columns.push_back(j);
    }
    for (std::size_t j = 0; j < n_columns; ++j) {
      if (table.label_column != j && !ignored_[j]) table.feature_columns.push_back(j);
    }
    if (table.feature_columns.empty()) {
      throw CsvError(source_, line_no, 1,
                     "no feature columns left (every column is the label column or ignored)");
    }
    n_columns_ = n_columns;
    first_line_ = line_no;
    return header;
  }

  /// Parses cells_ as one data row.
  void add_row(CsvTable& table, std::size_t line_no) {
    if (cells_.size() != n_columns_) {
      const std::size_t column =
          cells_.size() > n_columns_ ? cells_[n_columns_].column : line_length_ + 1;
      throw CsvError(source_, line_no, column,
                     "row has " + std::to_string(cells_.size()) + " cells but line " +
                         std::to_string(first_line_) + " has " + std::to_string(n_columns_));
    }
    for (std::size_t j = 0; j < n_columns_; ++j) {
      if (ignored_[j]) continue;  // e.g. an ID column: not even required to be a number
      const Cell& cell = cells_[j];
      double value = 0.0;
      const NumberStatus status =
          cell.quoted ? parse_number(unquote(cell), value) : parse_number(cell.text, value);
      if (status != NumberStatus::Ok) fail_cell(table, line_no, j, status);
      if (table.label_column == j) {
        if (value != 0.0 && value != 1.0) {
          throw CsvError(source_, line_no, cell.column,
                         "label " + shown(cell.text) + " is neither 0 nor 1 (" + where(table, j) +
                             "; 1 marks an outlier)");
        }
        labels_.push_back(value == 1.0 ? 1 : 0);
      } else {
        values_.push_back(value);
      }
    }
    table.row_lines.push_back(line_no);
  }

  /// "field 3, \"x2\"": which cell, for messages.
  static std::string where(const CsvTable& table, std::size_t j) {
    return "field " + std::to_string(j + 1) + ", \"" + table.column_names[j] + "\"";
  }

  [[noreturn]] void fail_cell(const CsvTable& table, std::size_t line_no, std::size_t j,
                              NumberStatus status) const {
    const Cell& cell = cells_[j];
    std::string message;
    switch (status) {
      case NumberStatus::Empty:
        message = "empty cell (" + where(table, j) + "); missing values are not supported";
        break;
      case NumberStatus::NotFinite:
        message = shown(cell.text) + " is not a finite number (" + where(table, j) +
                  "); NaN and infinity are not allowed";
        break;
      case NumberStatus::OutOfRange:
        message = shown(cell.text) + " is beyond the range of a double (" + where(table, j) + ")";
        break;
      default:
        message = shown(cell.text) + " is not a number (" + where(table, j) + ")";
        break;
    }
    throw CsvError(source_, line_no, cell.column, message);
  }

  /// Moves the row-major values into the column-major feature matrix.
  void finish(CsvTable& table) {
    const auto rows = static_cast<Eigen::Index>(table.row_lines.size());
    const auto cols = static_cast<Eigen::Index>(table.feature_columns.size());
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    table.features = Eigen::Map<const RowMajor>(values_.data(), rows, cols);
    if (table.label_column) {
      table.labels = Eigen::Map<const Eigen::VectorXi>(labels_.data(), rows);
    }
  }

  std::string_view text_;
  const std::string& source_;
  const CsvOptions& options_;
  std::vector<Cell> cells_;
  std::vector<bool> ignored_;  // per column of the file
  std::size_t line_length_ = 0;
  std::size_t n_columns_ = 0;
  std::size_t first_line_ = 0;
  std::vector<double> values_;
  std::vector<int> labels_;
};

}  // namespace

CsvTable parse_csv(std::string_view text, const std::string& source, const CsvOptions& options) {
  return Parser(text, source, options).run();
}

CsvTable read_csv(const std::string& path, const CsvOptions& options) {
  const bool from_stdin = path == "-";
  const std::string source = from_stdin ? "<stdin>" : path;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> owned(nullptr, &std::fclose);
  std::FILE* file = stdin;
  if (!from_stdin) {
    owned.reset(std::fopen(path.c_str(), "rb"));
    if (!owned) {
      throw CsvError(source, 0, 0, "cannot open: " + std::generic_category().message(errno));
    }
    file = owned.get();
  }
  std::string text;
  char buffer[1 << 16];
  while (true) {
    const std::size_t got = std::fread(buffer, 1, sizeof buffer, file);
    text.append(buffer, got);
    if (got < sizeof buffer) break;
  }
  if (std::ferror(file)) {
    throw CsvError(source, 0, 0, "cannot read: " + std::generic_category().message(errno));
  }
  return parse_csv(text, source, options);
}

}  // namespace hbos::cli
