// The explicit two-phase (saturated, single-point) MPM solver, separate from the single-phase
// Solver so that dry scenes allocate no liquid field and run no liquid kernel. One step:
//   time step (eq. 25, two_phase_time_step.hpp)
//   -> P2G of both phases + drag (two_phase_p2g.hpp)
//   -> grid update: liquid first, solid from the mixture; explicit or semi-implicit drag; walls
//      for both phases (two_phase_grid_update.hpp)
//   [-> barrier contact of both phases (the liquid without friction) -> barrier motion]
//   -> one pass over the points (two_phase_g2p.hpp, two_phase_g2p_update):
//      G2P of both phases, points move with the solid, health
//      -> effective stress: the single-phase per-point stress update on the skeleton
//         (stress_update.hpp: Jaumann + linear elastic / Mohr-Coulomb, volume)
//      -> pore pressure and porosity (pore_pressure_update.hpp; a pass of its own when the
//         free-surface drainage is on) -> the time-step limits of the next step
// Status and describe() are the single-phase ones (solver.hpp).
#pragma once
#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/mpm/stress_update.hpp"
#include "kernels/mpm/transfer_dissipation.hpp"
#include "kernels/mpm/two_phase/pore_pressure_update.hpp"
#include "kernels/mpm/two_phase/two_phase_energy.hpp"
#include "kernels/mpm/two_phase/two_phase_g2p.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/mirror_reaction.hpp"
#include "kernels/mpm/two_phase/two_phase_grid_update.hpp"
#include "kernels/mpm/two_phase/two_phase_p2g.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "kernels/mpm/two_phase/two_phase_time_step.hpp"
#include "kernels/common/constants.hpp"

namespace lsi::mpm::two_phase {

struct TwoPhaseSettings {
  double courant = 0.5;
  double max_time_step = std::numeric_limits<double>::infinity();   // s
  double min_time_step = 1e-12;                                     // s; below: collapse
  double gravity[2] = {0.0, -lsi::gravity};                                 // body force, m/s^2
  // The g in the definition of the hydraulic conductivity, k = kappa rho_L g / mu (m/s): a unit
  // convention, not the body force (a test without gravity still has a finite drag).
  double darcy_gravity = lsi::gravity;
  Drag drag = Drag::Explicit;         // explicit (the paper; permeability limit on dt) or
                                      // semi-implicit per node (no permeability limit)
  bool atomic_scatter = false;        // P2G with atomics instead of per-thread buffers (p2g.hpp)
  int scatter_tile_points = -1;       // points per tile of the atomic P2G, as Settings
  // Velocity transfer of both phases, as the single-phase Settings: APIC, or a FLIP/PIC blend
  // without affine terms (two_phase_g2p.hpp).
  Transfer transfer = Transfer::Apic;
  double flip_ratio = 0.99;           // FlipPic only: share of FLIP, [0, 1] (0: plain PIC)
  // Mirror-image wall correction of P2G (two_phase_p2g.hpp): removes the +15 % boundary layer of
  // stress and pore pressure next to walls the material rests on. Off by default (the
  // single-phase solver has no such correction); on in the column tests.
  bool wall_correction = false;
  double energy_growth_limit = 0.5;   // relative growth of the total energy deemed unstable
  // Optional stabilisations for saturated impacts (pore_pressure_update.hpp; docs/two_phase.md,
  // "Impacts": measured, none of them keeps the L3-B3 impact finite, so all are off by default).
  double bulk_viscosity_linear = 0.0;      // c1 of q = rho_m l |D| (c1 c + c2 l |D|), D < 0 only
  double bulk_viscosity_quadratic = 0.0;   // c2
  double free_surface_fill = 0.0;          // points whose neighbourhood fill is below: p = q = 0
  bool cell_pore_pressure = false;         // p projected to its cell's mean every step
  // Account the kinetic energy lost in the grid transfers of both phases
  // (transfer_dissipation.hpp): six reductions a step, off by default.
  bool track_transfer_dissipation = false;
};

template <class ExecSpace>
class TwoPhaseSolver {
 public:
  using Mem = typename ExecSpace::memory_space;

