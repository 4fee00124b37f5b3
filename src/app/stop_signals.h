// Ctrl-C (SIGINT) and SIGTERM (what batch schedulers such as Slurm send at a job's time limit)
// stop `render` and `converge` after the work completed so far, which is written, and `photons`
// before it writes anything. The handlers stay installed until the outputs are in place (in
// `compare --diff` too), so a signal while writing waits for them, and the exit is 128 + signal.
#pragma once
#include <atomic>

namespace caustica {

// Installs the stop handler for SIGINT and SIGTERM (and clears any earlier stop) until restore()
// or the end of the scope, an error on the way out included.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals() { restore(); }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  void restore();

  // Set by the handler: what a render's cancel and a preprocess's interrupt point at.
  static std::atomic<bool>& flag();
  static bool stopped() { return flag().load(); }
  // The shell's convention: 128 + the signal (130 for SIGINT, 143 for SIGTERM).
  static int exit_code();

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
  bool restored_ = false;
};

}  // namespace caustica
