// Memory bandwidth of this machine, measured with Kokkos: the memory roof of the roofline in
// docs/notes/performance.md ("Roofline"). STREAM-like kernels over Views of doubles on the default host
// execution space (OpenMP when compiled in: set OMP_NUM_THREADS) and on Serial:
//   copy   c(i) = a(i)               16 B per element (STREAM's count: 1 read, 1 write)
//   triad  a(i) = b(i) + s c(i)      24 B per element (2 reads, 1 write)
//   read   sum += a(i)                8 B per element (a reduction: reads only)
//   write  a(i) = s                   8 B per element (writes only)
// bytes_per_second (SetBytesProcessed) uses STREAM's count above. A cache-based CPU without
// non-temporal stores also reads every written line before writing it (write-allocate): the
// counter `bytes_per_second_with_write_allocate` counts that read too (copy 24, triad 32, write
// 16 B per element), i.e. the traffic the memory really saw. The MPM kernels write with ordinary
// stores, so the second counter is the roof to compare them with.
//
// Sizes: elements:16777216 (128 MiB per array, 256-384 MiB in all: far beyond the 33 MiB L3;
// the DRAM roof), elements:262144 (2 MiB per array: in L3) and elements:16384 (128 KiB per array:
// in L2 of one core, 1 MiB; with 2 threads each thread holds half). Each thread sweeps its own
// contiguous chunk, 2^24 / elements times per parallel region (so that the fork-join of the region
// does not count), and fills it first (first touch). Host execution spaces only.
//
// Times: real_time (the rates above) and cpu_time = the CPU time of the whole process (all
// threads). On a machine shared with other work the threads wait for a CPU part of the time; with
// OMP_NUM_THREADS=1, bytes / cpu_time is the bandwidth of one core while it runs.
//
// Run (docs/notes/performance.md has the numbers; the machine is shared: repetitions and medians):
//   OMP_NUM_THREADS=1 OMP_PROC_BIND=false OMP_WAIT_POLICY=passive build/bench/bench_bandwidth
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//   OMP_NUM_THREADS=2 ... (the same)
#include "bench_context.hpp"
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cstdint>
#include <string>
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

namespace {

enum class Kind { Copy, Triad, Read, Write };

// STREAM's bytes per element, and with the write-allocate read of every written element.
constexpr int stream_bytes(Kind k) { return k == Kind::Copy ? 16 : k == Kind::Triad ? 24 : 8; }
constexpr int true_bytes(Kind k) {
  return k == Kind::Copy ? 24 : k == Kind::Triad ? 32 : k == Kind::Read ? 8 : 16;
}

// One parallel region per benchmark iteration: thread t takes the contiguous chunk t of the
// arrays and sweeps it `sweeps` times (an empty region costs 20-30 us on 2 threads here, as much
// as one sweep over an L2-sized array, so the in-cache sizes repeat the sweep inside the region).
// Plain host lambdas over raw pointers: the compiler vectorises the loops; ClobberMemory after
// each sweep keeps repeated sweeps from being merged.
template <class Exec>
void bm_stream(benchmark::State& state, Kind kind) {
  using Mem = typename Exec::memory_space;
  using V = Kokkos::View<double*, Mem>;
  const int64_t n = state.range(0);
  const int nt = Exec().concurrency();
  const int64_t sweeps = std::max<int64_t>(1, (int64_t{1} << 24) / n);
  V a(Kokkos::view_alloc(Kokkos::WithoutInitializing, "a"), n);
  V b(Kokkos::view_alloc(Kokkos::WithoutInitializing, "b"), n);
  V c(Kokkos::view_alloc(Kokkos::WithoutInitializing, "c"), n);
  V sums("sums", 8 * nt);  // one cache line per thread
  double* pa = a.data();
  double* pb = b.data();
  double* pc = c.data();
  double* ps = sums.data();
  const Kokkos::RangePolicy<Exec> threads(0, nt);
  auto chunk = [=](int t, int64_t& begin, int64_t& end) {
    begin = n * t / nt;
    end = n * (t + 1) / nt;
  };
  Kokkos::parallel_for("first_touch", threads, [=](const int t) {
    int64_t i0, i1;
    chunk(t, i0, i1);
    for (int64_t i = i0; i < i1; ++i) {
      pa[i] = 1.0;
      pb[i] = 2.0;
      pc[i] = 0.5;
    }
  });
  Exec().fence();
  const double s = 3.0;
  for (auto _ : state) {
    Kokkos::parallel_for("stream", threads, [=](const int t) {
      int64_t i0, i1;
      chunk(t, i0, i1);
      for (int64_t r = 0; r < sweeps; ++r) {
        switch (kind) {
          case Kind::Copy:
            for (int64_t i = i0; i < i1; ++i) pc[i] = pa[i];
            break;
          case Kind::Triad:
            for (int64_t i = i0; i < i1; ++i) pa[i] = pb[i] + s * pc[i];
            break;
          case Kind::Read: {
            // 8 independent partial sums: one chain of dependent additions would bound the loop
            // by the adder's latency, not by memory.
            double acc[8] = {0, 0, 0, 0, 0, 0, 0, 0};
            int64_t i = i0;
            for (; i + 8 <= i1; i += 8)
              for (int k = 0; k < 8; ++k) acc[k] += pa[i + k];
            for (; i < i1; ++i) acc[0] += pa[i];
            ps[8 * t] +=
                ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
            break;
          }
          case Kind::Write:
            for (int64_t i = i0; i < i1; ++i) pb[i] = s;
            break;
        }
        benchmark::ClobberMemory();
      }
    });
    Exec().fence();
  }
  benchmark::DoNotOptimize(ps[0]);
  const double bytes = static_cast<double>(state.iterations()) * sweeps * n;
  state.SetBytesProcessed(static_cast<int64_t>(bytes * stream_bytes(kind)));
  state.counters["bytes_per_second_with_write_allocate"] =
      benchmark::Counter(bytes * true_bytes(kind), benchmark::Counter::kIsRate);
  state.counters["array_MiB"] = static_cast<double>(n) * 8 / (1 << 20);
  state.counters["sweeps_per_region"] = static_cast<double>(sweeps);
  state.counters["threads"] = nt;
}

template <class Exec>
void register_space() {
  const std::string ex = lsi::bench::exec_name<Exec>();
  struct K {
    Kind k;
    const char* name;
  };
  for (const K k : {K{Kind::Copy, "copy"}, K{Kind::Triad, "triad"}, K{Kind::Read, "read"},
                    K{Kind::Write, "write"}}) {
    const std::string name = "stream/" + ex + "/" + k.name;
    benchmark::RegisterBenchmark(name.c_str(), bm_stream<Exec>, k.k)
        ->ArgName("elements")
        ->Arg(int64_t{1} << 24)
        ->Arg(int64_t{1} << 18)
        ->Arg(int64_t{1} << 14)
        ->UseRealTime()
        ->MeasureProcessCPUTime()
        ->Unit(benchmark::kMicrosecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  using Host = Kokkos::DefaultHostExecutionSpace;
  register_space<Host>();
#ifdef KOKKOS_ENABLE_SERIAL
  if constexpr (!std::is_same_v<Host, Kokkos::Serial>) register_space<Kokkos::Serial>();
#endif
  lsi::bench::add_kokkos_context(LSI_GIT_REVISION);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
