// How many of the host's threads one MPM run takes: one, or every thread. A step of the MPM is a
// dozen or more parallel regions; at each, a thread that slept since the last one must be woken
// (the wait policy, app/openmp_wait_policy.hpp), and the per-thread copies of the grid are summed.
// A small scene's regions are shorter than those wake-ups, so it runs faster on one thread than
// on two. A run with fewer points than two threads' worth of `points_per_thread()` therefore runs
// on one thread, and the other threads sleep through it; a larger run takes every thread. A
// saturated step has more regions than a dry one, with host work between them, so a saturated
// run needs more points per thread before a second thread pays (docs/notes/performance.md,
// "Threads per run").
//
// With Kokkos' OpenMP backend (Kokkos 3) the one-thread run goes to a partition of one thread
// (Kokkos::OpenMP::partition_master, as the runs of a campaign, model/concurrent_runs.hpp). A
// partition of two or more threads is not used: GCC's OpenMP runtime starts a nested region's
// threads anew at every region. Elsewhere (Serial, Kokkos 4, a device: its kernels do not run on
// the host's threads) and inside a campaign's partition, where the run already has its own
// threads, the run takes every thread it is given. A run's numbers depend on its thread count by
// round-off only (the order of its sums).
#pragma once
#include <functional>

namespace lsi {

// The defaults of points_per_thread(): a run takes every thread from twice as many points on,
// about where a second thread starts to pay on the reference scenes, dry and saturated.
inline constexpr long kDefaultPointsPerThreadDry = 1024;
inline constexpr long kDefaultPointsPerThreadSaturated = 2048;

// One number of points per thread for every run, set from the command line
// (--points-per-thread); 0: every run takes every thread. reset_points_per_thread() goes back to
// the defaults.
void set_points_per_thread(long points);
void reset_points_per_thread();
long points_per_thread(bool saturated);

// Whether a run of `points` material points runs on one thread: fewer than
// 2 points_per_thread(saturated) points, on a build that can give a run one of several threads
// (Kokkos 3's OpenMP backend runs the kernels, with more than one thread) and not inside a
// parallel region.
bool runs_on_one_thread(long points, bool saturated);

// Calls f with the kernels on one thread (a partition of one) where runs_on_one_thread(points,
// saturated), else as it is. An exception from f reaches the caller.
void run_with_threads_for(long points, bool saturated, const std::function<void()>& f);

}  // namespace lsi
