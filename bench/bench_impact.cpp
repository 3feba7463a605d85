// MPM impact throughput, and what each feature costs: the same scene run with and without the
// liquid phase, the barrier's dynamics, snapshots; and the two-phase (saturated) solver's step and
// kernels beside the dry one on the same column. docs/notes/performance.md ("Feature pruning", "Roofline")
// has the numbers and how they were taken.
//
// 1. impact/...: whole impact runs through the driver, as `lsi run` does them (parse_scene ->
//    impact_case -> run_mpm_case; histories every output interval, no HDF5 file), of
//    scenes/examples/impact-small.json (a 1 m thick front-body-tail flow at 4 m/s against a 2 m
//    wall) at 16 cells through the thickness (cell 0.0625 m: 4096 points) and
//    methods.mpm.end_time_s = 0.2 s (the first 0.8 m of the flow's travel: the impact; one
//    variant 0.02 s), the other settings the scene's defaults (APIC, duplicated scatter, 400
//    outputs). One run per iteration (Iterations(1)); use --benchmark_repetitions. Counters:
//      solver_pups       particles x steps / solver seconds (MpmOutcome::particle_updates_per_second:
//                        the solver loop without the output callbacks: histories, energies,
//                        snapshots)
//      items_per_second  particles x steps / the whole run (building the case and the points,
//                        outputs, snapshots included): end-to-end particle-updates/s
//      steps, particles, grid_nodes, solver_seconds, output_share (1 - solver seconds / run),
//      snapshots
//    Variants (the name says what is on):
//      dry/fixed                 single-phase landslide, fixed barrier (the cheapest)
//      dry/free                  + the barrier slides on its base (barrier dynamics)
//      dry/free/atomic           P2G with atomic additions instead of per-thread buffers
//      dry/free/snapshots        + particle snapshots every 0.02 s (11 snapshots)
//      saturated/fixed           two-phase landslide (semi-implicit drag), fixed barrier
//      saturated/free            + barrier dynamics (the scene's physics, as the paper)
//      saturated/free/atomic     P2G with atomics instead of per-thread buffers
//      saturated/free/explicit_drag/end:0.02s  the paper's explicit Darcy drag: its time step is
//                                about 10x smaller, so this one runs 0.02 s (as many steps as
//                                the others' 0.2 s; compare particle-updates/s, not run times)
//      saturated/free/snapshots  + snapshots every 0.02 s
//      saturated/free/cells:8    the scene as shipped (cell 0.125 m: 1024 points)
//    The driver runs on the default execution space: compare OMP_NUM_THREADS=1 and 2.
//
// 2. column_step/...: Solver::step() (dry) and TwoPhaseSolver::step() (saturated) on the column of
//    bench_mpm.cpp (1 m x 2 m, 2 x 2 points per cell, 20 000 or 199 712 points, the grid 4 L0
//    wide; Mohr-Coulomb phi 30 deg, geostatic start K0 = 0.3) with the same mixture: grains
//    2650 kg/m^3, porosity 0.4 (mixture 1990 kg/m^3; the dry column has the mixture's density),
//    water with K_L = 30 MPa, k = 1e-4 m/s. 400 steps per repetition at 20 k points, 40 at 200 k,
//    as bench_mpm. Variants: the execution space (the default host space and Serial), dry /
//    saturated with semi-implicit or explicit drag, duplicated / atomic scatter. In a CUDA build
//    the column also runs on the device (atomic scatter only), also at 2 000 000 and 8 000 000
//    points (40 and 20 steps): a GPU needs millions of points to fill (docs/guide/cuda.md).
//    items_per_second = particle-updates/s.
// 3. twophase_kernel/...: the two-phase kernels one at a time on that saturated column advanced 5
//    steps (warm caches, as bench_mpm's kernel/...): p2g (scatter into per-thread buffers or
//    atomically, then the gather over the touched nodes), grid_update (semi-implicit /
//    explicit drag), g2p, stress_update (the skeleton's Mohr-Coulomb update),
//    pore_pressure_update, time_step_limits (the separate kernels), and g2p_update (what the
//    solver runs: the last four fused in one pass over the points).
//    items_per_second = points / seconds per call.
//
// 4. campaign/...: a campaign of 8 whole impact runs (the dry fixed variant of 1. at 8 cells
//    through the thickness, cell 0.125 m: 1024 points; and at 16 cells) one after the other with
//    every thread (campaign/.../one_after_another) and side by side, one per thread
//    (campaign/.../side_by_side: model/concurrent_runs.hpp; on a GPU each host thread's runs on
//    a CUDA stream of its own). items_per_second = runs per second of the whole campaign; their
//    ratio is what running a campaign side by side gains. A CUDA build adds campaigns of 32 runs
//    (campaign/cells:N/runs:32/...).
//
// Times: real_time (the rates: items_per_second, solver_pups) and cpu_time = the CPU time of the
// whole process (all threads; MeasureProcessCPUTime). On a machine shared with other work the
// real time also counts the time the threads waited for a CPU; with OMP_NUM_THREADS=1,
// particles x steps / cpu_time is the rate of one core while it runs (docs/notes/performance.md).
//
// Run:
//   OMP_NUM_THREADS=2 OMP_PROC_BIND=false OMP_WAIT_POLICY=passive build/bench/bench_impact
//       --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//   (--benchmark_filter=^impact/ for the driver runs only; --benchmark_out=impact.json
//    --benchmark_out_format=json to keep the numbers; OMP_NUM_THREADS=1 for one thread.)
#include "bench_context.hpp"
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <string>
#include <type_traits>
#include <vector>