  // materials: skeleton materials (Material::density = grain density rho_S); walls act on the
  // solid, liquid_walls on the liquid (an impermeable boundary is a liquid wall).
  TwoPhaseSolver(TwoPhaseGrid<Mem> grid, TwoPhaseParticles<Mem> particles,
                 const std::vector<Material>& materials, Liquid liquid, Boundaries walls,
                 Boundaries liquid_walls, TwoPhaseSettings settings)
      : grid_(grid), particles_(particles), liquid_(liquid), walls_(walls),
        liquid_walls_(liquid_walls), settings_(settings), user_max_dt_(settings.max_time_step) {
    if (settings_.wall_correction) {
      for (const Boundaries* b : {&walls_, &liquid_walls_})
        for (const Wall* w : {&b->left, &b->right, &b->bottom, &b->top}) {
          const int d = (w == &b->left || w == &b->right) ? 0 : 1;
          const double i = (w->position - grid_.solid.origin[d]) / grid_.dx();
          if (w->active && std::abs(i - std::round(i)) > 1e-6)
            throw std::invalid_argument("two-phase wall correction: walls must lie on grid lines");
        }
    }
    if (settings_.atomic_scatter) atomic_scatter_ = TwoPhaseScatter<ExecSpace, true>(grid_.solid);
    else duplicated_scatter_ = TwoPhaseScatter<ExecSpace, false>(grid_.solid);
    if (settings_.scatter_tile_points >= 0) {
      atomic_scatter_.use_tiles(settings_.scatter_tile_points);
      duplicated_scatter_.use_tiles(settings_.scatter_tile_points);
    }
    Kokkos::View<PreparedMaterial*, Mem> table("two_phase_materials", materials.size());
    auto host = Kokkos::create_mirror_view(table);
    for (size_t i = 0; i < materials.size(); ++i) {
      host(i) = PreparedMaterial(materials[i]);
      plastic_ = plastic_ || materials[i].model == Material::Model::MohrCoulomb;
    }
    Kokkos::deep_copy(table, host);
    materials_ = table;
    // The larger of the two phases' speeds at each point: the larger of the two maxima.
    max_speed_ = std::max(largest_speed<ExecSpace>(particles_.solid.velocity, particles_.count),
                          largest_speed<ExecSpace>(particles_.liquid_velocity, particles_.count));
    initial_ = energy();
    max_mechanical_ = initial_.kinetic() + initial_.elastic + initial_.liquid;
  }
  // The same walls for both phases (no penetration of either: impermeable walls).
  TwoPhaseSolver(TwoPhaseGrid<Mem> grid, TwoPhaseParticles<Mem> particles,
                 const std::vector<Material>& materials, Liquid liquid, Boundaries walls,
                 TwoPhaseSettings settings)
      : TwoPhaseSolver(grid, particles, materials, liquid, walls, walls, settings) {}

