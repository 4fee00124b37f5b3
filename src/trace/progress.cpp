// Progress reporting.
#include "trace/progress.h"
#include <cstdio>
#include <unistd.h>

namespace caustica {

std::string format_seconds(double s) {
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  return buf;
}

Progress::Progress(std::string label, double total, bool quiet)
    : label_(std::move(label)), total_(total > 0 ? total : 1), quiet_(quiet), tty_(isatty(2) != 0),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::set(double done) {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  draw(done, false);
}

void Progress::finish() {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  draw(total_, true);
  finished_ = true;
}

void Progress::draw(double done, bool final_line) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double frac = std::min(1.0, std::max(0.0, done / total_));
  const int tick = int(frac * 10.0);
  if (tty_) {
    if (!final_line && std::chrono::duration<double>(now - last_draw_).count() < 0.1) return;
    last_draw_ = now;
    const int width = 30, filled = int(frac * width);
    std::string bar(filled, '#');
    bar += std::string(width - filled, '.');
    const std::string eta = frac > 0 ? format_seconds(elapsed * (1 - frac) / frac) : "?";
    std::fprintf(stderr, "\r%s [%s] %5.1f%%  %s elapsed, ETA %s   ", label_.c_str(), bar.c_str(), 100 * frac,
                 format_seconds(elapsed).c_str(), final_line ? "0.0s" : eta.c_str());
    if (final_line) std::fputc('\n', stderr);
    std::fflush(stderr);
  } else if (tick > last_tick_ || final_line) {
    if (final_line && tick == last_tick_) return;
    last_tick_ = tick;
    const std::string eta = frac > 0 ? format_seconds(elapsed * (1 - frac) / frac) : "?";
    std::fprintf(stderr, "%s: %3d%%  %s elapsed, ETA %s\n", label_.c_str(), tick * 10,
                 format_seconds(elapsed).c_str(), eta.c_str());
    std::fflush(stderr);
  }
}

}  // namespace caustica
