// MPM throughput (kernels/mpm): particle-updates per second, items_per_second = particles x steps /
// seconds of the timed loop (no I/O, no energy evaluation: Solver::step() only).
//
// Scene: a dry column on a rough base, L0 = 1 m wide, H0 = 2 m high (a = 2), 2 x 2 points per cell,
// n cells across L0 (n = 50: 20 000 points; n = 158: 199 712 points), a grid 4 L0 wide and H0 + 5
// cells high (about as many nodes as points), smooth left wall, base friction tan(phi). Material
// as in tests/mpm/test_mpm_column_collapse.cpp: rho 1800, nu 0.3, E = rho g H0 / 0.005, and for
// Mohr-Coulomb phi 30 deg, psi 0, c 0, tension cut-off 0. Both models start from the geostatic
// stress with K0 = 0.3, just below the active limit Ka = 0.333 of phi = 30 deg, so that the
// Mohr-Coulomb column yields in the first step (a collapsing column is near the active state);
// the elastic column uses the same start. The kernel benchmark of the Mohr-Coulomb stress update
// reports the share of points that took the return mapping (plastic_share: 5-12 % after 5 steps);
// every point pays for the principal stresses and the yield check. Each repetition of a `step/...`
// benchmark builds the column afresh and runs a fixed number of steps (400 at 20 k, 40 at 200 k
// points), so every repetition does the same physical work.
//
// Variants: the execution space (Serial, the default host space: OpenMP when compiled in, and in a
// CUDA build the device, with atomics, also at 2 000 000 and 8 000 000 points), the
// P2G scatter (one node-interleaved buffer per thread, "duplicated", or one buffer with atomic
// additions; Serial needs neither and always uses one plain buffer, so it is run once), and one
// benchmark per kernel called directly on a column advanced 5 steps: p2g (scatter + gather),
// grid_update, g2p alone, stress_update alone (without and with the Mohr-Coulomb return), and
// g2p_stress_* (G2P with the stress update fused in, what Solver::step() runs). The sort of the
// points by cell (kernels/mpm/sort_points.hpp; the solver's default interval in every step
// benchmark): step/.../mohr_coulomb/duplicated_unsorted never sorts the column (built in cell
// order), .../duplicated_shuffled_unsorted runs it with its points in a random order and never
// sorts, .../duplicated_shuffled sorts the shuffled points with the default interval. fork_join
// is one empty parallel region: the fixed cost of each kernel launch (20-30 us on 2 threads with
// OMP_WAIT_POLICY=passive on the development machine). The kernels are timed on warm caches, one
// at a time. Note that the stress_update_* and g2p_stress_* kernel benchmarks apply the same
// velocity gradient hundreds of times: the stress drifts onto the yield surface, so their
// plastic share is higher than in a real step.
//
// Run (the threads of the OpenMP space from OMP_NUM_THREADS, 1 and 2; docs/notes/performance.md has the
// numbers and how they were taken):
//   OMP_NUM_THREADS=2 OMP_PROC_BIND=false OMP_WAIT_POLICY=passive build/bench/bench_mpm
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// (--benchmark_filter=step/ for the whole steps only; --benchmark_out=mpm.json
//  --benchmark_out_format=json to keep the numbers.) On a machine shared with other work, run one
// benchmark at a time (--benchmark_filter='^NAME') when the cores are idle, and compare two
// builds by alternating single repetitions of each: the speed of the shared machine drifts by
// +-30 % over minutes.
#include "bench_context.hpp"
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/mpm/sort_points.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

namespace {
using namespace lsi::mpm;

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

template <class Exec>
struct Column {
  using Mem = typename Exec::memory_space;
  Grid<Mem> grid;
  Particles<Mem> particles;
  Material material;
  Boundaries walls;
  Settings settings;

