// Progress bar with ETA on stderr: redrawn in place on a terminal, a plain line per 10 %
// otherwise, silent when quiet.
#pragma once
#include <chrono>
#include <mutex>
#include <string>

namespace caustica {

class Progress {
 public:
  Progress(std::string label, double total, bool quiet);
  ~Progress();
  void set(double done);  // thread-safe
  void finish();

 private:
  void draw(double done, bool final_line);
  std::string label_;
  double total_;
  bool quiet_, tty_, finished_ = false;
  int last_tick_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::mutex mutex_;
};

std::string format_seconds(double s);

}  // namespace caustica
