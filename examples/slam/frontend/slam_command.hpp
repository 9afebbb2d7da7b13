#pragma once
/// \file
/// The `hbos-slam` command, as a function so that tests drive it without spawning processes.

#include <iosfwd>

namespace hbos::slam {

/// Exit codes of run_slam_command().
enum SlamExitCode : int {
  kSlamOk = 0,
  kSlamOutputError = 1,  ///< a result file could not be written
  kSlamBadInput = 2,     ///< bad option, missing or malformed dataset, unreadable image or model
  /// SIGINT, SIGTERM or SIGHUP during the run: the frames done so far were written (128 + SIGINT,
  /// as a shell reports a Ctrl-C).
  kSlamInterrupted = 130,
};

/// `hbos-slam [options]`: tracks a TUM RGB-D sequence (by default the embedded 37 fr1/xyz frames
/// with a real person composited in) and writes trajectory, statistics, summary and figures;
/// `--ablation` runs every screen x mask instead. The summary goes to `out`, progress and errors
/// to `err`. Returns a SlamExitCode. Run with --help for the options.
int run_slam_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace hbos::slam
