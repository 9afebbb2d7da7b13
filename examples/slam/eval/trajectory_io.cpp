#include "eval/trajectory_io.hpp"

#include "common/atomic_file.hpp"
#include "common/shown_text.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>

namespace hbos::slam {

namespace {

constexpr std::array<const char*, 8> kFieldNames = {"t", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};

// The TUM scripts turn ',' and '\t' into spaces and strip each token, so all of these separate
// fields; '\r' matters for files written on Windows.
bool is_separator(char c) {
  return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\v' || c == '\f';
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_separator(line[i])) ++i;
    const std::size_t begin = i;
    while (i < line.size() && !is_separator(line[i])) ++i;
    if (i > begin) fields.push_back(line.substr(begin, i - begin));
  }
  return fields;
}

// std::from_chars is locale-independent and correctly rounded, like Python's float(); it does
// not take a leading '+', which Python does, so skip one.
bool parse_double(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && text.front() == '-') return false;  // "+-1" is not a number
  }
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ptr != end) return false;
  if (ec == std::errc::result_out_of_range) {
    // Python gives inf for "1e999" and 0 for "1e-999"; strtod does the same, and the caller
    // then reports the overflow as "not finite".
    const std::string copy(text);
    value = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
}

std::string location(const std::string& name, Eigen::Index line) {
  return name + ":" + std::to_string(line);
}

/// Stamps are seconds: Unix times (TUM, Bonn: ~1.3e9) or seconds from the start. Beyond 1e12 s
/// (31,700 years) a stamp is a corrupted field, and differences of such stamps lose every digit
/// of a frame period (1e300 - 1e300 is 0, 1e300 * 30 Hz overflows a frame count).
constexpr double kMaxAbsStamp = 1e12;  ///< [s]
/// Positions beyond 1e9 m (beyond any map on Earth, UTM included) are corrupted fields; their
/// squares in the alignment would overflow to inf.
constexpr double kMaxAbsPosition = 1e9;  ///< [m]

/// Throws unless `path` names something that can be read as a file (a directory opens as an
/// ifstream on Linux and then fails with a bare "read error").
void require_readable_file(const std::string& path, const char* what) {
  std::error_code error;
  detail::require(!std::filesystem::is_directory(path, error), path, ": is a directory, not ",
                  what);
  detail::require(std::filesystem::exists(path, error), path, ": ", what, " does not exist");
}

// A field as a message shows it: quoted, cut at 40 characters, and a byte no number holds (a
// byte order mark, a carriage return) escaped rather than printed as nothing.
std::string shown(std::string_view field) { return examples::shown_text(field, '\'', true); }

struct ParsedLine {
  Eigen::Index line = 0;
  std::string stamp_text;  // as written, for messages (the double prints differently)
  std::array<double, 8> values{};
};

ParsedLine parse_pose_line(const std::vector<std::string_view>& fields, const std::string& name,
                           Eigen::Index line_number, const ReadOptions& options) {
  const std::string where = location(name, line_number);
  detail::require(fields.size() == kFieldNames.size(), where, ": expected 8 fields ",
                  "(t tx ty tz qx qy qz qw), found ", fields.size());
  ParsedLine parsed;
  parsed.line = line_number;
  parsed.stamp_text = std::string(fields[0]);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    double value = 0.0;
    detail::require(parse_double(fields[k], value), where, ": field '", kFieldNames[k],
                    "' is not a number: ", shown(fields[k]));
    detail::require(std::isfinite(value), where, ": field '", kFieldNames[k],
                    "' is not finite: ", shown(fields[k]));
    parsed.values[k] = value;
  }
  for (std::size_t k = 1; k <= 3; ++k) {
    detail::require(std::abs(parsed.values[k]) <= kMaxAbsPosition, where, ": field '",
                    kFieldNames[k], "' = '", fields[k],
                    "' is not a plausible position in metres (|x| must be <= 1e9)");
  }
  detail::require(std::abs(parsed.values[0]) <= kMaxAbsStamp, where, ": stamp '", fields[0],
                  "' is not a plausible time in seconds (|t| must be <= 1e12)");
  const double norm =
      std::sqrt(parsed.values[4] * parsed.values[4] + parsed.values[5] * parsed.values[5] +
                parsed.values[6] * parsed.values[6] + parsed.values[7] * parsed.values[7]);
  detail::require(std::abs(norm - 1.0) <= options.max_quaternion_norm_error, where,
                  ": quaternion (qx qy qz qw) = (", fields[4], " ", fields[5], " ", fields[6], " ",
                  fields[7], ") has norm ", norm, ", farther than ",
                  options.max_quaternion_norm_error, " from 1");
  return parsed;
}

