// Sampling throughput of `lsi sweep` (sweeps/sampler.hpp): samples per second of sample_batch() for
// each design, items_per_second = samples drawn / seconds of the timed loop.
//
// Study: 5 inputs, as in a landslide-barrier sweep: a normal (flow velocity, 8 +- 1.5 m/s), a
// lognormal (flow density, mean 1800, sd 150 kg/m^3), a uniform (base friction 0.4..0.6), a
// truncated normal (flow thickness, 2 +- 0.5 m on [0.5, 4]), and a discrete input (barrier type,
// three values with weights 0.5/0.3/0.2). For Monte Carlo, Latin hypercube and Sobol the first two
// inputs are correlated (rho = 0.5 on the normal scores: one Cholesky row, two Phi^-1, one Phi);
// the Grid design takes no correlation and enumerates a 16^5 = 2^20 full factorial. Each iteration
// draws one batch of 2^20 samples into a preallocated 2^20 x 5 View on the default execution space
// (the OpenMP space when compiled in).
//
// Run (docs/theory/sampling.md has the numbers and the machine):
//   OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive OMP_PROC_BIND=false build/bench/bench_sampling
//       --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "sweeps/sampler.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

namespace {
using namespace lsi::sweeps;
using Exec = Kokkos::DefaultExecutionSpace;
using Mem = Exec::memory_space;
constexpr std::uint64_t kBatch = std::uint64_t{1} << 20;

std::vector<DistributionSpec> study_inputs(bool grid) {
  std::vector<DistributionSpec> in(5);
  in[0].kind = DistributionKind::Normal;
  in[0].mean = 8;
  in[0].sd = 1.5;
  in[1].kind = DistributionKind::Lognormal;
  in[1].mean = 1800;
  in[1].sd = 150;
  in[2].kind = DistributionKind::Uniform;
  in[2].min = 0.4;
  in[2].max = 0.6;
  in[3].kind = DistributionKind::TruncatedNormal;
  in[3].mean = 2;
  in[3].sd = 0.5;
  in[3].min = 0.5;
  in[3].max = 4;
  in[4].kind = DistributionKind::Discrete;
  in[4].values = {1, 2, 3};
  in[4].weights = {0.5, 0.3, 0.2};
  if (grid)
    for (auto& s : in) {
      s.values.clear();
      for (int k = 0; k < 16; ++k) s.values.push_back(k);
    }
  return in;
}

void BM_sample_batch(benchmark::State& state) {
  const auto design = static_cast<Design>(state.range(0));
  const bool grid = design == Design::Grid;
  std::vector<std::vector<double>> corr;
  if (!grid) {
    corr.assign(5, std::vector<double>(5, 0.0));
    for (int d = 0; d < 5; ++d) corr[d][d] = 1;
    corr[0][1] = corr[1][0] = 0.5;
  }
  const Sampler<Mem> sampler(study_inputs(grid), corr, design, 2024, kBatch);
  Kokkos::View<double**, Kokkos::LayoutLeft, Mem> out("samples", kBatch, 5);
  sample_batch(Exec(), sampler, 0, out);  // warm-up (first touch of the output pages)
  Exec().fence();
  for (auto _ : state) {
    sample_batch(Exec(), sampler, 0, out);
    Exec().fence();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetLabel(to_string(design));
}
BENCHMARK(BM_sample_batch)
    ->ArgName("design")
    ->Arg(static_cast<int>(Design::MonteCarlo))
    ->Arg(static_cast<int>(Design::LatinHypercube))
    ->Arg(static_cast<int>(Design::Sobol))
    ->Arg(static_cast<int>(Design::Grid))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("kokkos_version", std::to_string(KOKKOS_VERSION));
  benchmark::AddCustomContext("git_revision", LSI_GIT_REVISION);
  benchmark::AddCustomContext("execution_space", Exec::name());
  benchmark::AddCustomContext("concurrency", std::to_string(Exec().concurrency()));
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
