#include "npy_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

namespace hbos::cli {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw NpyError(path + ": " + message);
}

/// The value of `key` in the header dict (`'key': value`), up to the next top-level comma.
std::string_view dict_value(const std::string& path, std::string_view header,
                            std::string_view key) {
  const std::string quoted = "'" + std::string(key) + "'";
  const std::size_t at = header.find(quoted);
  if (at == std::string_view::npos) fail(path, "the .npy header has no '" + std::string(key) + "'");
  // numpy would take the last of two; which one a writer meant is not knowable.
  if (header.find(quoted, at + quoted.size()) != std::string_view::npos)
    fail(path, "the .npy header names '" + std::string(key) + "' twice");
  std::size_t i = header.find(':', at + quoted.size());
  if (i == std::string_view::npos)
    fail(path, "malformed .npy header near '" + std::string(key) + "'");
  ++i;
  while (i < header.size() && header[i] == ' ') ++i;
  std::size_t end = i;
  int depth = 0;
  while (end < header.size() && (depth > 0 || (header[end] != ',' && header[end] != '}'))) {
    if (header[end] == '(') ++depth;
    if (header[end] == ')') --depth;
    ++end;
  }
  std::size_t stop = end;  // numpy's own writer puts no space before the comma; others may
  while (stop > i && header[stop - 1] == ' ') --stop;
  return header.substr(i, stop - i);
}

/// The dimensions of a shape tuple such as `(378, 30)`, `(378,)`.
std::vector<long long> parse_shape(const std::string& path, std::string_view text) {
  if (text.size() < 2 || text.front() != '(' || text.back() != ')')
    fail(path, "the .npy shape '" + std::string(text) + "' is not a tuple");
  std::vector<long long> dims;
  std::size_t i = 1;
  while (i + 1 < text.size()) {
    while (i + 1 < text.size() && (text[i] == ' ' || text[i] == ',')) ++i;
    if (i + 1 >= text.size()) break;
    long long v = 0;
    std::size_t digits = 0;
    while (i + 1 < text.size() && text[i] >= '0' && text[i] <= '9') {
      if (v > std::numeric_limits<long long>::max() / 10) fail(path, "the .npy shape overflows");
      v = v * 10 + (text[i] - '0');
      ++i;
      ++digits;
    }
    if (digits == 0)
      fail(path, "the .npy shape '" + std::string(text) + "' is not a tuple of sizes");
    dims.push_back(v);
  }
  return dims;
}

}  // namespace

NpyArray read_npy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
  std::array<char, 8> magic{};
  if (!in.read(magic.data(), magic.size()) || std::memcmp(magic.data(), "\x93NUMPY", 6) != 0)
    fail(path, "not a .npy file (no \\x93NUMPY magic)");
  const auto major = static_cast<unsigned char>(magic[6]);
  if (major < 1 || major > 3)
    fail(path,
         "unsupported .npy format version " + std::to_string(major) + " (1, 2 or 3 are read)");
  std::uint32_t header_len = 0;
  std::array<unsigned char, 4> len{};
  const std::streamsize len_size = major == 1 ? 2 : 4;
  if (!in.read(reinterpret_cast<char*>(len.data()), len_size)) fail(path, "truncated .npy header");
  for (std::streamsize i = len_size; i-- > 0;)
    header_len = (header_len << 8) | len[static_cast<std::size_t>(i)];
  if (header_len > (1U << 20))
    fail(path, "the .npy header claims " + std::to_string(header_len) + " bytes");
  std::string header(header_len, '\0');
  if (!in.read(header.data(), static_cast<std::streamsize>(header_len)))
    fail(path, "truncated .npy header");

  const std::string_view descr = dict_value(path, header, "descr");
  NpyArray out;
  if (descr == "'<f8'") {
    out.float32 = false;
  } else if (descr == "'<f4'") {
    out.float32 = true;
  } else {
    fail(path, "dtype " + std::string(descr) +
                   " is not supported (little-endian float64 '<f8' or float32 '<f4' are read)");
  }
  const std::string_view order = dict_value(path, header, "fortran_order");
  if (order != "False" && order != "True")
    fail(path, "fortran_order '" + std::string(order) + "' is not True or False");
  const bool fortran = order == "True";
  const std::vector<long long> dims = parse_shape(path, dict_value(path, header, "shape"));
  if (dims.empty() || dims.size() > 2)
    fail(path, "the array has " + std::to_string(dims.size()) + " dimensions (1 or 2 are read)");
  const long long rows = dims[0];
  const long long cols = dims.size() == 2 ? dims[1] : 1;
  if (rows <= 0 || cols <= 0) fail(path, "the array is empty");
  if (rows > std::numeric_limits<Eigen::Index>::max() / cols / 8)
    fail(path, "the array shape is too large");

  // The values go straight into the buffer kept: C order is the row-major matrix, Fortran
  // order the row-major store of its transpose.
  const auto count = static_cast<std::size_t>(rows * cols);
  const std::size_t width = out.float32 ? 4 : 8;
  auto truncated = [&] {
    fail(path, "truncated data: the header declares " + std::to_string(rows) + " x " +
                   std::to_string(cols) + " values of " + std::to_string(width) + " bytes");
  };
  // A header declaring more values than the file holds is refused before the buffer is taken.
  const std::streamoff at = in.tellg();
  std::error_code size_error;
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, size_error);
  if (!size_error && at >= 0 &&
      file_bytes - static_cast<std::uintmax_t>(at) < static_cast<std::uintmax_t>(count * width))
    truncated();
  RowStore store(static_cast<Eigen::Index>(fortran ? rows : cols));
  store.resize_rows(static_cast<Eigen::Index>(fortran ? cols : rows));
  if (!out.float32) {
    // The bytes of '<f8' are the doubles of a little-endian machine (as memcpy assumed before).
    if (!in.read(reinterpret_cast<char*>(store.data()), static_cast<std::streamsize>(count * 8)))
      truncated();
  } else {
    constexpr std::size_t kChunk = std::size_t{1} << 18;  // floats: 1 MiB at a time
    std::vector<float> chunk(std::min(count, kChunk));
    for (std::size_t done = 0; done < count;) {
      const std::size_t m = std::min(kChunk, count - done);
      if (!in.read(reinterpret_cast<char*>(chunk.data()), static_cast<std::streamsize>(m * 4)))
        truncated();
      for (std::size_t k = 0; k < m; ++k) store.data()[done + k] = static_cast<double>(chunk[k]);
      done += m;
    }
  }
  if (in.peek() != std::char_traits<char>::eof())
    fail(path, "trailing bytes after the " + std::to_string(count) + " declared values");
  out.values = DataMatrix(std::move(store), fortran);
  return out;
}