// kLikeTumScripts: a dict keyed by stamp, then sorted keys. A stable sort keeps equal stamps in
// file order, so the last of each run is the line the dict would hold.
std::vector<ParsedLine> sort_keep_last(std::vector<ParsedLine> lines, const std::string& name,
                                       ReadReport& report) {
  const bool sorted = std::is_sorted(lines.begin(), lines.end(), [](const auto& a, const auto& b) {
    return a.values[0] < b.values[0];
  });
  if (!sorted) {
    report.reordered = true;
    report.warnings.push_back(name +
                              ": lines are not in stamp order; sorted them like the TUM "
                              "scripts");
    std::stable_sort(lines.begin(), lines.end(),
                     [](const auto& a, const auto& b) { return a.values[0] < b.values[0]; });
  }
  std::vector<ParsedLine> kept;
  kept.reserve(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const bool repeated_later =
        i + 1 < lines.size() && lines[i + 1].values[0] == lines[i].values[0];
    if (repeated_later) {
      ++report.duplicates_dropped;
      report.warnings.push_back(fmt::format(
          "{}: stamp {} repeats at line {}; dropped this line and kept the last one, like the "
          "TUM scripts",
          location(name, lines[i].line), lines[i].stamp_text, lines[i + 1].line));
      continue;
    }
    kept.push_back(std::move(lines[i]));
  }
  return kept;
}

}  // namespace

Trajectory parse_tum_trajectory(std::istream& in, const std::string& name,
                                const ReadOptions& options, ReadReport* report) {
  detail::require(
      options.max_quaternion_norm_error >= 0.0 && std::isfinite(options.max_quaternion_norm_error),
      "ReadOptions::max_quaternion_norm_error must be finite and >= 0, got ",
      options.max_quaternion_norm_error);
  ReadReport local_report;
  ReadReport& rep = report != nullptr ? *report : local_report;
  rep = ReadReport{};

  std::vector<ParsedLine> lines;
  std::string text;
  Eigen::Index line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    const std::vector<std::string_view> fields = split_fields(text);
    if (fields.empty()) {
      ++rep.blank_lines;
      continue;
    }
    if (fields.front().front() == '#') {
      ++rep.comment_lines;
      continue;
    }
    ParsedLine parsed = parse_pose_line(fields, name, line_number, options);
    if (options.stamps == StampPolicy::kStrict && !lines.empty()) {
      const ParsedLine& previous = lines.back();
      detail::require(parsed.values[0] != previous.values[0], location(name, line_number),
                      ": stamp ", parsed.stamp_text, " repeats line ", previous.line,
                      " (strict mode; the TUM scripts would keep the last of the two, see "
                      "StampPolicy::kLikeTumScripts / --lenient-duplicates)");
      detail::require(parsed.values[0] > previous.values[0], location(name, line_number),
                      ": stamp ", parsed.stamp_text, " is earlier than ", previous.stamp_text,
                      " on line ", previous.line, "; stamps must increase (strict mode)");
    }
    lines.push_back(std::move(parsed));
  }
  detail::require(!in.bad(), name, ": read error");
  detail::require(!lines.empty(), name, ": no poses found (", line_number, " lines, ",
                  rep.comment_lines, " comments)");
  rep.data_lines = static_cast<Eigen::Index>(lines.size());
  if (options.stamps == StampPolicy::kLikeTumScripts) {
    lines = sort_keep_last(std::move(lines), name, rep);
  }

  Trajectory trajectory;
  trajectory.name = name;
  const auto n = static_cast<Eigen::Index>(lines.size());
  trajectory.stamps.reserve(lines.size());
  trajectory.positions.resize(3, n);
  trajectory.quaternions.resize(4, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::array<double, 8>& v = lines[static_cast<std::size_t>(i)].values;
    trajectory.stamps.push_back(v[0]);
    trajectory.positions.col(i) << v[1], v[2], v[3];
    trajectory.quaternions.col(i) << v[4], v[5], v[6], v[7];
  }
  rep.poses = n;
  return trajectory;
}

