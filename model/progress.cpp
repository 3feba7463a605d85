#include "model/progress.hpp"

#include "model/input_error.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace lsi {
namespace {
double seconds_between(std::chrono::steady_clock::time_point a,
                       std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}
}  // namespace

namespace {
ProgressMode g_mode = ProgressMode::Auto;
}  // namespace

void set_progress_mode(ProgressMode mode) { g_mode = mode; }
ProgressMode progress_mode() { return g_mode; }

ProgressMode progress_mode_from(const std::string& text) {
  if (text == "auto") return ProgressMode::Auto;
  if (text == "log") return ProgressMode::Log;
  if (text == "none") return ProgressMode::None;
  throw InputError("--progress " + text + ": allowed: auto, log, none");
}

namespace {
StatusLine::Kind kind_for(bool wanted) {
  if (!wanted || g_mode == ProgressMode::None) return StatusLine::Kind::Off;
  if (g_mode == ProgressMode::Log || isatty(STDERR_FILENO) != 1) return StatusLine::Kind::Heartbeat;
  return StatusLine::Kind::Line;
}
}  // namespace

StatusLine::StatusLine(bool wanted) : StatusLine(kind_for(wanted), kHeartbeatSeconds, stderr) {}

StatusLine::StatusLine(Kind kind, double heartbeat_seconds, std::FILE* out)
    : kind_(kind),
      heartbeat_seconds_(heartbeat_seconds),
      out_(out),
      last_(std::chrono::steady_clock::now()),
      last_beat_(last_) {}

bool StatusLine::due() {
  const auto now = std::chrono::steady_clock::now();
  if (seconds_between(last_, now) < 0.5) return false;
  last_ = now;
  return true;
}

void StatusLine::show(const std::string& text) {
  if (kind_ == Kind::Off) return;
  if (kind_ == Kind::Heartbeat) {
    const auto now = std::chrono::steady_clock::now();
    if (seconds_between(last_beat_, now) < heartbeat_seconds_) return;
    last_beat_ = now;
    std::fprintf(out_, "%s\n", text.c_str());
    std::fflush(out_);
    return;
  }
  std::fprintf(out_, "\r%s\033[K", text.c_str());
  std::fflush(out_);
  shown_ = true;
}

void StatusLine::print_above(const std::string& text) {
  std::fprintf(out_, "%s%s\n", shown_ ? "\r\033[K" : "", text.c_str());
  shown_ = false;
}

void StatusLine::clear() {
  if (shown_) std::fprintf(out_, "\r\033[K");
  shown_ = false;
}

namespace {
std::atomic<int> g_quiet{0};
}  // namespace

QuietProgress::QuietProgress() { ++g_quiet; }
QuietProgress::~QuietProgress() { --g_quiet; }
bool progress_quiet() { return g_quiet.load() > 0; }

Progress::Progress(std::string label, double end_time, bool ends_at_rest)
    : label_(std::move(label)),
      end_time_(end_time),
      ends_at_rest_(ends_at_rest),
      status_(!progress_quiet()),
      start_(std::chrono::steady_clock::now()) {
  if (progress_quiet()) estimated_ = true;  // no estimate line either
}

void RecentRate::add(double seconds, double done) {
  samples_.emplace_back(seconds, done);
  const double window = std::max(0.25 * seconds, kWindowSeconds);
  while (samples_.size() > 2 && samples_[1].first <= seconds - window) samples_.pop_front();
}

double RecentRate::time_left(double total) const {
  if (samples_.size() < 2) return -1.0;
  const auto& [s0, d0] = samples_.front();
  const auto& [s1, d1] = samples_.back();
  if (!(d1 > d0) || !(s1 > s0)) return -1.0;
  return std::max(total - d1, 0.0) * (s1 - s0) / (d1 - d0);
}

