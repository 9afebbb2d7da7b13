#pragma once
/// \file
/// The `hbos-eval` command, as a function so that tests drive it without spawning processes.

#include <iosfwd>

namespace hbos::slam {

/// Exit codes of run_eval_command().
enum EvalExitCode : int {
  kEvalOk = 0,
  kEvalOutputError = 1,  ///< a result file or plot could not be written
  kEvalBadInput = 2,     ///< bad command line, unreadable or malformed trajectory, no overlap
};

/// `hbos-eval GT EST [options]`: evaluates an estimated trajectory against ground truth with the
/// TUM benchmark's conventions, prints a table to `out`, optionally writes JSON (--json) and
/// PNG plots (--plot DIR); messages and warnings go to `err`. Returns an EvalExitCode. Run with
/// --help for the options.
int run_eval_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace hbos::slam
