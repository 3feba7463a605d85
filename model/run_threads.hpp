// How many of the host's threads one MPM run takes. A step of the MPM is a dozen or more
// parallel regions; at each, a thread that slept since the last one must be woken (the wait
// policy, app/openmp_wait_policy.hpp), and the per-thread copies of the grid are summed. A small
// scene's regions are shorter than those wake-ups, so it runs faster on one thread than on two.
// A run therefore takes one thread per so many of its material points (at least one, at most
// all): the threads it does not take sleep through the run. A saturated step has more regions
// than a dry one, with host work between them, so a saturated run needs more points per thread
// before a second thread pays (docs/notes/performance.md, "Threads per run").
//
// With Kokkos' OpenMP backend (Kokkos 3) the run goes to one partition of that many threads
// (Kokkos::OpenMP::partition_master, as the runs of a campaign, model/concurrent_runs.hpp).
// Elsewhere (Serial, Kokkos 4, a device: its kernels do not run on the host's threads) and
// inside a campaign's partition, where the run already has its own threads, the run takes every
// thread it is given. A run's numbers depend on its thread count by round-off only (the order of
// its sums).
#pragma once
#include <functional>

namespace lsi {

// The defaults of points_per_thread(): a run takes a second thread from twice as many points on,
// about where a second thread starts to pay on the reference scenes, dry and saturated.
inline constexpr long kDefaultPointsPerThreadDry = 1024;
inline constexpr long kDefaultPointsPerThreadSaturated = 2048;

// One number of points per thread for every run, set from the command line
// (--points-per-thread); 0: every run takes every thread. reset_points_per_thread() goes back to
// the defaults.
void set_points_per_thread(long points);
void reset_points_per_thread();
long points_per_thread(bool saturated);

// The threads a run of `points` material points takes: points / points_per_thread(saturated),
// at least 1, at most the host backend's threads (all of them when points_per_thread is 0).
int threads_for_run(long points, bool saturated);

// Calls f with the host backend's kernels on `threads` of its threads (a partition of them) when
// that is fewer than it has, partitions are available and the caller is not in a partition
// already; otherwise calls f as it is. An exception from f reaches the caller.
void run_on_threads(int threads, const std::function<void()>& f);

}  // namespace lsi
