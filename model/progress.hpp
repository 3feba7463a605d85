// Progress of long work on a terminal: one status line rewritten in place on standard error at
// most twice a second, silent when standard error is not a terminal (logs, pipes, tests).
//   Progress        an MPM run: percent of simulated time, steps per second, the time left; and
//                   one line, on terminals and in logs alike, when a run projects to more than
//                   kLongRunSeconds to its end time: after kEstimateAfterSeconds of wall time it
//                   states the run time to the end time at the rate so far.
//   SampleProgress  a sweep: samples done of the total, samples per second, the time left.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace lsi {

// The line both progress kinds rewrite.
class StatusLine {
 public:
  explicit StatusLine(bool enabled);  // disabled: shows nothing
  ~StatusLine() { clear(); }
  bool enabled() const { return enabled_; }
  // True at most twice a second (the first call after construction is not due).
  bool due();
  void show(const std::string& text);
  // A line that stays (the status line is cleared first, and shown again by the next show()).
  void print_above(const std::string& text);
  void clear();  // removes the status line (if one was shown)

 private:
  bool enabled_, shown_ = false;
  std::chrono::steady_clock::time_point last_;
};

class Progress {
 public:
  Progress(std::string label, double end_time);  // enabled iff stderr is a terminal
  Progress(std::string label, double end_time, bool enabled);
  void update(double time, long steps);
  void finish();  // ends the line (if anything was printed)
  // The line update() prints, for the given state (exposed for tests).
  static std::string line(const std::string& label, double time, double end_time, long steps,
                          double seconds);
  // The estimate line, or "" when the run is not long (exposed for tests).
  static std::string estimate(const std::string& label, double time, double end_time,
                              double seconds);
  static constexpr double kEstimateAfterSeconds = 10.0, kLongRunSeconds = 300.0;

 private:
  std::string label_;
  double end_time_;
  bool estimated_ = false;
  StatusLine status_;
  std::chrono::steady_clock::time_point start_;
};

class SampleProgress {
 public:
  SampleProgress(std::string label, std::uint64_t total, bool enabled);
  // done: samples complete of the total (with earlier runs'); done_here: by this run.
  void update(std::uint64_t done, std::uint64_t done_here);
  // The line update() prints, for the given state (exposed for tests).
  static std::string line(const std::string& label, std::uint64_t done, std::uint64_t total,
                          std::uint64_t done_here, double seconds);

 private:
  std::string label_;
  std::uint64_t total_;
  StatusLine status_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace lsi
