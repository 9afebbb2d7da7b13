#include "common/stop_on_signal.hpp"

namespace hbos::examples {
namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void hbos_request_stop_on_signal(int) { g_stop = 1; }

}  // namespace

StopOnSignal::StopOnSignal() {
  g_stop = 0;
  struct sigaction action {};
  action.sa_handler = &hbos_request_stop_on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = static_cast<int>(SA_RESETHAND);
  ::sigaction(SIGINT, &action, &previous_int_);
  ::sigaction(SIGTERM, &action, &previous_term_);
}

StopOnSignal::~StopOnSignal() {
  ::sigaction(SIGINT, &previous_int_, nullptr);
  ::sigaction(SIGTERM, &previous_term_, nullptr);
}

volatile std::sig_atomic_t* StopOnSignal::flag() { return &g_stop; }

bool StopOnSignal::stopped() { return g_stop != 0; }

void StopOnSignal::request() { g_stop = 1; }

}  // namespace hbos::examples
