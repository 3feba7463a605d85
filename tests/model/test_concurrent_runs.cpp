// Runs of a campaign side by side (model/concurrent_runs.hpp): every task runs once, errors come
// back after all ran, and MPM runs side by side give the numbers they give one after the other.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>

#include <atomic>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/scene_parser.hpp"
#include "model/concurrent_runs.hpp"
#include "model/mpm_footprint.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"

namespace {

TEST(ConcurrentRuns, EveryTaskRunsOnceAndTheFirstErrorComesBackAfterAll) {
  std::vector<std::atomic<int>> calls(7);
  for (auto& c : calls) c = 0;
  EXPECT_THROW(lsi::run_concurrently(calls.size(),
                                     [&](std::size_t k) {
                                       ++calls[k];
                                       if (k == 2 || k == 5)
                                         throw std::runtime_error("task " + std::to_string(k));
                                     }),
               std::runtime_error);
  for (std::size_t k = 0; k < calls.size(); ++k) EXPECT_EQ(calls[k].load(), 1) << "task " << k;
  try {
    lsi::run_concurrently(calls.size(), [&](std::size_t k) {
      if (k == 2 || k == 5) throw std::runtime_error("task " + std::to_string(k));
    });
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "task 2");  // the first by index, whichever finished first
  }
}

TEST(ConcurrentRuns, AsManyAtOnceAsThreadsAndTasksAllow) {
  EXPECT_EQ(lsi::concurrent_runs(1), 1);
  EXPECT_EQ(lsi::concurrent_runs(0), 1);
  // The host's threads drive the runs, on a device too (each on a stream of its own).
  const int threads = Kokkos::DefaultHostExecutionSpace().concurrency();
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
  if (std::is_same_v<Kokkos::DefaultHostExecutionSpace, Kokkos::OpenMP>) {
    EXPECT_EQ(lsi::concurrent_runs(100), threads);
    EXPECT_EQ(lsi::concurrent_runs(100, 1), 1);
    EXPECT_EQ(lsi::concurrent_runs(2), std::min(threads, 2));
    lsi::set_runs_at_once(1);
    EXPECT_EQ(lsi::concurrent_runs(100), 1);
    lsi::set_runs_at_once(0);
    return;
  }
#endif
  EXPECT_EQ(lsi::concurrent_runs(100), 1) << "no partitions on this backend (" << threads << ")";
}

TEST(ConcurrentRuns, AsManyAtOnceAsFitInHalfTheMemory) {
  constexpr double GB = 1e9;
  EXPECT_EQ(lsi::runs_that_fit(8, 1 * GB, 0), 8) << "memory unknown: no limit";
  EXPECT_EQ(lsi::runs_that_fit(8, 0.0, 1 * GB), 8) << "a run of unknown size: no limit";
  EXPECT_EQ(lsi::runs_that_fit(8, 1 * GB, 16 * GB), 8);
  EXPECT_EQ(lsi::runs_that_fit(8, 1 * GB, 11 * GB), 5);
  EXPECT_EQ(lsi::runs_that_fit(8, 1 * GB, 2 * GB), 1);
  EXPECT_EQ(lsi::runs_that_fit(8, 3 * GB, 1 * GB), 1) << "one run at least (checked on its own)";
  EXPECT_EQ(lsi::runs_that_fit(1, 1 * GB, 100 * GB), 1);
}

TEST(ConcurrentRuns, ACampaignOfScenesTooLargeSideBySideRunsOneAfterTheOther) {
  std::ifstream in(LSI_SOURCE_DIR "/scenes/verification/granular-impact.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["methods"]["mpm"]["cell_size_m"] = 0.25;
  const lsi::Scene small = lsi::parse_scene(doc);
  // A cell of 1 mm: about 5e8 grid nodes by the estimate (model/mpm_footprint.hpp), tens of GB a
  // run, more than half the memory of a machine below a few hundred GB twice over; the estimate
  // is all that is computed.
  doc["methods"]["mpm"]["cell_size_m"] = 1e-3;
  const lsi::Scene huge = lsi::parse_scene(doc);
  const double huge_bytes = lsi::host_run_bytes(lsi::estimate_footprint(lsi::impact_case(huge)));
  ASSERT_GT(huge_bytes, 1e10);
  EXPECT_EQ(lsi::campaign_runs_that_fit(100, {&small}), lsi::concurrent_runs(100));
  EXPECT_EQ(lsi::campaign_runs_that_fit(100, {&small, &huge}), 1) << "the largest scene counts";
  EXPECT_EQ(lsi::campaign_runs_that_fit(1, {&small}), 1);
}

// Four small impacts (the granular-impact scene at two Froude numbers, each twice): side by side
// and one after the other (on a GPU: each side-by-side run on a stream of its own, so a kernel
// that read another run's data or launch arguments would change its numbers). A run's sums are
// taken in another order with one thread than with two, so the numbers agree to round-off, which
// the run's plastic flow may amplify: 1e-9 relative, far below any change of the physics (a
// setting moves the peak by per cents).
TEST(ConcurrentRuns, MpmRunsSideBySideGiveTheNumbersOfRunsOneAfterTheOther) {
  std::ifstream in(LSI_SOURCE_DIR "/scenes/verification/granular-impact.json");
  const nlohmann::json base = nlohmann::json::parse(in);
  std::vector<lsi::MpmCase> cases;
  for (double v : {4.0, 8.0, 4.0, 8.0}) {
    nlohmann::json doc = base;
    doc["landslide"]["velocity_m_s"] = v;
    doc["methods"]["mpm"]["cell_size_m"] = 0.25;
    cases.push_back(lsi::impact_case(lsi::parse_scene(doc)));
  }
  std::vector<lsi::MethodResult> side(cases.size()), after(cases.size());
  lsi::run_concurrently(cases.size(),
                        [&](std::size_t k) { side[k] = lsi::run_mpm_case(cases[k]).result; });
  for (std::size_t k = 0; k < cases.size(); ++k) after[k] = lsi::run_mpm_case(cases[k]).result;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    ASSERT_EQ(side[k].status, "finished") << k;
    EXPECT_NEAR(side[k].peak_force, after[k].peak_force, 1e-9 * after[k].peak_force) << k;
    ASSERT_EQ(side[k].time.size(), after[k].time.size()) << k;
    for (std::size_t i = 0; i < side[k].force.size(); ++i)
      EXPECT_NEAR(side[k].force[i], after[k].force[i], 1e-9 * after[k].peak_force) << k << " " << i;
  }
  // The same scene twice gives the same numbers, side by side too.
  EXPECT_NEAR(side[0].peak_force, side[2].peak_force, 1e-9 * side[0].peak_force);
  EXPECT_NEAR(side[1].peak_force, side[3].peak_force, 1e-9 * side[1].peak_force);
}

}  // namespace