#include "model/concurrent_runs.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "model/run_threads.hpp"
#include "model/scene.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/mpm/two_phase/two_phase_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_solver.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time
#include "io/scene_parser.hpp"

namespace {
using namespace lsi;
using namespace lsi::mpm;
namespace tp = lsi::mpm::two_phase;

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// 1. Whole impact runs through the driver.

struct ImpactVariant {
  std::string name;
  bool saturated = true;
  bool fixed = false;
  bool atomic = false;
  bool explicit_drag = false;
  bool snapshots = false;
  double cell_size = 0.0625;
  double end_time = 0.2;  // s
};

constexpr double kSnapshotInterval = 0.02;  // s

nlohmann::json impact_scene(const ImpactVariant& v) {
  nlohmann::json j = read_scene_document(LSI_SOURCE_DIR "/scenes/examples/impact-small.json");
  j["name"] = "bench-impact";
  j["barrier"]["fixed"] = v.fixed;
  auto& m = j["methods"]["mpm"];
  m["cell_size_m"] = v.cell_size;
  m["end_time_s"] = v.end_time;
  m["phases"] = v.saturated ? "saturated" : "dry";
  if (v.saturated) m["drag"] = v.explicit_drag ? "explicit" : "semi-implicit";
  m["scatter"] = v.atomic ? "atomic" : "duplicated";
  if (v.snapshots) m["snapshot_interval_s"] = kSnapshotInterval;
  return j;
}

void bm_impact(benchmark::State& state, const ImpactVariant& v) {
  Scene scene;
  try {
    scene = parse_scene(impact_scene(v));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  int grid_nodes = 0;
  try {
    const MpmCase c = impact_case(scene);
    const double dx = c.settings.cell_size_m;
    grid_nodes = (static_cast<int>((c.upper[0] - c.lower[0]) / dx + 0.5) + 1) *
                 (static_cast<int>((c.upper[1] - c.lower[1]) / dx + 0.5) + 1);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  MpmOutcome o;
  double run_seconds = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    o = run_mpm_case(impact_case(scene));
    run_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.finished()) {
      state.SkipWithError(("the MPM run stopped: " + o.status()).c_str());
      return;
    }
  }
  const double updates = double(o.run().particles) * o.run().steps;
  state.SetItemsProcessed(static_cast<int64_t>(updates * state.iterations()));
  state.counters["solver_pups"] = o.run().particle_updates_per_second;
  state.counters["particles"] = o.run().particles;
  state.counters["steps"] = static_cast<double>(o.run().steps);
  state.counters["solver_seconds"] = o.run().solver_seconds;
  state.counters["output_share"] =
      1.0 - o.run().solver_seconds * state.iterations() / std::max(run_seconds, 1e-300);
  state.counters["snapshots"] = static_cast<double>(o.snapshots.size());
  state.counters["grid_nodes"] = grid_nodes;
  state.counters["threads"] = Kokkos::DefaultExecutionSpace().concurrency();
}

void register_impact() {
  std::vector<ImpactVariant> variants;
  auto add = [&](std::string name, bool saturated, bool fixed, bool atomic = false,
                 bool explicit_drag = false, bool snapshots = false, double cell = 0.0625,
                 double end_time = 0.2) {
    variants.push_back(
        {std::move(name), saturated, fixed, atomic, explicit_drag, snapshots, cell, end_time});
  };
  add("dry/fixed", false, true);
  add("dry/free", false, false);
  add("dry/free/atomic", false, false, true);
  add("dry/free/snapshots", false, false, false, false, true);
  add("saturated/fixed", true, true);
  add("saturated/free", true, false);
  add("saturated/free/atomic", true, false, true);
  // A ~10x smaller time step: 0.02 s of impact, about as many steps as the others' 0.2 s.
  add("saturated/free/explicit_drag/end:0.02s", true, false, false, true, false, 0.0625, 0.02);
  add("saturated/free/snapshots", true, false, false, false, true);
  add("saturated/free/cells:8", true, false, false, false, false, 0.125);
  for (const auto& v : variants) {
    const std::string name = "impact/" + v.name;
    benchmark::RegisterBenchmark(name.c_str(), bm_impact, v)
        ->Iterations(1)
        ->UseRealTime()
        ->MeasureProcessCPUTime()
        ->Unit(benchmark::kMillisecond);
  }
}

// ---------------------------------------------------------------------------------------------
// 2-3. The column of bench_mpm.cpp, dry or saturated.

struct ColumnSetup {
  double L0 = 1.0, H0 = 2.0, dx = 0.0, x0 = 0.0, y0 = 0.0;
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  Material skeleton;  // density: grains (saturated) or the mixture (dry)
  tp::Liquid liquid;
  double porosity = 0.4, conductivity = 1e-4;
  Boundaries walls, liquid_walls;

