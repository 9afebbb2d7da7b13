#pragma once
/// \file
/// The line format of model files (hbos/model_file.hpp, hbos/pyod/model_file.hpp): writing
/// `key value...` lines with numbers in their exact shortest round-trip form, reading them back
/// strictly (every line's key checked in order, every token parsed completely, errors naming the
/// source, the line and the field), and replacing a file atomically.

#include <array>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "hbos/error.hpp"

namespace hbos::detail {

/// The message of a library exception without its "hbos: " prefix (for re-wrapping it).
inline std::string message_of(const std::exception& e) {
  const std::string_view what = e.what();
  constexpr std::string_view prefix = "hbos: ";
  return std::string(what.substr(0, prefix.size()) == prefix ? what.substr(prefix.size()) : what);
}

/// Appends `value` in the form a TextReader parses back to the same bits: integers in decimal,
/// floating-point values in the shortest decimal form that round-trips (std::to_chars).
template <class T>
void append_value(std::string& out, T value) {
  std::array<char, 64> buffer{};
  std::to_chars_result r{};
  if constexpr (std::is_same_v<T, bool>) {
    r = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value ? 1 : 0);
  } else {
    r = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  }
  out.append(buffer.data(), r.ptr);
}

/// Builds a model file: one `key value...` line at a time.
class TextWriter {
 public:
  /// `key` followed by each value, separated by single spaces.
  template <class... Values>
  void line(std::string_view key, const Values&... values) {
    text_.append(key);
    ((text_.push_back(' '), append_part(values)), ...);
    text_.push_back('\n');
  }

  /// A line holding just `value` (long arrays, one value a line).
  template <class T>
  void bare(const T& value) {
    append_value(text_, value);
    text_.push_back('\n');
  }

  /// `key n v_0 ... v_{n-1}`: an array with its length first.
  template <class Container>
  void array(std::string_view key, const Container& values) {
    text_.append(key);
    text_.push_back(' ');
    append_value(text_, static_cast<long long>(std::size(values)));
    for (const auto& v : values) {
      text_.push_back(' ');
      append_value(text_, v);
    }
    text_.push_back('\n');
  }

  [[nodiscard]] const std::string& text() const { return text_; }

 private:
  template <class T>
  void append_part(const T& v) {
    if constexpr (std::is_convertible_v<const T&, std::string_view>) {
      text_.append(std::string_view(v));
    } else {
      append_value(text_, v);
    }
  }

  std::string text_;
};