  // Advances one step. Returns Running, or the reason the run must stop.
  Status step() {
    // The limits of the points as they are now: left by the last step's fused G2P, or computed.
    if (next_limits_current_)
      limits_ = next_limits_;
    else
      limits_ = two_phase_time_step_limits<ExecSpace>(
          particles_, materials_, liquid_, settings_.darcy_gravity,
          settings_.bulk_viscosity_linear, settings_.bulk_viscosity_quadratic, grid_.dx());
    next_limits_current_ = false;
    dt_ = two_phase_time_step(grid_.dx(), limits_, max_speed_, settings_.drag == Drag::Explicit,
                              settings_.courant, settings_.max_time_step);
    if (!(dt_ >= settings_.min_time_step)) return status_ = Status::TimeStepCollapse;
    const Boundaries* cw = settings_.wall_correction ? &walls_ : nullptr;
    const Boundaries* cl = settings_.wall_correction ? &liquid_walls_ : nullptr;
    const bool track = settings_.track_transfer_dissipation;
    if (track && !transfer_.points_before_current)
      transfer_.points_before = points_kinetic_energy();
    if (settings_.atomic_scatter)
      two_phase_p2g(particles_, grid_, atomic_scatter_, settings_.gravity, liquid_.density,
                    settings_.darcy_gravity, cw, cl);
    else
      two_phase_p2g(particles_, grid_, duplicated_scatter_, settings_.gravity, liquid_.density,
                    settings_.darcy_gravity, cw, cl);
    if (track) transfer_.grid_after_p2g = grid_kinetic_energy(GridState::AfterP2G);
    // The walls' reaction through the mirror images (mirror_reaction.hpp), before the grid
    // update narrows the grid's rectangle.
    double mirror[2] = {0.0, 0.0};
    if (settings_.wall_correction)
      mirror_wall_reaction<ExecSpace>(grid_, particles_, settings_.gravity, mirror);
    const GridUpdateReport gu = two_phase_grid_update<ExecSpace>(
        grid_, walls_, liquid_walls_, dt_, settings_.gravity, settings_.drag);
    boundary_ += gu.wall_dissipation;
    drag_ += gu.drag_dissipation;
    seepage_work_ += gu.seepage_gravity_work;
    wall_force_[0] = gu.wall_force[0] + mirror[0];
    wall_force_[1] = gu.wall_force[1] + mirror[1];
    if (barrier_.active()) barrier_step();
    if (track) transfer_.grid_after_update = grid_kinetic_energy(GridState::AfterUpdate);
    // G2P, the effective stress and (unless the free-surface drainage needs every point's new
    // volume first) the pore pressure and the next step's limits in one pass.
    TwoPhasePointWork work;
    work.plastic = plastic_;
    work.pore_pressure = !(settings_.free_surface_fill > 0.0);
    work.constants = {liquid_.density,
                      liquid_.bulk_modulus,
                      settings_.darcy_gravity,
                      settings_.bulk_viscosity_linear,
                      settings_.bulk_viscosity_quadratic,
                      grid_.dx()};
    const TwoPhaseG2PReport r =
        two_phase_g2p_update<ExecSpace>(particles_, grid_, dt_, materials_, work, cw, cl,
                                        settings_.transfer, settings_.flip_ratio);
    load_work_ += r.load_work;
    if (work.pore_pressure) {
      viscous_ += r.viscous_work;
      next_limits_ = r.limits;
      next_limits_current_ = true;
    } else {
      viscous_ += pore_pressure_update<ExecSpace>(
          particles_, grid_, liquid_, dt_, materials_,
          BulkViscosity{settings_.bulk_viscosity_linear, settings_.bulk_viscosity_quadratic},
          settings_.free_surface_fill);
    }
    if (settings_.cell_pore_pressure)
      viscous_ += project_pore_pressure<ExecSpace>(particles_, grid_, liquid_.bulk_modulus);
    if (track) transfer_.close_step(points_kinetic_energy());
    time_ += dt_;
    ++steps_;
    max_speed_ = r.health.max_speed;
    if (r.health.non_finite > 0) return status_ = Status::NonFinite;
    if (r.health.outside > 0) return status_ = Status::LeftGrid;
    return status_ = Status::Running;
  }

  // Runs to end_time, calling on_output at t = 0 and every output_interval (and at the end);
  // the energy growth is checked at each output (as Solver::run).
  Status run(double end_time, double output_interval,
             const std::function<void(const TwoPhaseSolver&)>& on_output = {},
             const std::function<bool(const TwoPhaseSolver&)>& done = {}) {
    return status_ = run_loop(
        *this, end_time, output_interval, settings_.max_time_step, user_max_dt_,
        settings_.min_time_step, [this] { return step(); }, [this] { return energy_grew(); },
        on_output, done);
  }

  TwoPhaseEnergyReport energy() const {
    TwoPhaseEnergyReport e = two_phase_particle_energies<ExecSpace>(
        particles_, materials_, liquid_.bulk_modulus, settings_.gravity);
    e.time = time_;
    e.boundary = boundary_;
    e.drag = drag_;
    e.viscous = viscous_;
    e.seepage_potential = -seepage_work_;
    e.load_potential = -load_work_;
    return e;
  }
  // (total(t) - total(0)) relative to the largest kinetic + stored energy seen plus the
  // dissipated work and the change of the potentials (as Solver::energy_residual).
  double energy_residual(const TwoPhaseEnergyReport& e) const {
    return (e.total() - initial_.total()) / energy_scale(e);
  }
  // Kinetic energy lost in the grid transfers of both phases since the start (J/m; 0 unless
  // TwoPhaseSettings::track_transfer_dissipation), and the residual left once it is booked
  // (as Solver::energy_residual_unexplained).
  double transfer_dissipation() const { return transfer_.accumulated; }
  double energy_residual_unexplained(const TwoPhaseEnergyReport& e) const {
    return (e.total() - initial_.total() + transfer_.accumulated) / energy_scale(e);
  }