  ColumnSetup(int n, bool saturated) {
    dx = L0 / n;
    liquid.density = 1000;
    liquid.bulk_modulus = 30e6;
    const double rho_S = 2650, rho_m = (1 - porosity) * rho_S + porosity * liquid.density;
    skeleton.model = Material::Model::MohrCoulomb;
    skeleton.density = saturated ? rho_S : rho_m;
    skeleton.poisson_ratio = 0.3;
    skeleton.young_modulus = rho_m * kG * H0 / 0.005;
    skeleton.friction_angle = 30.0 * kPi / 180.0;
    skeleton.dilatancy_angle = 0.0;
    skeleton.cohesion = 0.0;
    skeleton.tension_cutoff = 0.0;
    x0 = 2 * dx;
    y0 = 2 * dx;
    hi[0] = x0 + 4 * L0;
    hi[1] = y0 + H0 + 3 * dx;
    walls.left = {true, x0, 0.0};
    walls.bottom = {true, y0, std::tan(skeleton.friction_angle)};
    walls.right = {true, x0 + 4 * L0 - 2 * dx, 0.0};
    liquid_walls = walls;  // impermeable, frictionless for the liquid (as the driver)
    liquid_walls.bottom.friction = 0.0;
  }
  std::vector<std::array<double, 2>> polygon() const {
    return {{{x0, y0}}, {{x0 + L0, y0}}, {{x0 + L0, y0 + H0}}, {{x0, y0 + H0}}};
  }
};

template <class Exec>
struct DryColumn {
  using Mem = typename Exec::memory_space;
  ColumnSetup s;
  Grid<Mem> grid;
  Particles<Mem> particles;
  DryColumn(int n) : s(n, false) {
    grid = Grid<Mem>(s.lo, s.hi, s.dx);
    BodySpec body;
    body.polygon = s.polygon();
    body.points_per_cell_direction = 2;
    body.geostatic_k0 = 0.3;
    body.surface_y = s.y0 + s.H0;
    body.gravity = kG;
    particles = build_particles<Mem>({body}, {s.skeleton}, s.lo, s.dx);
  }
};

template <class Exec>
struct WetColumn {
  using Mem = typename Exec::memory_space;
  ColumnSetup s;
  tp::TwoPhaseGrid<Mem> grid;
  tp::TwoPhaseParticles<Mem> particles;
  WetColumn(int n) : s(n, true) {
    grid = tp::TwoPhaseGrid<Mem>(s.lo, s.hi, s.dx);
    tp::TwoPhaseBodySpec body;
    body.polygon = s.polygon();
    body.points_per_cell_direction = 2;
    body.porosity = s.porosity;
    body.hydraulic_conductivity = s.conductivity;
    body.geostatic_k0 = 0.3;
    body.surface_y = s.y0 + s.H0;
    body.gravity = kG;
    particles = tp::build_two_phase_particles<Mem>({body}, {s.skeleton}, s.liquid, s.lo, s.dx);
  }
  tp::TwoPhaseSolver<Exec> solver(tp::Drag drag, bool atomic, int tiles = -1) const {
    tp::TwoPhaseSettings t;
    t.courant = 0.5;
    t.drag = drag;
    t.atomic_scatter = atomic;
    t.scatter_tile_points = tiles;
    return tp::TwoPhaseSolver<Exec>(grid, particles, {s.skeleton}, s.liquid, s.walls,
                                    s.liquid_walls, t);
  }
};

void common_counters(benchmark::State& state, int count, int nodes, int threads) {
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(count));
  state.counters["particles"] = count;
  state.counters["grid_nodes"] = nodes;
  state.counters["threads"] = threads;
}

