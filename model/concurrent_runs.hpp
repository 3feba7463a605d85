// Independent runs of one campaign side by side: the MPM samples of a sweep, the cases of a
// calibration, the runs of an accuracy study. A small scene keeps two threads only partly busy
// (each step is a few parallel regions over few points), while two scenes, one per thread, keep
// both busy: the campaign's throughput, not one run's speed, is what such work needs.
//
// With Kokkos' OpenMP backend (Kokkos 3) the threads are split into partitions of one thread
// each (Kokkos::OpenMP::partition_master, nested OpenMP); each partition takes the next task
// until none is left. On a GPU (CUDA, with OpenMP on the host) the host's threads are split the
// same way and each partition launches its runs' kernels on a CUDA stream of its own
// (kernels/common/own_stream.hpp): a small scene's step is a dozen short kernels and the waits
// for its reductions, and the runs fill the device between each other's. Elsewhere (Serial,
// Kokkos 4, one thread, one task) the tasks run one after the other with every thread. A run's
// numbers depend on its thread count by round-off only (the order of its sums), not on which
// tasks share the machine.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace lsi {

// How many runs of a campaign of `tasks` would run at once: at most runs_at_once (0: as many as
// the host backend has threads), at most tasks, 1 where partitions are not available. Starts
// Kokkos (ensure_kokkos) where partitions are available and tasks >= 2: the count is that of its
// threads, and the partitions are its own.
int concurrent_runs(std::size_t tasks, int runs_at_once = 0);

// How many of `runs` runs at once fit in memory side by side (the campaigns' counts come from
// model/mpm_footprint.hpp, campaign_runs_that_fit): each counted at `run_bytes`, all of
// them within half of `available_bytes` (the other half for what the runs' sizes vary and the
// rest of the process), at least one; `available_bytes` 0 (unknown) or `run_bytes` <= 0 limit
// nothing.
int runs_that_fit(int runs, double run_bytes, std::uint64_t available_bytes);

// The memory runs side by side may take together: half of `available_bytes` (runs_that_fit's
// rule; an MPM sweep holds each sample to it as the sample starts).
double memory_for_runs(std::uint64_t available_bytes);

// Calls task(k) for k = 0 .. tasks - 1, concurrent_runs(tasks, runs_at_once) at a time. Every
// task runs even when another throws; then the first exception (by task index) is rethrown.
// While tasks share the machine, MPM progress lines are off (model/progress.hpp); with a
// `progress_label` the campaign shows its own instead: the runs done of the tasks
// (SampleProgress, in the --progress mode).
void run_concurrently(std::size_t tasks, const std::function<void(std::size_t)>& task,
                      int runs_at_once = 0, const std::string& progress_label = {});

// The largest number of runs at once any campaign may use, set from the command line
// (--runs-at-once; 0: as many as threads). 1 runs every campaign one run after the other.
void set_runs_at_once(int runs);
int runs_at_once();

}  // namespace lsi
