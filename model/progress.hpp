// Progress of a long run on a terminal: percent of simulated time, steps per second and the
// estimated time left, rewritten in place on standard error at most twice a second. Silent when
// standard error is not a terminal (logs, pipes, tests), except for one line, on terminals and in
// logs alike, when a run projects to more than kLongRunSeconds to its end time: after
// kEstimateAfterSeconds of wall time it states the run time to the end time at the rate so far.
#pragma once
#include <chrono>
#include <string>

namespace lsi {

class Progress {
 public:
  Progress(std::string label, double end_time);   // enabled iff stderr is a terminal
  Progress(std::string label, double end_time, bool enabled);
  void update(double time, long steps);
  void finish();   // ends the line (if anything was printed)
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
  bool enabled_, printed_ = false, estimated_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace lsi
