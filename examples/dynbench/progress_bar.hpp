#pragma once
/// \file
/// The benchmark's progress: on a terminal one bar redrawn in place (cells done, elapsed, an
/// estimate of the time left, what runs now); in a log or a pipe one line per event.

#include <chrono>
#include <iosfwd>
#include <mutex>
#include <string>

namespace hbos::dynbench {

/// Thread-safe: cells finish on several threads.
class ProgressBar {
 public:
  /// `out` may be null (silent). `total` = cells to run.
  ProgressBar(std::ostream* out, bool terminal, int total);

  /// What runs now (a rendering, a cell), without advancing.
  void status(const std::string& what);
  /// One cell finished (or was taken from an earlier run); `what` says which and its result.
  void advance(const std::string& what);
  /// Ends the bar's line.
  void finish();

 private:
  void draw(const std::string& what);

  std::ostream* out_;
  bool terminal_;
  int total_;
  int done_ = 0;
  int run_ = 0;  ///< cells actually run (not resumed): the time estimate's basis
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
};

}  // namespace hbos::dynbench
