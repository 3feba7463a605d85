// The explicit MPM solver: one time step is a handful of named kernels,
//   time step -> P2G -> grid update (walls) [-> barrier contact -> barrier motion]
//   -> G2P (+ health) -> stress update,
// templated on the Kokkos execution space so the same code runs on Serial, OpenMP and CUDA.
#pragma once
#include <Kokkos_Core.hpp>
#include <Kokkos_ScatterView.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "kernels/mpm/barrier_coupling.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/energy.hpp"
#include "kernels/mpm/g2p.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/grid_update.hpp"
#include "kernels/mpm/p2g.hpp"
#include "kernels/mpm/particle_extrema.hpp"
#include "kernels/mpm/particles.hpp"
#include "kernels/mpm/stress_update.hpp"
#include "kernels/mpm/run_loop.hpp"
#include "kernels/mpm/status.hpp"
#include "kernels/mpm/time_step.hpp"
#include "kernels/mpm/transfer_dissipation.hpp"
#include "kernels/common/constants.hpp"

namespace lsi::mpm {


struct Settings {
  double courant = 0.5;
  double max_time_step = std::numeric_limits<double>::infinity();   // s
  double min_time_step = 1e-12;                                     // s; below: collapse
  double gravity[2] = {0.0, -lsi::gravity};                                 // m/s^2
  Transfer transfer = Transfer::Apic;   // APIC, or a FLIP/PIC blend without affine terms
  double flip_ratio = 0.99;           // FlipPic only: share of FLIP, [0, 1] (0: plain PIC)
  bool atomic_scatter = false;        // P2G with atomics instead of per-thread buffers (p2g.hpp)
  // Points per tile of the atomic P2G (P2GScatter::tile_points): -1 the default (128 on a
  // device from 50 000 points on, none on the host), 0 none, n > 0 tiles of n points at any
  // size. A knob of the benchmarks and tests.
  int scatter_tile_points = -1;
  double energy_growth_limit = 0.5;   // relative growth of the total energy deemed unstable
  // Nodes with less mass than this fraction of the lightest point get gravity but no internal
  // force (grid_update.hpp: the small-mass instability at the edge of the B-spline support).
  // 0: off (momentum conserved to round-off); 1e-3 stabilises violent splashing flows.
  double small_mass_fraction = 0.0;
  // Account the kinetic energy lost in the grid transfers (transfer_dissipation.hpp): three
  // reductions a step, off by default.
  bool track_transfer_dissipation = false;
};

template <class ExecSpace>
class Solver {
 public:
  using Mem = typename ExecSpace::memory_space;

  Solver(Grid<Mem> grid, Particles<Mem> particles, const std::vector<Material>& materials,
         Boundaries walls, Settings settings)
      : grid_(grid), particles_(particles), walls_(walls), settings_(settings),
        user_max_dt_(settings.max_time_step) {
    if (settings_.atomic_scatter) atomic_scatter_ = P2GScatter<ExecSpace, true>(grid_);
    else duplicated_scatter_ = P2GScatter<ExecSpace, false>(grid_);
    if (settings_.scatter_tile_points >= 0) {
      atomic_scatter_.use_tiles(settings_.scatter_tile_points);
      duplicated_scatter_.use_tiles(settings_.scatter_tile_points);
    }
    Kokkos::View<PreparedMaterial*, Mem> table("materials", materials.size());
    auto host = Kokkos::create_mirror_view(table);
    wave_speed_ = 0.0;
    for (size_t i = 0; i < materials.size(); ++i) {
      host(i) = PreparedMaterial(materials[i]);
      wave_speed_ = std::max(wave_speed_, materials[i].wave_speed());
      plastic_ = plastic_ || materials[i].model == Material::Model::MohrCoulomb;
    }
    Kokkos::deep_copy(table, host);
    materials_ = table;
    max_speed_ = largest_speed<ExecSpace>(particles_.velocity, particles_.count);
    expansion_ = largest_expansion<ExecSpace>(particles_.volume, particles_.volume0,
                                              particles_.count);
    initial_ = energy();
    max_mechanical_ = initial_.kinetic + initial_.elastic;
    small_mass_ = settings_.small_mass_fraction *
                  lightest_mass<ExecSpace>(particles_.mass, particles_.count);
  }