  Column(int n, bool plastic, bool atomic) {
    const double L0 = 1.0, H0 = 2.0, dx = L0 / n;
    material.model = plastic ? Material::Model::MohrCoulomb : Material::Model::LinearElastic;
    material.density = 1800;
    material.poisson_ratio = 0.3;
    material.young_modulus = material.density * kG * H0 / 0.005;
    material.friction_angle = 30.0 * kPi / 180.0;
    material.dilatancy_angle = 0.0;
    material.cohesion = 0.0;
    material.tension_cutoff = 0.0;
    const double x0 = 2 * dx, y0 = 2 * dx;
    const double lo[2] = {0, 0}, hi[2] = {x0 + 4 * L0, y0 + H0 + 3 * dx};
    grid = Grid<Mem>(lo, hi, dx);
    BodySpec body;
    body.polygon = {{{x0, y0}}, {{x0 + L0, y0}}, {{x0 + L0, y0 + H0}}, {{x0, y0 + H0}}};
    body.points_per_cell_direction = 2;
    body.geostatic_k0 = 0.3;
    body.surface_y = y0 + H0;
    body.gravity = kG;
    particles = build_particles<Mem>({body}, {material}, lo, dx);
    walls.left = {true, x0, 0.0};
    walls.bottom = {true, y0, std::tan(material.friction_angle)};
    walls.right = {true, grid.upper(0) - 2 * dx, 0.0};
    settings.courant = 0.5;
    settings.atomic_scatter = atomic;
  }
};

void common_counters(benchmark::State& state, int count, int nodes, int threads) {
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(count));
  state.counters["particles"] = count;
  state.counters["grid_nodes"] = nodes;
  state.counters["threads"] = threads;
}

// The points of a column in a random order (a fixed seed): what a long run that never sorts its
// points (SolverSettings::sort_interval 0) comes to.
template <class Exec>
void shuffle_points(Column<Exec>& c) {
  std::vector<int> from(c.particles.count);
  std::iota(from.begin(), from.end(), 0);
  std::shuffle(from.begin(), from.end(), std::mt19937(12345));
  PointSorter<Exec> shuffle;
  shuffle.use_order(from);
  shuffle.apply(c.particles);
}

// Whole steps: time step, P2G, grid update with walls, G2P with the health check, stress update.
// sort_interval: -1 the solver's default, else SolverSettings::sort_interval.
template <class Exec>
void bm_step(benchmark::State& state, int n, bool plastic, bool atomic, int tiles, bool shuffled,
             int sort_interval) {
  Column<Exec> c(n, plastic, atomic);
  c.settings.scatter_tile_points = tiles;
  if (sort_interval >= 0) c.settings.sort_interval = sort_interval;
  if (shuffled) shuffle_points(c);
  Solver<Exec> solver(c.grid, c.particles, {c.material}, c.walls, c.settings);
  lsi::bench::step_each_iteration(state, solver);
  Exec().fence();
  common_counters(state, c.particles.count, c.grid.size(), Exec().concurrency());
}

enum class Kernel {
  P2G,
  P2GAtomic,
  GridUpdate,
  G2P,
  G2PStressElastic,
  G2PStressPlastic,
  StressElastic,
  StressPlastic,
  ForkJoin
};

