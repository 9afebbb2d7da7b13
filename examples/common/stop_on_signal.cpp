#include "common/stop_on_signal.hpp"

#include <time.h>

#include <atomic>

namespace hbos::examples {
namespace {

volatile std::sig_atomic_t g_stop = 0;
// When the first signal came [ns, CLOCK_MONOTONIC]; 0: none yet. Written by the handler alone;
// a handler may touch only lock-free atomics (and volatile sig_atomic_t, too narrow for this).
std::atomic<long long> g_first_signal_ns{0};
static_assert(std::atomic<long long>::is_always_lock_free);
// A second signal this soon after the first is the same request delivered twice: coreutils'
// `timeout` signals the process and then its whole process group.
constexpr long long kSameRequestNs = 500'000'000;

extern "C" void hbos_request_stop_on_signal(int signal_number) {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  const long long ns = static_cast<long long>(now.tv_sec) * 1'000'000'000LL + now.tv_nsec;
  const long long first = g_first_signal_ns.load(std::memory_order_relaxed);
  if (first == 0) {
    g_first_signal_ns.store(ns > 0 ? ns : 1, std::memory_order_relaxed);
    g_stop = 1;
    return;
  }
  if (ns - first < kSameRequestNs) return;
  // A second request: end the process as the signal does by default (blocked in this handler,
  // it is delivered as soon as the handler returns).
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

}  // namespace

StopOnSignal::StopOnSignal() {
  g_stop = 0;
  g_first_signal_ns.store(0, std::memory_order_relaxed);
  struct sigaction action {};
  action.sa_handler = &hbos_request_stop_on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  ::sigaction(SIGINT, &action, &previous_int_);
  ::sigaction(SIGTERM, &action, &previous_term_);
  ::sigaction(SIGHUP, &action, &previous_hup_);
}

StopOnSignal::~StopOnSignal() {
  ::sigaction(SIGINT, &previous_int_, nullptr);
  ::sigaction(SIGTERM, &previous_term_, nullptr);
  ::sigaction(SIGHUP, &previous_hup_, nullptr);
}

volatile std::sig_atomic_t* StopOnSignal::flag() { return &g_stop; }

bool StopOnSignal::stopped() { return g_stop != 0; }

void StopOnSignal::request() { g_stop = 1; }

}  // namespace hbos::examples
