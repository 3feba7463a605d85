// The threads one MPM run takes (model/run_threads.hpp): one thread below two threads' worth of
// points_per_thread(), in a partition of one, else every thread; a one-thread run gives the
// numbers of a campaign's one-thread run to the last bit.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>

#include <fstream>
#include <stdexcept>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "io/scene_parser.hpp"
#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/p2g.hpp"
#include "model/concurrent_runs.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "model/run_threads.hpp"

namespace {

// Whether this build can give a run fewer threads than the backend has (Kokkos 3 partitions of
// the OpenMP backend that runs the kernels) and the backend has more than one.
bool partitions_here() {
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
  return std::is_same_v<Kokkos::DefaultExecutionSpace, Kokkos::OpenMP> &&
         lsi::instance_concurrency<Kokkos::DefaultExecutionSpace>() > 1;
#else
  return false;
#endif
}

// Restores the default after a test that changes it.
struct PointsPerThread {
  explicit PointsPerThread(long p) { lsi::set_points_per_thread(p); }
  ~PointsPerThread() { lsi::reset_points_per_thread(); }
};

TEST(RunThreads, FewerThanTwoThreadsWorthOfPointsRunOnOneThread) {
  // The defaults: a saturated run needs more points per thread than a dry one.
  EXPECT_EQ(lsi::points_per_thread(false), lsi::kDefaultPointsPerThreadDry);
  EXPECT_EQ(lsi::points_per_thread(true), lsi::kDefaultPointsPerThreadSaturated);
  EXPECT_LT(lsi::kDefaultPointsPerThreadDry, lsi::kDefaultPointsPerThreadSaturated);
  const bool p = partitions_here();
  const long dry = lsi::kDefaultPointsPerThreadDry, wet = lsi::kDefaultPointsPerThreadSaturated;
  EXPECT_EQ(lsi::runs_on_one_thread(2 * dry - 1, false), p);
  EXPECT_FALSE(lsi::runs_on_one_thread(2 * dry, false));
  EXPECT_EQ(lsi::runs_on_one_thread(2 * dry, true), p);
  EXPECT_EQ(lsi::runs_on_one_thread(2 * wet - 1, true), p);
  EXPECT_FALSE(lsi::runs_on_one_thread(2 * wet, true));
  // One number for both, set from the command line.
  const PointsPerThread set(1000);
  for (const bool saturated : {false, true}) {
    EXPECT_EQ(lsi::runs_on_one_thread(0, saturated), p);
    EXPECT_EQ(lsi::runs_on_one_thread(1999, saturated), p);
    EXPECT_FALSE(lsi::runs_on_one_thread(2000, saturated));
  }
  lsi::set_points_per_thread(0);  // every run on every thread
  EXPECT_FALSE(lsi::runs_on_one_thread(1, true));
  lsi::set_points_per_thread(-5);  // as 0
  EXPECT_EQ(lsi::points_per_thread(false), 0);
  EXPECT_FALSE(lsi::runs_on_one_thread(1, false));
  lsi::reset_points_per_thread();
  EXPECT_EQ(lsi::points_per_thread(true), lsi::kDefaultPointsPerThreadSaturated);
}

// 0 + 1 + ... + (n - 1) by a kernel (outside the test body: nvcc takes no device lambda in a
// test's body, a private member function).
long sum_of_indices(const int n) {
  long sum = -1;
  Kokkos::parallel_reduce(
      "test_sum", Kokkos::RangePolicy<>(0, n), KOKKOS_LAMBDA(const int i, long& s) { s += i; },
      sum);
  return sum;
}

TEST(RunThreads, TheRunSeesItsThreadsAndTheirErrorsComeBack) {
  const int all = lsi::instance_concurrency<Kokkos::DefaultExecutionSpace>();
  int inside = 0;
  lsi::run_with_threads_for(
      1, false, [&] { inside = lsi::instance_concurrency<Kokkos::DefaultExecutionSpace>(); });
  EXPECT_EQ(inside, partitions_here() ? 1 : all);
  EXPECT_EQ(lsi::instance_concurrency<Kokkos::DefaultExecutionSpace>(), all) << "after the run";
  lsi::run_with_threads_for(
      1000000, false, [&] { inside = lsi::instance_concurrency<Kokkos::DefaultExecutionSpace>(); });
  EXPECT_EQ(inside, all);
  // A kernel inside the partition reaches every index once.
  long sum = -1;
  lsi::run_with_threads_for(1, false, [&] { sum = sum_of_indices(1000); });
  EXPECT_EQ(sum, 999L * 1000 / 2);
  EXPECT_THROW(lsi::run_with_threads_for(1, false, [] { throw std::runtime_error("inside"); }),
               std::runtime_error);
  // Inside a campaign's partition the run keeps the thread it was given.
  lsi::run_concurrently(2, [&](std::size_t k) {
    EXPECT_FALSE(lsi::runs_on_one_thread(1, false)) << "inside a parallel region";
    int seen = 0;
    lsi::run_with_threads_for(
        1, false, [&] { seen = lsi::instance_concurrency<Kokkos::DefaultExecutionSpace>(); });
    if (k == 0) inside = seen;
  });
  EXPECT_EQ(inside, partitions_here() ? 1 : all);
}

// The host scatter keeps one copy of the grid per thread of the run, not of the whole backend:
// a one-thread run adds into one copy and its gather reads one.
TEST(RunThreads, TheScatterOfARunKeepsACopyPerThreadOfTheRun) {
  using Exec = Kokkos::DefaultHostExecutionSpace;
  using Scatter = lsi::mpm::P2GScatter<Exec, false>;
  if (!Scatter::duplicated) GTEST_SKIP() << "this host space adds into one buffer";
  const double lo[2] = {0.0, 0.0}, hi[2] = {2.0, 1.0};
  const lsi::mpm::Grid<Exec::memory_space> grid(lo, hi, 0.25);
  const int all = lsi::instance_concurrency<Exec>();
  EXPECT_EQ(Scatter(grid).copies_count, all);
  int copies = 0;
  lsi::run_with_threads_for(1, false, [&] { copies = Scatter(grid).copies_count; });
  EXPECT_EQ(copies, partitions_here() ? 1 : all);
}

lsi::MpmCase small_impact() {
  std::ifstream in(LSI_SOURCE_DIR "/scenes/verification/granular-impact.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["methods"]["mpm"]["cell_size_m"] = 0.25;
  return lsi::impact_case(lsi::parse_scene(doc));
}

// A small run on one thread (the default rule) is the run of a one-thread campaign partition to
// the last bit: one copy of the grid for its scatter, the same sums in the same order (a run's
// numbers depend on its thread count through the order of its sums, which a granular impact's
// plastic flow amplifies, so the runs on one and on every thread are not compared here). Each
// run reports the threads it took.
TEST(RunThreads, ASmallRunOnOneThreadIsTheRunOfAOneThreadPartition) {
  const lsi::MpmCase c = small_impact();
  const int all = lsi::instance_concurrency<Kokkos::DefaultExecutionSpace>();
  lsi::MpmOutcome one, every;
  {
    const PointsPerThread set(1000000);
    ASSERT_EQ(lsi::runs_on_one_thread(100000, false), partitions_here());
    one = lsi::run_mpm_case(c);
  }
  {
    const PointsPerThread set(0);
    every = lsi::run_mpm_case(c);
  }
  std::vector<lsi::MethodResult> side(2);
  lsi::run_concurrently(2, [&](std::size_t k) { side[k] = lsi::run_mpm_case(c).result; });
  ASSERT_EQ(one.status(), "finished");
  ASSERT_EQ(every.status(), "finished");
  EXPECT_EQ(every.run().threads, all);
  EXPECT_EQ(one.run().threads, partitions_here() ? 1 : all);
  EXPECT_EQ(side[0].run->threads, partitions_here() ? 1 : all);
  if (partitions_here()) {
    for (const auto& campaign : side) {
      ASSERT_EQ(one.result.force.size(), campaign.force.size());
      for (std::size_t i = 0; i < campaign.force.size(); ++i)
        ASSERT_EQ(one.result.force[i], campaign.force[i]) << i;
    }
  }
}

}  // namespace