enum class Phases { Dry, SemiImplicit, Explicit };

template <class Exec>
void bm_column_step(benchmark::State& state, int n, Phases phases, bool atomic, int tiles) {
  if (phases == Phases::Dry) {
    DryColumn<Exec> c(n);
    Settings st;
    st.courant = 0.5;
    st.atomic_scatter = atomic;
    st.scatter_tile_points = tiles;
    Solver<Exec> solver(c.grid, c.particles, {c.s.skeleton}, c.s.walls, st);
    lsi::bench::step_each_iteration(state, solver);
    Exec().fence();
    common_counters(state, c.particles.count, c.grid.size(), Exec().concurrency());
    return;
  }
  WetColumn<Exec> c(n);
  auto solver = c.solver(phases == Phases::Explicit ? tp::Drag::Explicit : tp::Drag::SemiImplicit,
                         atomic, tiles);
  lsi::bench::step_each_iteration(state, solver);
  Exec().fence();
  common_counters(state, c.particles.count, c.grid.size(), Exec().concurrency());
  state.counters["time_step"] = solver.time_step();
}

enum class TpKernel {
  P2G,
  P2GAtomic,
  GridUpdateSemiImplicit,
  GridUpdateExplicit,
  G2P,
  StressUpdate,
  PorePressure,
  TimeStepLimits,
  G2PUpdate
};

template <class Exec>
void bm_twophase_kernel(benchmark::State& state, int n, TpKernel k, int tiles, bool contiguous) {
  using Mem = typename Exec::memory_space;
  WetColumn<Exec> c(n);
  {
    auto solver = c.solver(tp::Drag::SemiImplicit, false);
    for (int i = 0; i < 5; ++i) solver.step();  // nonzero velocities, gradients, stresses
  }
  const auto& p = c.particles;
  const auto& g = c.grid;
  const double dt = 1e-5;
  Kokkos::View<PreparedMaterial*, Mem> table("materials", 1);
  auto host = Kokkos::create_mirror_view(table);
  host(0) = PreparedMaterial(c.s.skeleton);
  Kokkos::deep_copy(table, host);
  const Kokkos::View<const PreparedMaterial*, Mem> materials = table;
  // Per-thread copies only on host spaces (kHost); a device uses atomics.
  constexpr bool kHost = Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
  using Duplicated = tp::TwoPhaseScatter<Exec, !kHost>;
  Duplicated duplicated;  // allocated once, as in the solver
  tp::TwoPhaseScatter<Exec, true> atomic;
  if (k == TpKernel::P2G) duplicated = Duplicated(g.solid);
  if (k == TpKernel::P2GAtomic) atomic = tp::TwoPhaseScatter<Exec, true>(g.solid);
  if (tiles >= 0) atomic.use_tiles(tiles);  // the variant asked for, at every size
  if (contiguous) atomic.tile_spread = false;
  const double gravity[2] = {0.0, -kG};
  tp::TwoPhasePointWork fused;  // as the solver: Mohr-Coulomb, pore pressure, next limits
  fused.plastic = true;
  fused.pore_pressure = true;
  fused.constants = {c.s.liquid.density, c.s.liquid.bulk_modulus, kG, 0.0, 0.0, g.dx()};
  for (auto _ : state) {
    switch (k) {
      case TpKernel::P2G:
        tp::two_phase_p2g(p, g, duplicated, gravity, c.s.liquid.density, kG);
        break;
      case TpKernel::P2GAtomic:
        tp::two_phase_p2g(p, g, atomic, gravity, c.s.liquid.density, kG);
        break;
      case TpKernel::GridUpdateSemiImplicit:
        benchmark::DoNotOptimize(tp::two_phase_grid_update<Exec>(g, c.s.walls, c.s.liquid_walls, dt,
                                                                 gravity, tp::Drag::SemiImplicit));
        break;
      case TpKernel::GridUpdateExplicit:
        benchmark::DoNotOptimize(tp::two_phase_grid_update<Exec>(g, c.s.walls, c.s.liquid_walls, dt,
                                                                 gravity, tp::Drag::Explicit));
        break;
      case TpKernel::G2P:
        benchmark::DoNotOptimize(tp::two_phase_g2p<Exec>(p, g, dt));
        break;
      case TpKernel::StressUpdate:
        stress_update<Exec, true>(p.solid, materials, dt);
        break;
      case TpKernel::PorePressure:
        benchmark::DoNotOptimize(tp::pore_pressure_update<Exec>(p, g, c.s.liquid, dt, materials));
        break;
      case TpKernel::TimeStepLimits:
        benchmark::DoNotOptimize(
            tp::two_phase_time_step_limits<Exec>(p, materials, c.s.liquid, kG));
        break;
      case TpKernel::G2PUpdate:
        benchmark::DoNotOptimize(tp::two_phase_g2p_update<Exec>(p, g, dt, materials, fused));
        break;
    }
    Exec().fence();
  }
  common_counters(state, p.count, g.size(), Exec().concurrency());
}

