// The progress line of long runs and the one-line estimate of a run that projects to more than
// Progress::kLongRunSeconds (model/progress.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "model/input_error.hpp"
#include "model/progress.hpp"

namespace {

TEST(Progress, LineShowsTheFractionRateAndTimeLeft) {
  // A quarter of 2 s simulated in 10 s with 500 steps: 50 steps/s, 30 s left.
  const std::string line = lsi::Progress::line("mpm x", 0.5, 2.0, 500, 10.0);
  EXPECT_EQ(line, "mpm x:  25 % of 2 s simulated, 50 steps/s, 10 s elapsed, ETA 30 s");
  // An impact run stops once at rest, usually well before its end time: the time left to the end
  // time is an upper bound, and the line says so.
  EXPECT_EQ(lsi::Progress::line("mpm x", 0.5, 2.0, 500, 10.0, -1.0, true),
            "mpm x:  25 % of 2 s simulated, 50 steps/s, 10 s elapsed, ETA <= 30 s (earlier once "
            "at rest)");
}

// A run whose pace halves at 30 % of the work (100 s of simulated time; 1 s per wall second, then
// 0.5): it takes 170 s. Sampled twice a second as Progress::update does, the recent rate's time
// left is right from one window after the change on (0.25 of the elapsed time: 15 s at 60 s),
// while the average since the start is a third short at 60 s. Checked from 10 % of the run
// (17 s) on: within 20 % of the truth wherever the window lies past the change, and never more
// than the average's error.
TEST(Progress, TimeLeftFollowsTheRecentRate) {
  auto done_at = [](double s) { return s < 30.0 ? s : 30.0 + 0.5 * (s - 30.0); };
  const double total = 100.0, end = 170.0;
  lsi::RecentRate rate;
  EXPECT_LT(rate.time_left(total), 0.0);  // unknown before two samples
  for (double s = 0.5; s < end; s += 0.5) {
    rate.add(s, done_at(s));
    if (s < 0.1 * end) continue;
    const double truth = end - s, left = rate.time_left(total);
    const double average = s * (total - done_at(s)) / done_at(s);
    EXPECT_LE(std::fabs(left - truth), std::fabs(average - truth) + 1e-9) << s;
    if (s - 0.25 * s >= 30.0) EXPECT_NEAR(left / truth, 1.0, 0.2) << s;
  }
  // The line shows the time left it is given.
  EXPECT_EQ(lsi::Progress::line("mpm x", 0.5, 2.0, 500, 10.0, 12.0),
            "mpm x:  25 % of 2 s simulated, 50 steps/s, 10 s elapsed, ETA 12 s");
}

TEST(Progress, EstimateOnlyForLongRuns) {
  // 0.1 s simulated in 10 s: 100 s of simulated time take 1e4 s, 2.8 h.
  EXPECT_EQ(lsi::Progress::estimate("mpm x", 0.1, 100.0, 10.0),
            "mpm x: at the rate of the first 10 s, end_time_s = 100 s takes about 2.8 h of run "
            "time (an impact run ends earlier, once at rest)");
  // 40 min and 3 days are shown in their units.
  EXPECT_NE(lsi::Progress::estimate("a", 1.0, 240.0, 10.0).find("about 40 min"), std::string::npos);
  EXPECT_NE(lsi::Progress::estimate("a", 1.0, 25920.0, 10.0).find("about 3 days"),
            std::string::npos);
  // Projected 200 s (not long), nothing simulated yet, or the end already reached: no estimate.
  EXPECT_EQ(lsi::Progress::estimate("a", 1.0, 20.0, 10.0), "");
  EXPECT_EQ(lsi::Progress::estimate("a", 0.0, 20.0, 10.0), "");
  EXPECT_EQ(lsi::Progress::estimate("a", 20.0, 20.0, 10.0), "");
}

}  // namespace

// Once the samples are run the line says what follows instead of "100 %, ETA 0 s".
TEST(SampleProgress, FinishingSaysWhatFollowsTheSamples) {
  EXPECT_EQ(
      lsi::SampleProgress::finishing_line("sweep s", 1000, 1000, 12.0, "writing the result file"),
      "sweep s: 1000 of 1000 samples run, 12 s elapsed; writing the result file");
  // The time left it is given, in place of the average's.
  EXPECT_EQ(lsi::SampleProgress::line("sweep s", 300, 1000, 200, 4.0, 20.0),
            "sweep s: 300 of 1000 samples (30 %), 50 samples/s, 4 s elapsed, ETA 20 s");
}

TEST(SampleProgress, LineShowsTheSamplesRateAndTimeLeft) {
  // 300 of 1000 done, 200 of them by this run in 4 s: 50 samples/s, 700 left: 14 s.
  EXPECT_EQ(lsi::SampleProgress::line("sweep s", 300, 1000, 200, 4.0),
            "sweep s: 300 of 1000 samples (30 %), 50 samples/s, 4 s elapsed, ETA 14 s");
  // Nothing run yet: no rate, no estimate; an empty study is complete.
  EXPECT_EQ(lsi::SampleProgress::line("s", 0, 10, 0, 0.0),
            "s: 0 of 10 samples (0 %), 0 samples/s, 0 s elapsed, ETA 0 s");
  EXPECT_EQ(lsi::SampleProgress::line("s", 0, 0, 0, 1.0),
            "s: 0 of 0 samples (100 %), 0 samples/s, 1 s elapsed, ETA 0 s");
  // A campaign's runs side by side (model/concurrent_runs.hpp) count runs.
  EXPECT_EQ(lsi::SampleProgress::line("compare", 3, 27, 3, 6.0, -1.0, "runs"),
            "compare: 3 of 27 runs (11 %), 0.5 runs/s, 6 s elapsed, ETA 48 s");
}

// The heartbeat of logs: the text as a line of its own, at most once per interval (none before the
// first interval has passed); a status line on a terminal is rewritten in place instead.
TEST(StatusLine, HeartbeatPrintsLinesAtMostOncePerInterval) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    lsi::StatusLine beat(lsi::StatusLine::Kind::Heartbeat, 0.0, f);  // every call is due
    beat.show("one");
    beat.show("two");
    lsi::StatusLine slow(lsi::StatusLine::Kind::Heartbeat, 3600.0, f);  // never within the test
    slow.show("never");
    lsi::StatusLine off(lsi::StatusLine::Kind::Off, 0.0, f);
    off.show("off");
    lsi::StatusLine line(lsi::StatusLine::Kind::Line, 0.0, f);
    line.show("a");
    line.show("b");
  }  // the line is cleared when it goes
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += static_cast<char>(c);
  std::fclose(f);
  EXPECT_EQ(text, "one\ntwo\n\ra\033[K\rb\033[K\r\033[K");
}

TEST(ProgressMode, ParsesTheThreeModesAndRefusesOthers) {
  EXPECT_EQ(lsi::progress_mode_from("auto"), lsi::ProgressMode::Auto);
  EXPECT_EQ(lsi::progress_mode_from("log"), lsi::ProgressMode::Log);
  EXPECT_EQ(lsi::progress_mode_from("none"), lsi::ProgressMode::None);
  try {
    lsi::progress_mode_from("verbose");
    ADD_FAILURE() << "no error";
  } catch (const lsi::InputError& e) {
    EXPECT_STREQ(e.what(), "--progress verbose: allowed: auto, log, none");
  }
}
