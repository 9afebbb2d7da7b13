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
#include <istream>
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

  /// A line written by the caller: `line` must not hold a newline.
  void raw_line(std::string_view line) {
    text_.append(line);
    text_.push_back('\n');
  }

  /// Starts a line with `key` and returns the text for the caller to append the rest of the
  /// line to, ending it with '\n' (long lines built without a temporary).
  std::string& begin_line(std::string_view key) {
    text_.append(key);
    return text_;
  }

  [[nodiscard]] const std::string& text() const { return text_; }
  [[nodiscard]] std::string& text() { return text_; }

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
/// Every error is an InvalidArgument "<source>, line <n> (<key>): <what>". Lines are taken one
/// at a time, from text in memory or from a stream (a model file larger than memory allows is
/// read in one pass); the tokens a call returns stay valid until the next call.
class TextReader {
 public:
  TextReader(std::string_view text, std::string source) : source_(std::move(source)), text_(text) {}
  /// Reads from `stream`, which must outlive the reader.
  TextReader(std::istream& stream, std::string source)
      : source_(std::move(source)), stream_(&stream) {}

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
    std::string_view line;
    if (!next_line(line))
      throw InvalidArgument(concat(source_, ": the file ends after line ", next_, " where '", key,
                                   "' was expected (truncated?)"));
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
    std::string_view line;
    if (!next_line(line))
      throw InvalidArgument(concat(source_, ": the file ends after line ", next_,
                                   " where a value of '", field, "' was expected (truncated?)"));
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
    std::string_view line;
    while (next_line(line)) {
      for (const char c : line)
        if (!is_space(c))
          fail("end of file", concat("unexpected content after the model: '", shorten(line), "'"));
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

  /// The next line without its '\n' (a last line without one counts), or false at the end.
  bool next_line(std::string_view& line) {
    if (stream_ != nullptr) {
      if (!std::getline(*stream_, current_)) {
        if (stream_->bad())
          throw InvalidArgument(concat(source_, ": read error after line ", next_));
        return false;
      }
      line = current_;
    } else {
      if (position_ >= text_.size()) return false;
      std::size_t end = text_.find('\n', position_);
      if (end == std::string_view::npos) end = text_.size();
      line = text_.substr(position_, end - position_);
      position_ = end + 1;
    }
    ++next_;
    return true;
  }

  std::string source_;
  std::string_view text_;           // the text, when reading from memory
  std::size_t position_ = 0;        // where its next line starts
  std::istream* stream_ = nullptr;  // the stream, when reading from one
  std::string current_;             // the stream's current line
  std::size_t next_ = 0;            // lines read so far
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

/// Replaces `path` atomically by what is written to it: the content goes to a new temporary
/// file in the same directory (opened exclusively), renamed over `path` by commit(); on any
/// failure, or when destroyed without commit(), the temporary file is removed and `path` is left
/// as it was. No fsync (a crash of the process, not of the machine, is what this protects
/// against). Lets a large model file be written piece by piece instead of built in memory.
class AtomicFileWriter {
 public:
  /// \throws InvalidArgument naming the path and the system's reason.
  explicit AtomicFileWriter(std::string path) : path_(std::move(path)) {
    namespace fs = std::filesystem;
    require(!path_.empty(), "cannot write a model file to an empty path");
    std::error_code ec;
    require(!fs::is_directory(fs::path(path_), ec), "cannot write model file '", path_,
            "': it is a directory");
    const auto stamp = static_cast<unsigned long long>(
        std::chrono::steady_clock::now().time_since_epoch().count());
    for (unsigned attempt = 0; attempt < 100 && file_ == nullptr; ++attempt) {
      temp_ = concat(path_, ".tmp", stamp % 1000000007ULL, "-", attempt);
      file_ = std::fopen(temp_.c_str(), "wbx");  // x: fail if it exists (never share a temp file)
      if (file_ == nullptr && errno != EEXIST) break;
    }
    require(file_ != nullptr, "cannot create a temporary file next to model file '", path_,
            "': ", std::strerror(errno));
  }
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  ~AtomicFileWriter() { discard(); }

  /// Appends `content`. \throws InvalidArgument naming the path when it cannot be written.
  void write(std::string_view content) {
    require(file_ != nullptr, "model file '", path_, "' was already committed");
    if (content.empty() || std::fwrite(content.data(), 1, content.size(), file_) == content.size())
      return;
    const int error = errno;
    discard();
    throw InvalidArgument(concat("cannot write model file '", path_, "': ", std::strerror(error)));
  }

  /// Closes the temporary file and renames it over the path.
  /// \throws InvalidArgument naming the path when that fails (the path is then unchanged).
  void commit() {
    require(file_ != nullptr, "model file '", path_, "' was already committed");
    const bool closed = std::fclose(file_) == 0;
    const int close_errno = errno;
    file_ = nullptr;
    std::error_code ec;
    if (!closed) {
      std::filesystem::remove(temp_, ec);
      throw InvalidArgument(
          concat("cannot write model file '", path_, "': ", std::strerror(close_errno)));
    }
    std::filesystem::rename(temp_, std::filesystem::path(path_), ec);
    if (ec) {
      std::error_code ignored;
      std::filesystem::remove(temp_, ignored);
      throw InvalidArgument(concat("cannot write model file '", path_, "': ", ec.message()));
    }
  }

 private:
  void discard() noexcept {
    if (file_ == nullptr) return;
    std::fclose(file_);
    file_ = nullptr;
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
  }

  std::string path_;
  std::string temp_;
  std::FILE* file_ = nullptr;
};

/// Replaces `path` by `content` atomically (AtomicFileWriter).
/// \throws InvalidArgument naming the path and the system's reason.
inline void write_file_atomically(const std::string& path, std::string_view content) {
  AtomicFileWriter file(path);
  file.write(content);
  file.commit();
}

}  // namespace hbos::detail
