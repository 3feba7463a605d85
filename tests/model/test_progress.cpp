// The progress line of long runs and the one-line estimate of a run that projects to more than
// Progress::kLongRunSeconds (model/progress.hpp).
#include <gtest/gtest.h>

#include <string>

#include "model/progress.hpp"

namespace {

TEST(Progress, LineShowsTheFractionRateAndTimeLeft) {
  // A quarter of 2 s simulated in 10 s with 500 steps: 50 steps/s, 30 s left.
  const std::string line = lsi::Progress::line("mpm x", 0.5, 2.0, 500, 10.0);
  EXPECT_EQ(line, "mpm x:  25 % of 2 s simulated, 50 steps/s, ETA 30 s");
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

TEST(SampleProgress, LineShowsTheSamplesRateAndTimeLeft) {
  // 300 of 1000 done, 200 of them by this run in 4 s: 50 samples/s, 700 left: 14 s.
  EXPECT_EQ(lsi::SampleProgress::line("sweep s", 300, 1000, 200, 4.0),
            "sweep s: 300 of 1000 samples (30 %), 50 samples/s, ETA 14 s");
  // Nothing run yet: no rate, no estimate; an empty study is complete.
  EXPECT_EQ(lsi::SampleProgress::line("s", 0, 10, 0, 0.0),
            "s: 0 of 10 samples (0 %), 0 samples/s, ETA 0 s");
  EXPECT_EQ(lsi::SampleProgress::line("s", 0, 0, 0, 1.0),
            "s: 0 of 0 samples (100 %), 0 samples/s, ETA 0 s");
}
