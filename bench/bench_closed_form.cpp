// Closed-form models, batched (kernels/closed_form/batch.hpp): samples per second on the default
// host execution space (OpenMP when built; set OMP_NUM_THREADS) and on Serial; and the empirical
// model's x^y alone (kernels/common/pow_nonnegative.hpp), values per second on one thread.
// Run: build/bench/bench_closed_form --benchmark_out=closed_form.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "kernels/closed_form/batch.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

namespace {
using namespace lsi;

template <class Exec>
struct Batch {
  using Mem = typename Exec::memory_space;
  Kokkos::View<double* [10], Kokkos::LayoutLeft, Mem> in_data;
  ClosedFormInputs<Mem> in;
  ClosedFormOutputs<Mem> out;
  explicit Batch(int n) : in_data("in", n) {
    auto h = Kokkos::create_mirror_view(in_data);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < n; ++i) {
      const double th = 1 + 2 * u(rng), L = 6 * th;
      h(i, 0) = th;
      h(i, 1) = 4 + 10 * u(rng);
      h(i, 2) = 1800;
      h(i, 3) = 1800 * L * th;
      h(i, 4) = L;
      h(i, 5) = 1e4 + 5e4 * u(rng);
      h(i, 6) = 0.5;
      h(i, 7) = 1.2 + 0.37 * u(rng);
      h(i, 8) = 0.25;
      h(i, 9) = 0.41;
    }
    Kokkos::deep_copy(in_data, h);
    auto col = [&](int k) { return Kokkos::subview(in_data, Kokkos::ALL, k); };
    in = {col(0), col(1), col(2), col(3), col(4), col(5), col(6), col(7), col(8), col(9)};
    out = {Kokkos::View<double*, Mem>("p", n), Kokkos::View<double*, Mem>("t1", n),
           Kokkos::View<double*, Mem>("t2", n), Kokkos::View<double*, Mem>("dx", n)};
  }
};

template <class Exec>
void analytical(benchmark::State& state) {
  Batch<Exec> b(state.range(0));
  for (auto _ : state) {
    evaluate_two_body_batch(Exec(), b.in, b.out);
    Exec().fence();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["threads"] = Exec().concurrency();
}

template <class Exec>
void empirical(benchmark::State& state) {
  Batch<Exec> b(state.range(0));
  for (auto _ : state) {
    evaluate_empirical_batch(Exec(), b.in, EmpiricalCoefficients{}, b.out);
    Exec().fence();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["threads"] = Exec().concurrency();
}

// Fr^a2 for 2^14 Froude numbers in [0.1, 10] (in the L1/L2) and a2 = -0.515.
struct PowInputs {
  std::vector<double> froude, power;
  PowInputs() : froude(1 << 14), power(1 << 14) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    for (double& x : froude) x = std::pow(10.0, u(rng));
  }
};

// pow_nonnegative_each: eight values at a time where the host has AVX-512 (the batched empirical
// model's way).
void pow_eight_lanes(benchmark::State& state) {
  PowInputs p;
  for (auto _ : state) {
    math::pow_nonnegative_each(p.froude.data(), -0.515, p.power.data(), int(p.froude.size()));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(p.froude.size()));
  state.counters["lanes"] = LSI_HOST_SIMD_LANES ? 8 : 1;
}

// pow_nonnegative one value at a time, kept scalar (the per-sample sweep kernel's way, and the
// batch's on hosts without AVX-512).
void pow_one_lane(benchmark::State& state) {
  PowInputs p;
  for (auto _ : state) {
    for (std::size_t k = 0; k < p.froude.size(); ++k)
      benchmark::DoNotOptimize(p.power[k] = math::pow_nonnegative(p.froude[k], -0.515));
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(p.froude.size()));
}

BENCHMARK(pow_eight_lanes);
BENCHMARK(pow_one_lane);
BENCHMARK_TEMPLATE(analytical, Kokkos::DefaultHostExecutionSpace)
    ->Arg(1 << 20)  // 128 MB of inputs and outputs: from and to DRAM
    ->Arg(1 << 16)  // 8 MB: in the L3
    ->UseRealTime();
BENCHMARK_TEMPLATE(empirical, Kokkos::DefaultHostExecutionSpace)->Arg(1 << 20)->UseRealTime();
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
BENCHMARK_TEMPLATE(analytical, Kokkos::Serial)->Arg(1 << 20)->UseRealTime();
BENCHMARK_TEMPLATE(empirical, Kokkos::Serial)->Arg(1 << 20)->UseRealTime();
#endif
}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("kokkos_version", std::to_string(KOKKOS_VERSION));
  benchmark::AddCustomContext("git_revision", LSI_GIT_REVISION);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