  // Code that changes the points' porosity, conductivity, material or volumetric rate between
  // steps must call this: the next step then recomputes the time-step limits instead of taking
  // those the last step's G2P left.
  void points_changed() {
    next_limits_current_ = false;
    transfer_.points_before_current = false;
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
  long steps() const { return steps_; }
  Status status() const { return status_; }
  const TimeStepLimits& time_step_limits() const { return limits_; }   // of the last step
  // N/m on the walls, last step: eq. 26 over the constrained nodes, plus the mirror images'
  // share with the wall correction (mirror_reaction.hpp).
  const double* wall_force() const { return wall_force_; }
  const TwoPhaseParticles<Mem>& particles() const { return particles_; }
  const TwoPhaseGrid<Mem>& grid() const { return grid_; }
  const TwoPhaseSettings& settings() const { return settings_; }
  const Liquid& liquid() const { return liquid_; }
  bool has_plasticity() const { return plastic_; }

 private:
  // Contact of both phases with the barrier: the solid with the face friction, the liquid
  // without (no shear stress in the pore liquid); the barrier moves under their sum.
  void barrier_step() {
    const Barrier& b = barrier_.barrier();
    const auto& m = b.motion;
    BarrierContactReport both = barrier_contact<ExecSpace>(
        grid_.solid, b.shape, m.displacement, m.velocity, b.face_friction, dt_);
    const BarrierContactReport l = barrier_contact<ExecSpace>(
        grid_.liquid, b.shape, m.displacement, m.velocity, 0.0, dt_);
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) both.force[k][d] += l.force[k][d];
    both.work += l.work;
    both.nodes += l.nodes;
    both.upstream_moment += l.upstream_moment;
    boundary_ += barrier_.apply(both, dt_);
  }

  double energy_scale(const TwoPhaseEnergyReport& e) const {
    return max_mechanical_ + std::abs(e.plastic) + std::abs(e.boundary) + std::abs(e.drag) +
           std::abs(e.viscous) + std::abs(e.potential - initial_.potential) +
           std::abs(e.seepage_potential) + std::abs(e.load_potential) + 1e-300;
  }
  // Kinetic energies of both phases, of the points and of the grid (transfer_dissipation.hpp).
  double points_kinetic_energy() const {
    const auto& p = particles_;
    return mpm::points_kinetic_energy<ExecSpace>(p.solid.mass, p.solid.velocity) +
           mpm::points_kinetic_energy<ExecSpace>(p.liquid_mass, p.liquid_velocity);
  }
  double grid_kinetic_energy(GridState state) const {
    return mpm::grid_kinetic_energy<ExecSpace>(grid_.solid, state) +
           mpm::grid_kinetic_energy<ExecSpace>(grid_.liquid, state);
  }
  bool energy_grew() {
    const TwoPhaseEnergyReport e = energy();
    max_mechanical_ = std::max(max_mechanical_, e.kinetic() + e.elastic + e.liquid);
    return !(energy_residual(e) <= settings_.energy_growth_limit);
  }

  TwoPhaseGrid<Mem> grid_;
  TwoPhaseParticles<Mem> particles_;
  Kokkos::View<const PreparedMaterial*, Mem> materials_;
  Liquid liquid_;
  Boundaries walls_, liquid_walls_;
  TwoPhaseSettings settings_;
  TwoPhaseScatter<ExecSpace, true> atomic_scatter_;
  TwoPhaseScatter<ExecSpace, false> duplicated_scatter_;
  double user_max_dt_;
  TimeStepLimits limits_;          // of the last step
  TimeStepLimits next_limits_;     // of the points as they are, when next_limits_current_
  bool next_limits_current_ = false;
  double max_speed_ = 0.0, dt_ = 0.0, time_ = 0.0;
  double boundary_ = 0.0, drag_ = 0.0, seepage_work_ = 0.0, load_work_ = 0.0, viscous_ = 0.0;
  double wall_force_[2] = {0.0, 0.0};
  long steps_ = 0;
  bool plastic_ = false;

  BarrierCoupling barrier_;
  TransferDissipation transfer_;
  Status status_ = Status::Running;
  TwoPhaseEnergyReport initial_;
  double max_mechanical_ = 0.0;
};

}  // namespace lsi::mpm::two_phase