template <class Exec>
void bm_kernel(benchmark::State& state, int n, Kernel k, int tiles, bool contiguous) {
  using Mem = typename Exec::memory_space;
  Column<Exec> c(n, true, k == Kernel::P2GAtomic);
  Solver<Exec> solver(c.grid, c.particles, {c.material}, c.walls, c.settings);
  for (int i = 0; i < 5; ++i) solver.step();  // nonzero velocities, gradients, stresses
  const double dt = solver.time_step();
  Kokkos::View<PreparedMaterial*, Mem> table("materials", 1);
  auto host = Kokkos::create_mirror_view(table);
  host(0) = PreparedMaterial(c.material);
  Kokkos::deep_copy(table, host);
  const Kokkos::View<const PreparedMaterial*, Mem> materials = table;
  P2GScatter<Exec, false> duplicated(c.grid);  // allocated once, as in the solver
  P2GScatter<Exec, true> atomic(c.grid);
  if (tiles >= 0) atomic.use_tiles(tiles);  // the variant asked for, at every size
  if (contiguous) atomic.tile_spread = false;
  const auto& p = c.particles;
  const auto& g = c.grid;
  double wall_force[2] = {0, 0};
  for (auto _ : state) {
    switch (k) {
      case Kernel::P2G:
        p2g(p, g, duplicated, c.settings.gravity);
        break;
      case Kernel::P2GAtomic:
        p2g(p, g, atomic, c.settings.gravity);
        break;
      case Kernel::GridUpdate:
        benchmark::DoNotOptimize(grid_update<Exec>(g, c.walls, dt, wall_force));
        break;
      case Kernel::G2P:
        benchmark::DoNotOptimize(g2p<Exec>(p, g, dt, c.settings.transfer, c.settings.flip_ratio));
        break;
      case Kernel::G2PStressElastic:
        benchmark::DoNotOptimize(g2p_stress_update<Exec, false>(
            p, g, materials, dt, c.settings.transfer, c.settings.flip_ratio));
        break;
      case Kernel::G2PStressPlastic:
        benchmark::DoNotOptimize(g2p_stress_update<Exec, true>(
            p, g, materials, dt, c.settings.transfer, c.settings.flip_ratio));
        break;
      case Kernel::StressElastic:
        stress_update<Exec, false>(p, materials, dt);
        break;
      case Kernel::StressPlastic:
        stress_update<Exec, true>(p, materials, dt);
        break;
      case Kernel::ForkJoin:  // one empty parallel region: the cost of each kernel launch
        Kokkos::parallel_for("fork_join", Kokkos::RangePolicy<Exec>(0, Exec().concurrency()),
                             KOKKOS_LAMBDA(const int){});
        break;
    }
    Exec().fence();
  }
  common_counters(state, p.count, g.size(), Exec().concurrency());
  if (k == Kernel::StressPlastic) {
    // Share of the points that took the return mapping in one more call.
    Kokkos::View<double*, Mem> before("before", p.count);
    Kokkos::deep_copy(before, p.plastic_work);
    stress_update<Exec, true>(p, materials, dt);
    int yielded = 0;
    const auto work = p.plastic_work;
    Kokkos::parallel_reduce(
        "count_plastic", Kokkos::RangePolicy<Exec>(0, p.count),
        KOKKOS_LAMBDA(const int q, int& s) { s += work(q) != before(q) ? 1 : 0; }, yielded);
    state.counters["plastic_share"] = static_cast<double>(yielded) / p.count;
  }
}

using lsi::bench::Scatters;

