#pragma once
/// \file
/// Reading and writing TUM RGB-D trajectory files (`t tx ty tz qx qy qz qw`).
///
/// Format, as the TUM benchmark scripts read it: commas and tabs count as spaces, runs of spaces
/// separate fields, blank lines and lines starting with `#` are skipped. Unlike the scripts, this
/// reader refuses anything it cannot read unambiguously and says where: every error names
/// `file:line`, the field and the offending value.

#include "eval/trajectory.hpp"

#include <Eigen/Core>

#include <iosfwd>
#include <string>
#include <vector>

namespace hbos::slam {

/// What to do with repeated or out-of-order stamps.
enum class StampPolicy {
  /// Default. Stamps must strictly increase line by line; a repeated or decreasing stamp is an
  /// error naming both lines. A repeated stamp with two different poses is ambiguous, so the
  /// reader should not pick one silently.
  kStrict,
  /// Exactly what the TUM scripts do (they store poses in a dict keyed by stamp): lines are
  /// sorted by stamp and a repeated stamp keeps the **last** line. Needed to reproduce the
  /// scripts on files such as fr2/desk's ground truth, which repeats stamp 1311868229.5760.
  /// Every dropped line is listed in ReadReport::warnings.
  kLikeTumScripts,
};

/// Options of the trajectory reader.
struct ReadOptions {
  StampPolicy stamps = StampPolicy::kStrict;  ///< repeated / unsorted stamps
  /// Largest accepted | ‖q‖ − 1 |. Files store quaternions rounded to 4–9 decimals (TUM ground
  /// truth: 4, so ‖q‖ is off by up to ~2e-4); anything much larger is a wrong column order or a
  /// corrupted line, not rounding. The pose is normalised when used either way.
  double max_quaternion_norm_error = 1e-2;  ///< [-]
};

/// What the reader saw, for reports.
struct ReadReport {
  Eigen::Index poses = 0;               ///< poses kept (unique stamps)
  Eigen::Index data_lines = 0;          ///< lines holding a pose, before dropping duplicates
  Eigen::Index comment_lines = 0;       ///< lines starting with '#'
  Eigen::Index blank_lines = 0;         ///< empty or whitespace-only lines
  Eigen::Index duplicates_dropped = 0;  ///< kLikeTumScripts only
  bool reordered = false;               ///< kLikeTumScripts only: lines were not sorted
  std::vector<std::string> warnings;    ///< one line each, `file:line: ...`
};

/// Reads a TUM trajectory file. Throws hbos::InvalidArgument (`file:line: field 'qx' ...`) on
/// unreadable files, malformed lines (not exactly 8 fields), values that are not numbers or not
/// finite, quaternions far from unit length, stamps that repeat or decrease (kStrict), and files
/// without any pose.
[[nodiscard]] Trajectory read_tum_trajectory(const std::string& path,
                                             const ReadOptions& options = {},
                                             ReadReport* report = nullptr);

/// As read_tum_trajectory, from a stream; `name` stands for the file in messages.
[[nodiscard]] Trajectory parse_tum_trajectory(std::istream& in, const std::string& name,
                                              const ReadOptions& options = {},
                                              ReadReport* report = nullptr);

/// Writes a trajectory as a TUM file (a header comment, then one pose per line, every number in
/// shortest round-trip form so that reading it back gives identical doubles). Atomic. Throws
/// std::runtime_error on I/O failure.
void write_tum_trajectory(const std::string& path, const Trajectory& trajectory);

/// Reads the frame stamps of a sequence from the first column of a TUM `rgb.txt`, `depth.txt`
/// or association file (other columns are ignored); used for the share of frames tracked.
/// Returns them sorted. Throws hbos::InvalidArgument (`file:line`) on a non-numeric or
/// non-finite stamp or a file without stamps.
[[nodiscard]] std::vector<double> read_frame_stamps(const std::string& path);

}  // namespace hbos::slam