using lsi::bench::Scatters;

template <class Exec>
void register_column(Scatters scatters) {
  const std::string ex = lsi::bench::exec_name<Exec>();
  std::vector<bool> atomics;
  if (scatters != Scatters::AtomicOnly) atomics.push_back(false);
  if (scatters != Scatters::Plain) atomics.push_back(true);
  auto label = [&](bool atomic) -> std::string {
    if (scatters == Scatters::Plain) return "";
    return atomic ? "/atomic" : "/duplicated";
  };
  for (const auto& [n, steps] : lsi::bench::column_sizes(scatters)) {
    const std::string size = "/particles:" + std::to_string(8 * n * n);
    struct P {
      Phases p;
      const char* name;
    };
    for (const P ph : {P{Phases::Dry, "dry"}, P{Phases::SemiImplicit, "saturated"},
                       P{Phases::Explicit, "saturated_explicit_drag"}}) {
      // On a device: the atomic scatter without tiles ("/atomic", the default) and with tiles
      // of 128 points (kernels/mpm/p2g.hpp, scatter_tiles).
      const std::vector<int> tilings =
          scatters == Scatters::AtomicOnly ? std::vector<int>{0, 128} : std::vector<int>{-1};
      for (const bool atomic : atomics) {
        for (const int tiles : tilings) {
          const std::string name = "column_step/" + ex + "/" + ph.name + label(atomic) +
                                   (tiles > 0 ? "_tiles:" + std::to_string(tiles) : "") + size;
          benchmark::RegisterBenchmark(name.c_str(), bm_column_step<Exec>, n, ph.p, atomic, tiles)
              ->Iterations(steps)
              ->UseRealTime()
              ->MeasureProcessCPUTime()
              ->Unit(benchmark::kMillisecond);
        }
      }
    }
    struct K {
      TpKernel k;
      std::string name;
      int tiles = -1;
      bool contiguous = false;
    };
    std::vector<K> kernels;
    for (const bool atomic : atomics)
      kernels.push_back({atomic ? TpKernel::P2GAtomic : TpKernel::P2G,
                         "p2g" + (label(atomic).empty() ? "" : "_" + label(atomic).substr(1)),
                         scatters == Scatters::AtomicOnly ? 0 : -1});
    if (scatters == Scatters::AtomicOnly)
      for (const int tiles : {64, 128, 256})
        for (const bool contiguous : {false, true})
          kernels.push_back(
              {TpKernel::P2GAtomic,
               "p2g_atomic_tiles:" + std::to_string(tiles) + (contiguous ? "_contiguous" : ""),
               tiles, contiguous});
    for (const K& k :
         {K{TpKernel::GridUpdateSemiImplicit, "grid_update_semi_implicit"},
          K{TpKernel::GridUpdateExplicit, "grid_update_explicit"}, K{TpKernel::G2P, "g2p"},
          K{TpKernel::StressUpdate, "stress_update_plastic"},
          K{TpKernel::PorePressure, "pore_pressure_update"},
          K{TpKernel::TimeStepLimits, "time_step_limits"}, K{TpKernel::G2PUpdate, "g2p_update"}})
      kernels.push_back(k);
    for (const auto& k : kernels) {
      const std::string name = "twophase_kernel/" + ex + "/" + k.name + size;
      benchmark::RegisterBenchmark(name.c_str(), bm_twophase_kernel<Exec>, n, k.k, k.tiles,
                                   k.contiguous)
          ->UseRealTime()
          ->MeasureProcessCPUTime()
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 4. A campaign of small runs, one after the other or side by side.

void bm_campaign(benchmark::State& state, double cell, bool side_by_side, int runs) {
  ImpactVariant v{"campaign", false, true};
  v.cell_size = cell;
  std::vector<MpmCase> cases;
  try {
    const Scene scene = parse_scene(impact_scene(v));
    for (int k = 0; k < runs; ++k) cases.push_back(impact_case(scene));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const int at_once = side_by_side ? 0 : 1;
  // One after the other: each run on every thread, whatever its points (model/run_threads.hpp).
  struct EveryThread {
    explicit EveryThread(bool on) : on(on) {
      if (on) set_points_per_thread(0);
    }
    ~EveryThread() {
      if (on) reset_points_per_thread();
    }
    bool on;
  } const every_thread(!side_by_side);
  for (auto _ : state) {
    std::vector<int> finished(cases.size(), 0);
    run_concurrently(
        cases.size(), [&](std::size_t k) { finished[k] = run_mpm_case(cases[k]).finished(); },
        at_once);
    for (int f : finished)
      if (!f) {
        state.SkipWithError("an MPM run of the campaign stopped");
        return;
      }
  }
  state.SetItemsProcessed(static_cast<int64_t>(cases.size() * state.iterations()));
  state.counters["runs_at_once"] = concurrent_runs(cases.size(), at_once);
  state.counters["threads"] = Kokkos::DefaultExecutionSpace().concurrency();
}

void register_campaign() {
  // A device build adds campaigns of 32 runs: a GPU host has more threads to drive runs.
  std::vector<int> sizes{8};
  if constexpr (!std::is_same_v<Kokkos::DefaultExecutionSpace, Kokkos::DefaultHostExecutionSpace>)
    sizes.push_back(32);
  for (const int runs : sizes)
    for (double cell : {0.125, 0.0625})
      for (bool side : {false, true}) {
        const std::string name = std::string("campaign/cells:") + (cell > 0.1 ? "8" : "16") +
                                 (runs == 8 ? "" : "/runs:" + std::to_string(runs)) +
                                 (side ? "/side_by_side" : "/one_after_another");
        benchmark::RegisterBenchmark(name.c_str(), bm_campaign, cell, side, runs)
            ->Iterations(1)
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
      }
}

}  // namespace

int main(int argc, char** argv) {
  // As the driver (ensure_kokkos): threads that may migrate, unless the user binds them.
  setenv("OMP_PROC_BIND", "false", /*overwrite=*/0);
  Kokkos::ScopeGuard kokkos(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  using Host = Kokkos::DefaultHostExecutionSpace;
  register_impact();
  register_campaign();
#ifdef KOKKOS_ENABLE_SERIAL
  if constexpr (!std::is_same_v<Host, Kokkos::Serial>) register_column<Host>(Scatters::Both);
  register_column<Kokkos::Serial>(Scatters::Plain);
#else
  register_column<Host>(Scatters::Both);
#endif
  // A device (CUDA build): the column on it too, with atomics.
  using Device = Kokkos::DefaultExecutionSpace;
  if constexpr (!std::is_same_v<Device, Host>) register_column<Device>(Scatters::AtomicOnly);
  lsi::bench::add_kokkos_context(LSI_GIT_REVISION);
  benchmark::AddCustomContext("impact_scene",
                              "scenes/examples/impact-small.json, cell 0.0625 m, "
                              "end_time_s 0.2");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
