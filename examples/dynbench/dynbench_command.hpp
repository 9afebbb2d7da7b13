#pragma once
/// \file
/// The `hbos-dynbench` command, as a function so that tests drive it without spawning processes.

#include <iosfwd>

namespace hbos::dynbench {

/// Exit codes of run_dynbench_command().
enum DynbenchExitCode : int {
  kDynbenchOk = 0,
  kDynbenchFailed = 1,         ///< rendering failed or a result file could not be written
  kDynbenchBadInput = 2,       ///< bad option, no renderer, a missing or misfit input file
  kDynbenchInterrupted = 130,  ///< SIGINT/SIGTERM/SIGHUP: the finished cells are kept for a re-run
};

/// `hbos-dynbench [options]`: renders the scenarios (hbos-render) into a cache, runs the front
/// end on every cell of the grid (scenario x seed x mask variant x screen), skipping cells an
/// earlier run finished with the same settings, and writes dynbench.md, dynbench.json and
/// figures/ into --out. The table goes to `out`, progress and errors to `err`. Returns a
/// DynbenchExitCode. Run with --help for the options.
int run_dynbench_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace hbos::dynbench
