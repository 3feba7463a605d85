// A campaign whose program has not used Kokkos yet (lsi calibrate and lsi compare start with
// closed forms and file checks): its runs still go side by side, one a thread. This program's
// main does not start Kokkos; the campaign does (model/concurrent_runs.hpp).
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <type_traits>
#include <vector>

#include "model/concurrent_runs.hpp"

namespace {

TEST(ConcurrentRuns, ACampaignStartsKokkosAndRunsSideBySide) {
  ASSERT_FALSE(Kokkos::is_initialized());
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
  if (std::is_same_v<Kokkos::DefaultHostExecutionSpace, Kokkos::OpenMP>) {
    // The test runs with OMP_NUM_THREADS=2 (tests/model/CMakeLists.txt).
    EXPECT_EQ(lsi::concurrent_runs(100), 2);
    EXPECT_TRUE(Kokkos::is_initialized());
    // Two tasks at once: each waits (up to 30 s) for the other to have started.
    std::atomic<int> started{0};
    std::vector<int> saw_both(2, 0);
    lsi::run_concurrently(2, [&](std::size_t k) {
      ++started;
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
      while (started.load() < 2 && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      saw_both[k] = started.load() == 2;
    });
    EXPECT_EQ(saw_both[0], 1);
    EXPECT_EQ(saw_both[1], 1);
    return;
  }
#endif
  GTEST_SKIP() << "no partitions on this backend: a campaign runs one task after the other";
}

}  // namespace
