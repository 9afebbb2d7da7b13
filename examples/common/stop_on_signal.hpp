#pragma once
// Ctrl-C for long runs: while a StopOnSignal is alive, SIGINT, SIGTERM and SIGHUP (a closed
// terminal or ssh session) set a flag that the run polls between units of work (frames, cells),
// so what is finished is kept and written. A second signal half a second or more after the first
// ends the process as the signal does by default, so a stuck run can still be killed; one sooner
// is taken as the same request (coreutils' `timeout` sends its signal twice: to the process, then
// to its process group).

#include <signal.h>

#include <csignal>

namespace hbos::examples {

class StopOnSignal {
 public:
  /// Clears the flag and installs the handler for SIGINT, SIGTERM and SIGHUP.
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
  struct sigaction previous_hup_ {};
};

}  // namespace hbos::examples
