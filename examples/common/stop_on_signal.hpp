#pragma once
// Ctrl-C for long runs: while a StopOnSignal is alive, SIGINT and SIGTERM set a flag that the run
// polls between units of work (frames, cells), so what is finished is kept and written; a second
// signal ends the process as usual (the previous disposition is back), so a stuck run can still
// be killed.

#include <signal.h>

#include <csignal>

namespace hbos::examples {

class StopOnSignal {
 public:
  /// Clears the flag and installs the handler for SIGINT and SIGTERM.
  StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  /// Restores the previous handlers.
  ~StopOnSignal();

  /// The flag the handler sets: pass it to code that polls it.
  [[nodiscard]] static volatile std::sig_atomic_t* flag();
  /// True once a signal (or request()) asked the run to stop.
  [[nodiscard]] static bool stopped();
  /// Asks the run to stop as a signal would (e.g. one worker failed, the others stop too).
  static void request();

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

}  // namespace hbos::examples
