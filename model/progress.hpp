// Progress of long work on standard error, in one of three modes (set_progress_mode; the command
// line's --progress):
//   auto  on a terminal one status line rewritten in place at most twice a second; elsewhere
//         (logs of Slurm, mpirun, CI) a heartbeat: the same text as a line of its own every
//         kHeartbeatSeconds;
//   log   the heartbeat, on terminals too;
//   none  nothing.
// The two kinds of work:
//   Progress        an MPM run: percent of simulated time, steps per second, the time left at the
//                   recent rate (RecentRate); and
//                   one line, in every mode but none, when a run projects to more than
//                   kLongRunSeconds to its end time: after kEstimateAfterSeconds of wall time it
//                   states the run time to the end time at the rate so far.
//   SampleProgress  a sweep: samples done of the total, samples per second, the time left at the
//                   recent rate; then what follows the samples (the result file being written).
//                   Also a campaign's runs side by side (model/concurrent_runs.hpp), in runs.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <string>
#include <utility>

namespace lsi {

enum class ProgressMode { Auto, Log, None };
void set_progress_mode(ProgressMode mode);
ProgressMode progress_mode();
// "auto", "log", "none"; throws InputError naming --progress for anything else.
ProgressMode progress_mode_from(const std::string& text);

inline constexpr double kHeartbeatSeconds = 30.0;

// While one exists, MPM runs show no progress (their lines would mix: runs side by side of
// model/concurrent_runs.hpp). A sweep's SampleProgress is not affected.
class QuietProgress {
 public:
  QuietProgress();
  ~QuietProgress();
  QuietProgress(const QuietProgress&) = delete;
  QuietProgress& operator=(const QuietProgress&) = delete;
};
bool progress_quiet();

// The line both progress kinds show: rewritten in place (Kind::Line) or printed as a heartbeat.
class StatusLine {
 public:
  enum class Kind { Off, Line, Heartbeat };
  // wanted: the caller's choice; the mode and whether `out` is a terminal decide the kind.
  explicit StatusLine(bool wanted);
  StatusLine(Kind kind, double heartbeat_seconds, std::FILE* out);
  ~StatusLine() { clear(); }
  bool enabled() const { return kind_ != Kind::Off; }
  Kind kind() const { return kind_; }
  // True at most twice a second (the first call after construction is not due).
  bool due();
  // Shows the text (Line), or prints it as a line of its own if the last heartbeat (or the start)
  // is at least heartbeat_seconds ago (Heartbeat).
  void show(const std::string& text);
  // A line that stays (the status line is cleared first, and shown again by the next show()).
  void print_above(const std::string& text);
  void clear();  // removes the status line (if one was shown)

 private:
  Kind kind_;
  double heartbeat_seconds_ = kHeartbeatSeconds;
  std::FILE* out_ = stderr;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_, last_beat_;
};

// The rate of recent progress: simulated time per wall second over the last quarter of the
// elapsed time (at least kWindowSeconds), so that a run whose pace changes (a flow piling up
// against the barrier, a shrinking time step) shows in its estimate within that window instead
// of being diluted in the average since the start.
class RecentRate {
 public:
  static constexpr double kWindowSeconds = 5.0;
  void add(double seconds, double done);  // wall seconds since the start, work done so far
  // Wall seconds to reach `total` at the recent rate; < 0 while unknown.
  double time_left(double total) const;

 private:
  std::deque<std::pair<double, double>> samples_;
};

class Progress {
 public:
  // ends_at_rest: a run that may stop before end_time, once at rest (an impact): its time left is
  // an upper bound, shown as "ETA <= ... (earlier once at rest)".
  Progress(std::string label, double end_time, bool ends_at_rest = false);
  void update(double time, long steps);
  void finish();  // ends the line (if anything was printed)
  // The line update() prints, for the given state (exposed for tests); `left`, the run time left
  // (RecentRate), or < 0 for the average rate since the start.
  static std::string line(const std::string& label, double time, double end_time, long steps,
                          double seconds, double left = -1.0, bool ends_at_rest = false);
  // The estimate line, or "" when the run is not long (exposed for tests).
  static std::string estimate(const std::string& label, double time, double end_time,
                              double seconds);
  static constexpr double kEstimateAfterSeconds = 10.0, kLongRunSeconds = 300.0;

 private:
  std::string label_;
  double end_time_;
  bool ends_at_rest_ = false;
  bool estimated_ = false;
  StatusLine status_;
  RecentRate rate_;
  std::chrono::steady_clock::time_point start_;
};

class SampleProgress {
 public:
  // unit: what is counted, in the plural ("samples", "runs").
  SampleProgress(std::string label, std::uint64_t total, bool enabled,
                 std::string unit = "samples");
  // done: samples complete of the total (with earlier runs'); done_here: by this run.
  void update(std::uint64_t done, std::uint64_t done_here);
  // The samples are run and `what` (e.g. writing the result file) follows: says so at once, in
  // place of a line at 100 % with nothing left (in a log only after a heartbeat's time).
  void finishing(const std::string& what);
  // The line update() prints, for the given state (exposed for tests); `left`, the time left at
  // the recent rate (RecentRate), or < 0 for the average rate of this run.
  static std::string line(const std::string& label, std::uint64_t done, std::uint64_t total,
                          std::uint64_t done_here, double seconds, double left = -1.0,
                          const std::string& unit = "samples");
  // The line finishing() prints.
  static std::string finishing_line(const std::string& label, std::uint64_t done,
                                    std::uint64_t total, double seconds, const std::string& what);

 private:
  std::string label_, unit_;
  std::uint64_t total_, done_ = 0;
  StatusLine status_;
  RecentRate rate_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace lsi
