// What every Kokkos benchmark program of bench/ shares: the name of an execution space in
// benchmark names, the Kokkos configuration and git revision in the JSON context (so that two
// result files say what they measured), and a solver stepped for as long as the benchmark runs.
#pragma once
#include <Kokkos_Core.hpp>
#include <benchmark/benchmark.h>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace lsi::bench {

template <class Exec>
std::string exec_name() {
#ifdef KOKKOS_ENABLE_SERIAL
  if constexpr (std::is_same_v<Exec, Kokkos::Serial>) return "Serial";
#endif
  return std::string(Exec::name());
}

inline std::string kokkos_backends() {
  std::string s;
  auto add = [&](const char* b) { s += (s.empty() ? "" : ",") + std::string(b); };
#ifdef KOKKOS_ENABLE_SERIAL
  add("Serial");
#endif
#ifdef KOKKOS_ENABLE_OPENMP
  add("OpenMP");
#endif
#ifdef KOKKOS_ENABLE_THREADS
  add("Threads");
#endif
#ifdef KOKKOS_ENABLE_CUDA
  add("Cuda");
#endif
#ifdef KOKKOS_ENABLE_HIP
  add("HIP");
#endif
  return s;
}

// Kokkos version and backends, the git revision, the default execution spaces and the host's
// concurrency, as custom context of the benchmark output.
inline void add_kokkos_context(const char* git_revision) {
  using Host = Kokkos::DefaultHostExecutionSpace;
  benchmark::AddCustomContext("kokkos_version", std::to_string(KOKKOS_VERSION));
  benchmark::AddCustomContext("kokkos_backends", kokkos_backends());
  benchmark::AddCustomContext("git_revision", git_revision);
  benchmark::AddCustomContext("default_execution_space", Kokkos::DefaultExecutionSpace::name());
  benchmark::AddCustomContext("default_host_execution_space", Host::name());
  benchmark::AddCustomContext("default_host_concurrency", std::to_string(Host().concurrency()));
}

// Which P2G scatters a space runs: host spaces with threads both, Serial its plain one (it needs
// neither), a device atomics only (per-thread copies are for host threads).
enum class Scatters { Both, Plain, AtomicOnly };

// The column sizes of bench_mpm and bench_impact as (cells across L0, steps per repetition): 20 000
// and 199 712 points everywhere (2 x 2 points per cell, 8 n^2), and 2 000 000 and 8 000 000 points
// on a device, which needs millions of points to fill (docs/guide/cuda.md).
inline std::vector<std::pair<int, int>> column_sizes(Scatters scatters) {
  std::vector<std::pair<int, int>> sizes = {{50, 400}, {158, 40}};
  if (scatters == Scatters::AtomicOnly) sizes.insert(sizes.end(), {{500, 40}, {1000, 20}});
  return sizes;
}

// One solver step per benchmark iteration; a step that does not leave the solver running
// (unstable, finished) ends the benchmark with the solver's status as its error.
template <class SolverT>
void step_each_iteration(benchmark::State& state, SolverT& solver) {
  for (auto _ : state) {
    const auto s = solver.step();
    if (s != std::remove_cv_t<decltype(s)>::Running) {
      state.SkipWithError(describe(s));
      break;
    }
  }
}

}  // namespace lsi::bench