bool is_npy_path(const std::string& path) {
  constexpr std::string_view suffix = ".npy";
  if (path.size() >= suffix.size()) {
    bool same = true;  // the suffix in any case: x.NPY was parsed as CSV
    for (std::size_t k = 0; k < suffix.size(); ++k)
      same =
          same && std::tolower(static_cast<unsigned char>(path[path.size() - suffix.size() + k])) ==
                      suffix[k];
    if (same) return true;
  }
  // Or numpy's magic string, whatever the name (a regular file only: never standard input).
  std::error_code ec;
  if (path == "-" || !std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  char magic[6] = {};
  in.read(magic, sizeof magic);
  return in.gcount() == 6 && std::string_view(magic, 6) == "\x93NUMPY";
}

void refuse_csv_options(const std::string& path, const CsvOptions& csv) {
  const auto refuse = [&](const std::string& option, const std::string& why) {
    fail(path, option + " is for CSV input: " + why);
  };
  const std::string features_only =
      "a .npy array is all features (save it without the column, or use a CSV file)";
  if (!csv.label_column.empty()) refuse("--label-column " + csv.label_column, features_only);
  if (!csv.ignore_columns.empty()) refuse("--ignore-columns", features_only);
  const std::string no_text = "a .npy file has no header line and no delimiter";
  if (csv.header == HeaderMode::Present) refuse("--header", no_text);
  if (csv.header == HeaderMode::Absent) refuse("--no-header", no_text);
  if (csv.delimiter != CsvOptions{}.delimiter) refuse("--delimiter", no_text);
}

RowStore read_npy_rows(const std::string& path, const CsvOptions& csv) {
  refuse_csv_options(path, csv);
  DataMatrix x = std::move(read_npy(path).values);
  // The one-shot scorer fits one feature at a time, whose own errors know only the row: name
  // the value here, by row and column, as the CSV reader does by line and field.
  const auto view = x.matrix();
  for (Eigen::Index j = 0; j < view.cols(); ++j) {
    for (Eigen::Index i = 0; i < view.rows(); ++i) {
      if (!std::isfinite(view(i, j))) {
        fail(path, "row " + std::to_string(i) + ", column " + std::to_string(j) + " (x" +
                       std::to_string(j) + ") is not finite (" + std::to_string(view(i, j)) +
                       "); NaN and infinity are not allowed");
      }
    }
  }
  if (!x.column_major()) return std::move(x).release();
  RowStore rows(x.cols());
  rows.resize_rows(x.rows());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      rows.data(), x.rows(), x.cols()) = view;
  return rows;
}

DataMatrix read_data(const std::string& path, const CsvOptions& csv) {
  if (is_npy_path(path)) {
    refuse_csv_options(path, csv);
    return std::move(read_npy(path).values);
  }
  // Rows go into a RowStore as they are parsed; the layout stays the parser's, not copied, and
  // holds no made-up names for a file without a header (32 bytes a column).
  RowStore values;
  CsvOptions options = csv;
  options.default_names = false;
  CsvHandlers handlers;
  handlers.on_layout = [&](const CsvLayout& layout) { values = RowStore(layout.n_features()); };
  handlers.on_row = [&](const CsvRow& row) { values.append(row.features); };
  read_csv_rows(path, options, handlers);
  return DataMatrix(std::move(values), false);
}

}  // namespace hbos::cli
