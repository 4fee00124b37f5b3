// The stop handler: it only sets two atomics (async-signal-safe).
#include "app/stop_signals.h"
#include <csignal>

namespace caustica {
namespace {
std::atomic<bool> g_stopped{false};
std::atomic<int> g_signal{0};
extern "C" void on_stop_signal(int sig) {
  g_signal.store(sig);
  g_stopped.store(true);
}
}  // namespace

StopSignals::StopSignals() {
  g_stopped = false;
  g_signal = 0;
  previous_int_ = std::signal(SIGINT, on_stop_signal);
  previous_term_ = std::signal(SIGTERM, on_stop_signal);
}

void StopSignals::restore() {
  if (restored_) return;
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
  restored_ = true;
}

std::atomic<bool>& StopSignals::flag() { return g_stopped; }

int StopSignals::exit_code() { return 128 + (g_signal.load() != 0 ? g_signal.load() : SIGINT); }

}  // namespace caustica