Trajectory read_tum_trajectory(const std::string& path, const ReadOptions& options,
                               ReadReport* report) {
  require_readable_file(path, "a trajectory file");
  std::ifstream in(path);
  detail::require(static_cast<bool>(in), path, ": cannot open trajectory file (",
                  std::strerror(errno), ")");
  return parse_tum_trajectory(in, path, options, report);
}

void write_tum_trajectory(const std::string& path, const Trajectory& trajectory) {
  check_trajectory(trajectory, "write_tum_trajectory");
  std::string text = "# timestamp tx ty tz qx qy qz qw\n";
  for (Eigen::Index i = 0; i < trajectory.size(); ++i) {
    const auto& p = trajectory.positions.col(i);
    const auto& q = trajectory.quaternions.col(i);
    // fmt prints doubles in shortest round-trip form, so a read gives back the same bits.
    fmt::format_to(std::back_inserter(text), "{} {} {} {} {} {} {} {}\n",
                   trajectory.stamps[static_cast<std::size_t>(i)], p.x(), p.y(), p.z(), q(0), q(1),
                   q(2), q(3));
  }
  examples::write_file_atomically(path, text);
}

std::vector<double> read_frame_stamps(const std::string& path) {
  require_readable_file(path, "a frame list");
  std::ifstream in(path);
  detail::require(static_cast<bool>(in), path, ": cannot open frame list (", std::strerror(errno),
                  ")");
  std::vector<double> stamps;
  std::vector<Eigen::Index> lines;  // of each stamp, for messages
  std::string text;
  Eigen::Index line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    const std::vector<std::string_view> fields = split_fields(text);
    if (fields.empty() || fields.front().front() == '#') continue;
    double stamp = 0.0;
    detail::require(parse_double(fields.front(), stamp) && std::isfinite(stamp),
                    location(path, line_number),
                    ": frame stamp is not a finite number: ", shown(fields.front()));
    detail::require(std::abs(stamp) <= kMaxAbsStamp, location(path, line_number), ": frame stamp '",
                    fields.front(), "' is not a plausible time in seconds (|t| must be <= 1e12)");
    stamps.push_back(stamp);
    lines.push_back(line_number);
  }
  detail::require(!in.bad(), path, ": read error");
  detail::require(!stamps.empty(), path, ": no frame stamps found");
  // A frame listed twice would be counted twice in the share of frames tracked.
  std::vector<std::size_t> order(stamps.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return stamps[a] < stamps[b]; });
  for (std::size_t k = 1; k < order.size(); ++k) {
    detail::require(stamps[order[k]] != stamps[order[k - 1]], location(path, lines[order[k]]),
                    ": frame stamp ", fmt::format("{:.6f}", stamps[order[k]]),
                    " is listed again (first at line ", lines[order[k - 1]], ")");
  }
  std::sort(stamps.begin(), stamps.end());
  return stamps;
}

}  // namespace hbos::slam