  // Advances one step. Returns Running, or the reason the run must stop.
  Status step() {
    dt_ = stable_time_step(grid_.dx, wave_speed_, expansion_, max_speed_, settings_.courant,
                           settings_.max_time_step);
    if (!(dt_ >= settings_.min_time_step)) return status_ = Status::TimeStepCollapse;
    const bool track = settings_.track_transfer_dissipation;
    if (track && !transfer_.points_before_current)
      transfer_.points_before =
          points_kinetic_energy<ExecSpace>(particles_.mass, particles_.velocity);
    if (settings_.atomic_scatter) p2g(particles_, grid_, atomic_scatter_, settings_.gravity);
    else p2g(particles_, grid_, duplicated_scatter_, settings_.gravity);
    if (track)
      transfer_.grid_after_p2g = grid_kinetic_energy<ExecSpace>(grid_, GridState::AfterP2G);
    wall_force_[0] = wall_force_[1] = 0.0;
    boundary_ += grid_update<ExecSpace>(grid_, walls_, dt_, wall_force_, small_mass_,
                                        settings_.gravity);
    if (barrier_.active()) {
      const Barrier& b = barrier_.barrier();
      boundary_ += barrier_.apply(
          barrier_contact<ExecSpace>(grid_, b.shape, b.motion.displacement, b.motion.velocity,
                                     b.face_friction, dt_),
          dt_);
    }
    if (track)
      transfer_.grid_after_update = grid_kinetic_energy<ExecSpace>(grid_, GridState::AfterUpdate);
    // G2P and the stress update in one pass over the points (g2p.hpp).
    const G2PReport r =
        plastic_ ? g2p_stress_update<ExecSpace, true>(particles_, grid_, materials_, dt_,
                                                      settings_.transfer, settings_.flip_ratio)
                 : g2p_stress_update<ExecSpace, false>(particles_, grid_, materials_, dt_,
                                                       settings_.transfer, settings_.flip_ratio);
    if (track)
      transfer_.close_step(points_kinetic_energy<ExecSpace>(particles_.mass, particles_.velocity));
    time_ += dt_;
    ++steps_;
    max_speed_ = r.max_speed;
    expansion_ = r.max_expansion;
    if (r.non_finite > 0) return status_ = Status::NonFinite;
    if (r.outside > 0) return status_ = Status::LeftGrid;
    return status_ = Status::Running;
  }

  // Runs to end_time with outputs (run_loop.hpp): on_output at t = 0, every output_interval and
  // at the end, energy growth checked there, `done` may end the run early (Finished).
  Status run(double end_time, double output_interval,
             const std::function<void(const Solver&)>& on_output = {},
             const std::function<bool(const Solver&)>& done = {}) {
    return status_ = run_loop(
        *this, end_time, output_interval, settings_.max_time_step, user_max_dt_,
        settings_.min_time_step, [this] { return step(); }, [this] { return energy_grew(); },
        on_output, done);
  }

  EnergyReport energy() const {
    EnergyReport e = particle_energies<ExecSpace>(particles_, materials_, settings_.gravity);
    e.time = time_;
    e.boundary = boundary_;
    return e;
  }
  // (total(t) - total(0)) / (largest kinetic + elastic energy seen + dissipated work + change of
  // potential energy): the energy balance residual, relative.
  double energy_residual(const EnergyReport& e) const {
    return (e.total() - initial_.total()) / energy_scale(e);
  }
  // Kinetic energy lost in the grid transfers since the start (J/m; 0 unless
  // Settings::track_transfer_dissipation), and the residual left once it is booked:
  // (total(t) - total(0) + transfer loss) over the same scale as energy_residual().
  double transfer_dissipation() const { return transfer_.accumulated; }
  double energy_residual_unexplained(const EnergyReport& e) const {
    return (e.total() - initial_.total() + transfer_.accumulated) / energy_scale(e);
  }

  // The rigid barrier (barrier_coupling.hpp): attach before the first step.
  void attach_barrier(const Barrier& b) { barrier_.attach(b); }
  bool has_barrier() const { return barrier_.active(); }
  const Barrier& barrier() const { return barrier_.barrier(); }
  const BarrierContactReport& barrier_contact_report() const { return barrier_.contact(); }
  void take_barrier_impulse(double impulse[3][2]) { barrier_.take_impulse(impulse); }
  double take_barrier_moment_impulse() { return barrier_.take_moment_impulse(); }

  double time() const { return time_; }
  double time_step() const { return dt_; }
  // Largest V / V0 of a point after the last step, at least 1 (sets the next step, time_step.hpp).
  double max_expansion() const { return expansion_; }
  long steps() const { return steps_; }
  Status status() const { return status_; }
  const double* wall_force() const { return wall_force_; }   // N/m on the walls, last step
  const Particles<Mem>& particles() const { return particles_; }
  const Grid<Mem>& grid() const { return grid_; }
  const Settings& settings() const { return settings_; }
  bool has_plasticity() const { return plastic_; }

 private:
  double energy_scale(const EnergyReport& e) const {
    return max_mechanical_ + std::abs(e.plastic) + std::abs(e.boundary) +
           std::abs(e.potential - initial_.potential) + 1e-300;
  }
  bool energy_grew() {
    const EnergyReport e = energy();
    max_mechanical_ = std::max(max_mechanical_, e.kinetic + e.elastic);
    return !(energy_residual(e) <= settings_.energy_growth_limit);   // NaN counts as growth
  }

  Grid<Mem> grid_;
  Particles<Mem> particles_;
  Kokkos::View<const PreparedMaterial*, Mem> materials_;
  Boundaries walls_;
  Settings settings_;
  TransferDissipation transfer_;
  P2GScatter<ExecSpace, true> atomic_scatter_;
  P2GScatter<ExecSpace, false> duplicated_scatter_;
  double user_max_dt_;
  double expansion_ = 1.0;   // largest V / V0 of the last G2P (time_step.hpp)
  double wave_speed_ = 0.0, max_speed_ = 0.0, dt_ = 0.0, time_ = 0.0, boundary_ = 0.0;
  double wall_force_[2] = {0.0, 0.0};
  long steps_ = 0;
  bool plastic_ = false;

  double small_mass_ = 0.0;
  BarrierCoupling barrier_;
  Status status_ = Status::Running;
  EnergyReport initial_;
  double max_mechanical_ = 0.0;
};

}  // namespace lsi::mpm