/// Reads a model file line by line, strictly: each call names the key the next line must have.
/// Every error is an InvalidArgument "<source>, line <n> (<key>): <what>".
class TextReader {
 public:
  TextReader(std::string_view text, std::string source) : source_(std::move(source)) {
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      lines_.push_back(text.substr(start, end - start));
      start = end + 1;
    }
  }

  /// Line number (1-based) of the line read last.
  [[nodiscard]] std::size_t line_number() const { return next_; }
  [[nodiscard]] const std::string& source() const { return source_; }

  /// Throws with the position of the line read last.
  [[noreturn]] void fail(std::string_view key, const std::string& what) const {
    throw InvalidArgument(concat(source_, ", line ", next_, " (", key, "): ", what));
  }

  /// The next line, which must start with `key`; returns its remaining tokens (`count` of them
  /// unless count is `any`).
  static constexpr std::size_t any = std::numeric_limits<std::size_t>::max();
  std::vector<std::string_view> expect(std::string_view key, std::size_t count = any) {
    if (next_ >= lines_.size())
      throw InvalidArgument(concat(source_, ": the file ends after line ", next_, " where '", key,
                                   "' was expected (truncated?)"));
    const std::string_view line = lines_[next_++];
    std::vector<std::string_view> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !is_space(line[i])) ++i;
      if (i > start) tokens.push_back(line.substr(start, i - start));
    }
    if (tokens.empty() || tokens.front() != key)
      fail(key, concat("expected a line starting with '", key, "', got '", shorten(line), "'"));
    tokens.erase(tokens.begin());
    if (count != any && tokens.size() != count)
      fail(key, concat("expected ", count, " value(s), got ", tokens.size()));
    return tokens;
  }

  /// A line holding one value and nothing else (see TextWriter::bare); `field` names it in errors.
  template <class T>
  T bare(std::string_view field) {
    if (next_ >= lines_.size())
      throw InvalidArgument(concat(source_, ": the file ends after line ", next_,
                                   " where a value of '", field, "' was expected (truncated?)"));
    std::string_view line = lines_[next_++];
    while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
    while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
    return parse<T>(field, line);
  }

  /// `key value`, parsed as T.
  template <class T>
  T value(std::string_view key) {
    const auto tokens = expect(key, 1);
    return parse<T>(key, tokens[0]);
  }

  /// `key n v_0 ... v_{n-1}`, parsed as T; n must not exceed `max_size`.
  template <class T>
  std::vector<T> array(std::string_view key, std::size_t max_size) {
    const auto tokens = expect(key);
    if (tokens.empty()) fail(key, "missing the array length");
    const auto n = parse<long long>(key, tokens[0]);
    if (n < 0 || static_cast<unsigned long long>(n) > max_size)
      fail(key, concat("array length ", n, " is outside [0, ", max_size, "]"));
    if (tokens.size() != static_cast<std::size_t>(n) + 1)
      fail(key, concat("declares ", n, " values but has ", tokens.size() - 1));
    std::vector<T> values;
    values.reserve(static_cast<std::size_t>(n));
    for (std::size_t i = 1; i < tokens.size(); ++i) values.push_back(parse<T>(key, tokens[i]));
    return values;
  }

  /// One of `names` (enumerators spelled in the file); returns its index.
  template <std::size_t N>
  std::size_t choice(std::string_view key, const std::array<std::string_view, N>& names) {
    const auto tokens = expect(key, 1);
    for (std::size_t i = 0; i < N; ++i)
      if (tokens[0] == names[i]) return i;
    std::string allowed;
    for (std::size_t i = 0; i < N; ++i) allowed += concat(i > 0 ? ", " : "", names[i]);
    fail(key, concat("'", shorten(tokens[0]), "' is not one of ", allowed));
  }

  /// Only blank lines may follow.
  void expect_end() {
    for (; next_ < lines_.size(); ++next_) {
      for (const char c : lines_[next_])
        if (!is_space(c)) {
          ++next_;
          fail("end of file",
               concat("unexpected content after the model: '", shorten(lines_[next_ - 1]), "'"));
        }
    }
  }

  /// Parses a whole token as T (bool: 0 or 1); floating-point values must be finite.
  template <class T>
  T parse(std::string_view key, std::string_view token) const {
    if constexpr (std::is_same_v<T, bool>) {
      if (token == "0") return false;
      if (token == "1") return true;
      fail(key, concat("'", shorten(token), "' is not 0 or 1"));
    } else {
      T v{};
      const char* end = token.data() + token.size();
      std::from_chars_result r{};
      if constexpr (std::is_floating_point_v<T>) {
        r = std::from_chars(token.data(), end, v, std::chars_format::general);
      } else {
        r = std::from_chars(token.data(), end, v);
      }
      if (r.ec == std::errc::result_out_of_range)
        fail(key, concat("'", shorten(token), "' is out of range"));
      if (r.ec != std::errc() || r.ptr != end)
        fail(key, concat("'", shorten(token), "' is not a ",
                         std::is_floating_point_v<T> ? "number" : "whole number"));
      if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(v)) fail(key, concat("'", shorten(token), "' is not finite"));
      }
      return v;
    }
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }
  static std::string shorten(std::string_view s) {
    return s.size() <= 60 ? std::string(s) : std::string(s.substr(0, 57)) + "...";
  }

  std::string source_;
  std::vector<std::string_view> lines_;
  std::size_t next_ = 0;
};

/// The whole content of the file at `path`. \throws InvalidArgument naming it if unreadable.
inline std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  require(static_cast<bool>(in), "cannot open model file '", path, "': ", std::strerror(errno));
  std::ostringstream content;
  content << in.rdbuf();
  require(!in.bad(), "cannot read model file '", path, "'");
  return content.str();
}

/// The first `max_lines` lines of the file at `path` (a header, without reading a large file).
inline std::string read_text_head(const std::string& path, int max_lines) {
  std::ifstream in(path, std::ios::binary);
  require(static_cast<bool>(in), "cannot open model file '", path, "': ", std::strerror(errno));
  std::string head, line;
  for (int i = 0; i < max_lines && std::getline(in, line); ++i) head += line + "\n";
  return head;
}

/// Replaces `path` by `content` atomically: written to a new temporary file in the same
/// directory (opened exclusively), then renamed over `path`; on any failure the temporary file
/// is removed and `path` is left as it was. No fsync (a crash of the process, not of the
/// machine, is what this protects against).
/// \throws InvalidArgument naming the path and the system's reason.
inline void write_file_atomically(const std::string& path, std::string_view content) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  require(!path.empty(), "cannot write a model file to an empty path");
  std::error_code ec;
  require(!fs::is_directory(target, ec), "cannot write model file '", path, "': it is a directory");
  const auto stamp =
      static_cast<unsigned long long>(std::chrono::steady_clock::now().time_since_epoch().count());
  std::string temp;
  std::FILE* file = nullptr;
  for (unsigned attempt = 0; attempt < 100 && file == nullptr; ++attempt) {
    temp = concat(path, ".tmp", stamp % 1000000007ULL, "-", attempt);
    file = std::fopen(temp.c_str(), "wbx");  // x: fail if it exists (never share a temp file)
    if (file == nullptr && errno != EEXIST) break;
  }
  require(file != nullptr, "cannot create a temporary file next to model file '", path,
          "': ", std::strerror(errno));
  const bool written =
      content.empty() || std::fwrite(content.data(), 1, content.size(), file) == content.size();
  const int write_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) {
    fs::remove(temp, ec);
    throw InvalidArgument(concat("cannot write model file '", path,
                                 "': ", std::strerror(written ? errno : write_errno)));
  }
  fs::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw InvalidArgument(concat("cannot write model file '", path, "': ", ec.message()));
  }
}

}  // namespace hbos::detail