std::string Progress::line(const std::string& label, double time, double end_time, long steps,
                           double seconds, double left, bool ends_at_rest) {
  const double fraction = end_time > 0 ? std::clamp(time / end_time, 0.0, 1.0) : 1.0;
  const double rate = seconds > 0 ? steps / seconds : 0.0;
  char buf[256];
  if (fraction > 0 && seconds > 0) {
    if (left < 0.0) left = seconds * (1.0 - fraction) / fraction;
    std::snprintf(buf, sizeof buf,
                  "%s: %3.0f %% of %.3g s simulated, %.0f steps/s, %.0f s elapsed, ETA %s%.0f s%s",
                  label.c_str(), 100 * fraction, end_time, rate, seconds, ends_at_rest ? "<= " : "",
                  left, ends_at_rest ? " (earlier once at rest)" : "");
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
  if (total < 2 * 3600.0)
    std::snprintf(took, sizeof took, "%.0f min", total / 60.0);
  else if (total < 2 * 86400.0)
    std::snprintf(took, sizeof took, "%.1f h", total / 3600.0);
  else
    std::snprintf(took, sizeof took, "%.3g days", total / 86400.0);
  std::snprintf(buf, sizeof buf,
                "%s: at the rate of the first %.0f s, end_time_s = %.6g s takes about %s of run "
                "time (an impact run ends earlier, once at rest)",
                label.c_str(), seconds, end_time, took);
  return buf;
}

void Progress::update(double time, long steps) {
  if (!status_.enabled() && estimated_) return;
  if (!status_.due()) return;
  const double seconds = seconds_between(start_, std::chrono::steady_clock::now());
  if (!estimated_ && seconds >= kEstimateAfterSeconds) {
    estimated_ = true;
    const std::string e = estimate(label_, time, end_time_, seconds);
    if (!e.empty() && progress_mode() != ProgressMode::None) status_.print_above(e);
  }
  rate_.add(seconds, time);
  status_.show(
      line(label_, time, end_time_, steps, seconds, rate_.time_left(end_time_), ends_at_rest_));
}

void Progress::finish() { status_.clear(); }

SampleProgress::SampleProgress(std::string label, std::uint64_t total, bool enabled,
                               std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      status_(enabled),
      start_(std::chrono::steady_clock::now()) {}

std::string SampleProgress::line(const std::string& label, std::uint64_t done, std::uint64_t total,
                                 std::uint64_t done_here, double seconds, double left,
                                 const std::string& unit) {
  const double rate = seconds > 0 ? double(done_here) / seconds : 0.0;
  if (left < 0.0) left = rate > 0 ? double(total - std::min(done, total)) / rate : 0.0;
  char buf[256];
  std::snprintf(
      buf, sizeof buf, "%s: %llu of %llu %s (%.0f %%), %.3g %s/s, %.0f s elapsed, ETA %.0f s",
      label.c_str(), static_cast<unsigned long long>(done), static_cast<unsigned long long>(total),
      unit.c_str(), total > 0 ? 100.0 * double(done) / double(total) : 100.0, rate, unit.c_str(),
      seconds, left);
  return buf;
}

void SampleProgress::update(std::uint64_t done, std::uint64_t done_here) {
  done_ = done;
  if (!status_.enabled()) return;
  const double seconds = seconds_between(start_, std::chrono::steady_clock::now());
  rate_.add(seconds, double(done_here));
  const double here_total = double(done_here) + double(total_ - std::min(done, total_));
  status_.show(line(label_, done, total_, done_here, seconds, rate_.time_left(here_total), unit_));
}

std::string SampleProgress::finishing_line(const std::string& label, std::uint64_t done,
                                           std::uint64_t total, double seconds,
                                           const std::string& what) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: %llu of %llu samples run, %.0f s elapsed; %s", label.c_str(),
                static_cast<unsigned long long>(done), static_cast<unsigned long long>(total),
                seconds, what.c_str());
  return buf;
}

void SampleProgress::finishing(const std::string& what) {
  if (!status_.enabled()) return;
  const double seconds = seconds_between(start_, std::chrono::steady_clock::now());
  const std::string text = finishing_line(label_, done_, total_, seconds, what);
  // A log gets it at once, as a terminal does, when the run was long enough to have heartbeats.
  if (status_.kind() == StatusLine::Kind::Heartbeat) {
    if (seconds >= kHeartbeatSeconds) status_.print_above(text);
  } else {
    status_.show(text);
  }
}

}  // namespace lsi