template <class Exec>
void register_space(Scatters scatters) {
  const std::string ex = lsi::bench::exec_name<Exec>();
  const bool with_atomic = scatters != Scatters::Plain;
  for (const auto& [n, steps] : lsi::bench::column_sizes(scatters)) {
    const std::string size = "/particles:" + std::to_string(8 * n * n);
    for (const bool plastic : {false, true}) {
      for (const bool atomic : {false, true}) {
        if (atomic && !with_atomic) continue;
        if (!atomic && scatters == Scatters::AtomicOnly) continue;
        // On a device: the atomic scatter without tiles ("/atomic", the default) and with
        // tiles of 128 points (kernels/mpm/p2g.hpp, scatter_tiles), and of 64 and 256 for
        // Mohr-Coulomb.
        std::vector<int> tilings = {-1};
        if (scatters == Scatters::AtomicOnly) tilings = {0, 128};
        if (scatters == Scatters::AtomicOnly && plastic) tilings = {0, 64, 128, 256};
        for (const int tiles : tilings) {
          const std::string name = "step/" + ex + (plastic ? "/mohr_coulomb" : "/elastic") +
                                   (with_atomic ? (atomic ? "/atomic" : "/duplicated") : "") +
                                   (tiles > 0 ? "_tiles:" + std::to_string(tiles) : "") + size;
          benchmark::RegisterBenchmark(name.c_str(), bm_step<Exec>, n, plastic, atomic, tiles,
                                       false, -1)
              ->Iterations(steps)
              ->UseRealTime()
              ->Unit(benchmark::kMillisecond);
        }
      }
    }
    // The sort of the points by cell (kernels/mpm/sort_points.hpp), Mohr-Coulomb on the host
    // with duplicated scatter buffers: the column as built (in cell order) never sorted
    // ("unsorted"), and the column in a random order, never sorted or sorted every
    // sort_interval steps (the default; the first sort before the first step).
    if (scatters != Scatters::AtomicOnly) {
      const std::string base = "step/" + ex + "/mohr_coulomb/" + (with_atomic ? "duplicated_" : "");
      struct V {
        std::string name;
        bool shuffled;
        int sort_interval;
      };
      for (const V& v :
           {V{"unsorted", false, 0}, V{"shuffled_unsorted", true, 0}, V{"shuffled", true, -1}}) {
        const std::string name = base + v.name + size;
        benchmark::RegisterBenchmark(name.c_str(), bm_step<Exec>, n, true, false, -1, v.shuffled,
                                     v.sort_interval)
            ->Iterations(steps)
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
      }
    }
    struct K {
      Kernel k;
      std::string name;
      int tiles = -1;
      bool contiguous = false;
    };
    std::vector<K> kernels = {{Kernel::GridUpdate, "grid_update"},
                              {Kernel::G2P, "g2p"},
                              {Kernel::StressElastic, "stress_update_elastic"},
                              {Kernel::StressPlastic, "stress_update_plastic"},
                              {Kernel::G2PStressElastic, "g2p_stress_elastic"},
                              {Kernel::G2PStressPlastic, "g2p_stress_plastic"}};
    if (n == 50) kernels.push_back({Kernel::ForkJoin, "fork_join"});
    if (with_atomic) kernels.insert(kernels.begin(), {Kernel::P2GAtomic, "p2g_atomic", 0});
    if (scatters == Scatters::AtomicOnly)
      for (const int tiles : {64, 128, 256})
        for (const bool contiguous : {false, true})
          kernels.insert(kernels.begin() + 1, {Kernel::P2GAtomic,
                                               "p2g_atomic_tiles:" + std::to_string(tiles) +
                                                   (contiguous ? "_contiguous" : ""),
                                               tiles, contiguous});
    if (scatters != Scatters::AtomicOnly)
      kernels.insert(kernels.begin(), {Kernel::P2G, with_atomic ? "p2g_duplicated" : "p2g"});
    for (const auto& k : kernels) {
      const std::string name = "kernel/" + ex + "/" + k.name + size;
      benchmark::RegisterBenchmark(name.c_str(), bm_kernel<Exec>, n, k.k, k.tiles, k.contiguous)
          ->UseRealTime()
          ->Unit(benchmark::kMicrosecond);
    }
  }
}
}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  benchmark::Initialize(&argc, argv);
  using Host = Kokkos::DefaultHostExecutionSpace;
#ifdef KOKKOS_ENABLE_SERIAL
  if constexpr (!std::is_same_v<Host, Kokkos::Serial>) register_space<Host>(Scatters::Both);
  register_space<Kokkos::Serial>(Scatters::Plain);
#else
  register_space<Host>(Scatters::Both);
#endif
  // A device (CUDA build): the column on it too, with atomics, up to 8 M points.
  using Device = Kokkos::DefaultExecutionSpace;
  if constexpr (!std::is_same_v<Device, Host>) register_space<Device>(Scatters::AtomicOnly);
  lsi::bench::add_kokkos_context(LSI_GIT_REVISION);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
