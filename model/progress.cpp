#include "model/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace lsi {

Progress::Progress(std::string label, double end_time)
    : Progress(std::move(label), end_time, isatty(STDERR_FILENO) == 1) {}

Progress::Progress(std::string label, double end_time, bool enabled)
    : label_(std::move(label)), end_time_(end_time), enabled_(enabled),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

std::string Progress::line(const std::string& label, double time, double end_time, long steps,
                           double seconds) {
  const double fraction = end_time > 0 ? std::clamp(time / end_time, 0.0, 1.0) : 1.0;
  const double rate = seconds > 0 ? steps / seconds : 0.0;
  char buf[256];
  if (fraction > 0 && seconds > 0) {
    const double left = seconds * (1.0 - fraction) / fraction;
    std::snprintf(buf, sizeof buf, "%s: %3.0f %% of %.3g s simulated, %.0f steps/s, ETA %.0f s",
                  label.c_str(), 100 * fraction, end_time, rate, left);
  } else {
    std::snprintf(buf, sizeof buf, "%s: %3.0f %% of %.3g s simulated", label.c_str(),
                  100 * fraction, end_time);
  }
  return buf;
}

std::string Progress::estimate(const std::string& label, double time, double end_time,
                               double seconds) {
  if (!(time > 0.0) || !(end_time > time)) return "";
  const double total = seconds * end_time / time;
  if (!(total > kLongRunSeconds)) return "";
  char took[64], buf[384];
  if (total < 2 * 3600.0) std::snprintf(took, sizeof took, "%.0f min", total / 60.0);
  else if (total < 2 * 86400.0) std::snprintf(took, sizeof took, "%.1f h", total / 3600.0);
  else std::snprintf(took, sizeof took, "%.3g days", total / 86400.0);
  std::snprintf(buf, sizeof buf,
                "%s: at the rate of the first %.0f s, end_time_s = %.6g s takes about %s of run "
                "time (an impact run ends earlier, once at rest)",
                label.c_str(), seconds, end_time, took);
  return buf;
}

void Progress::update(double time, long steps) {
  if (!enabled_ && estimated_) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() < 0.5) return;
  last_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  if (!estimated_ && seconds >= kEstimateAfterSeconds) {
    estimated_ = true;
    const std::string e = estimate(label_, time, end_time_, seconds);
    if (!e.empty()) {
      std::fprintf(stderr, "%s%s\n", printed_ ? "\r\033[K" : "", e.c_str());
      printed_ = false;
    }
  }
  if (!enabled_) return;
  std::fprintf(stderr, "\r%s\033[K", line(label_, time, end_time_, steps, seconds).c_str());
  std::fflush(stderr);
  printed_ = true;
}

void Progress::finish() {
  if (printed_) std::fprintf(stderr, "\r\033[K");
  printed_ = false;
}

}  // namespace lsi
