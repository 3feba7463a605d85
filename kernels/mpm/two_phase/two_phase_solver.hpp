// The explicit two-phase (saturated, single-point) MPM solver, separate from the single-phase
// Solver so that dry scenes allocate no liquid field and run no liquid kernel. One step:
//   time step (eq. 25, two_phase_time_step.hpp)
//   -> P2G of both phases + drag (two_phase_p2g.hpp)
//   -> grid update: liquid first, solid from the mixture; explicit or semi-implicit drag; walls
//      for both phases (two_phase_grid_update.hpp); in one pass over the nodes with P2G's
//      gather where nothing runs between them (two_phase_p2g_grid_update.hpp)
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
#include "kernels/mpm/scatter_choice.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/mpm/solver_base.hpp"
#include "kernels/mpm/solver_settings.hpp"
#include "kernels/mpm/stress_update.hpp"
#include "kernels/mpm/transfer_dissipation.hpp"
#include "kernels/mpm/two_phase/pore_pressure_update.hpp"
#include "kernels/mpm/two_phase/two_phase_energy.hpp"
#include "kernels/mpm/two_phase/two_phase_g2p.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/mirror_reaction.hpp"
#include "kernels/mpm/two_phase/two_phase_grid_update.hpp"
#include "kernels/mpm/two_phase/two_phase_p2g.hpp"
#include "kernels/mpm/two_phase/two_phase_p2g_grid_update.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "kernels/mpm/two_phase/two_phase_time_step.hpp"
#include "kernels/common/constants.hpp"

namespace lsi::mpm::two_phase {

// The saturated solver's settings: the shared ones (solver_settings.hpp) and the liquid's.
struct TwoPhaseSettings : SolverSettings {
  // The g in the definition of the hydraulic conductivity, k = kappa rho_L g / mu (m/s): a unit
  // convention, not the body force (a test without gravity still has a finite drag).
  double darcy_gravity = lsi::gravity;
  Drag drag = Drag::Explicit;  // explicit (the paper; permeability limit on dt) or
                               // semi-implicit per node (no permeability limit)
  // Mirror-image wall correction of P2G (two_phase_p2g.hpp): removes the +15 % boundary layer of
  // stress and pore pressure next to walls the material rests on. Off by default (the
  // single-phase solver has no such correction); on in the column tests.
  bool wall_correction = false;
  // Optional stabilisations for saturated impacts (pore_pressure_update.hpp; docs/notes/two_phase.md,
  // "Impacts": measured, none of them keeps the L3-B3 impact finite, so all are off by default).
  double bulk_viscosity_linear = 0.0;     // c1 of q = rho_m l |D| (c1 c + c2 l |D|), D < 0 only
  double bulk_viscosity_quadratic = 0.0;  // c2
  double free_surface_fill = 0.0;         // points whose neighbourhood fill is below: p = q = 0
  bool cell_pore_pressure = false;        // p projected to its cell's mean every step
};

template <class ExecSpace>
class TwoPhaseSolver : public SolverBase<TwoPhaseSolver<ExecSpace>, ExecSpace, TwoPhaseSettings> {
  using Base = SolverBase<TwoPhaseSolver<ExecSpace>, ExecSpace, TwoPhaseSettings>;
  friend Base;

 public:
  using Mem = typename ExecSpace::memory_space;

  // materials: skeleton materials (Material::density = grain density rho_S); walls act on the
  // solid, liquid_walls on the liquid (an impermeable boundary is a liquid wall).
  TwoPhaseSolver(TwoPhaseGrid<Mem> grid, TwoPhaseParticles<Mem> particles,
                 const std::vector<Material>& materials, Liquid liquid, Boundaries walls,
                 Boundaries liquid_walls, TwoPhaseSettings settings)
      : Base(settings),
        grid_(grid),
        particles_(particles),
        liquid_(liquid),
        walls_(walls),
        liquid_walls_(liquid_walls),
        scatter_(grid_.solid, settings.atomic_scatter, settings.scatter_tile_points) {
    if (settings.wall_correction) {
      for (const Boundaries* b : {&walls_, &liquid_walls_})
        for (const Wall* w : {&b->left, &b->right, &b->bottom, &b->top}) {
          const int d = (w == &b->left || w == &b->right) ? 0 : 1;
          const double i = (w->position - grid_.solid.origin[d]) / grid_.dx();
          if (w->active && std::abs(i - std::round(i)) > 1e-6)
            throw std::invalid_argument("two-phase wall correction: walls must lie on grid lines");
        }
    }
    this->prepare_materials(materials, "two_phase_materials");
    // The larger of the two phases' speeds at each point: the larger of the two maxima.
    this->max_speed_ =
        std::max(largest_speed<ExecSpace>(particles_.solid.velocity, particles_.count),
                 largest_speed<ExecSpace>(particles_.liquid_velocity, particles_.count));
    initial_ = energy();
    this->max_mechanical_ = initial_.kinetic() + initial_.elastic + initial_.liquid;
  }
  // The same walls for both phases (no penetration of either: impermeable walls).
  TwoPhaseSolver(TwoPhaseGrid<Mem> grid, TwoPhaseParticles<Mem> particles,
                 const std::vector<Material>& materials, Liquid liquid, Boundaries walls,
                 TwoPhaseSettings settings)
      : TwoPhaseSolver(grid, particles, materials, liquid, walls, walls, settings) {}

  // Advances one step. Returns Running, or the reason the run must stop.
  Status step() {
    const TwoPhaseSettings& s = this->settings_;
    if (!this->take_time_step(two_phase_time_step(grid_.dx(), time_step_limits_now(),
                                                  this->max_speed_, s.drag == Drag::Explicit,
                                                  s.courant, s.max_time_step)))
      return this->status_;
    if (this->sort_due()) sort_points();
    this->observe(StepStage::BeforeP2G);
    if (!s.wall_correction && !s.track_transfer_dissipation) {
      // Nothing to do between P2G and the grid update: both in one pass over the nodes.
      scatter_.visit([&](auto& scatter) {
        book_grid_update(
            two_phase_p2g_grid_update(particles_, grid_, scatter, s.gravity, liquid_.density,
                                      s.darcy_gravity, walls_, liquid_walls_, this->dt_, s.drag),
            0.0, 0.0);
      });
    } else {
      scatter_.visit([&](auto& scatter) {
        two_phase_p2g(particles_, grid_, scatter, s.gravity, liquid_.density, s.darcy_gravity,
                      corrected_walls(), corrected_liquid_walls());
      });
      this->observe(StepStage::AfterP2G);
      update_grid();
    }
    if (this->barrier_.active()) contact_barrier();
    this->observe(StepStage::AfterGridUpdate);
    const TwoPhaseG2PReport r = g2p_and_point_updates();
    this->observe(StepStage::AfterG2P);
    return this->end_step(r.health.max_speed, r.health.non_finite, r.health.outside);
  }

  TwoPhaseEnergyReport energy() const {
    TwoPhaseEnergyReport e = two_phase_particle_energies<ExecSpace>(
        particles_, this->materials_, liquid_.bulk_modulus, this->settings_.gravity);
    e.time = this->time_;
    e.boundary = this->boundary_;
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
  // The residual left once the kinetic energy lost in the grid transfers of both phases is
  // booked (as Solver::energy_residual_unexplained).
  double energy_residual_unexplained(const TwoPhaseEnergyReport& e) const {
    return (e.total() - initial_.total() + this->transfer_.accumulated) / energy_scale(e);
  }

  // Code that changes the points' porosity, conductivity, material or volumetric rate between
  // steps must call this: the next step then recomputes the time-step limits instead of taking
  // those the last step's G2P left.
  void points_changed() {
    next_limits_current_ = false;
    this->transfer_.points_before_current = false;
  }

  const TimeStepLimits& time_step_limits() const { return limits_; }  // of the last step
  // N/m on the walls, last step: eq. 26 over the constrained nodes, plus the mirror images'
  // share with the wall correction (mirror_reaction.hpp).
  const double* wall_force() const { return this->wall_force_; }
  const TwoPhaseParticles<Mem>& particles() const { return particles_; }
  const TwoPhaseGrid<Mem>& grid() const { return grid_; }
  const Liquid& liquid() const { return liquid_; }

 private:
  // The points in cell order (sort_points.hpp), with every field of both phases.
  void sort_points() {
    const Particles<Mem>& s = particles_.solid;
    const Grid<Mem>& g = grid_.solid;
    if (!sorter_.order(s.position, particles_.count, g.origin[0], g.origin[1], g.dx, g.nx, g.ny))
      return;
    const TwoPhaseParticles<Mem>& p = particles_;
    sorter_.apply(s);
    sorter_.apply(p.liquid_velocity);
    sorter_.apply(p.liquid_affine);
    sorter_.apply(p.liquid_divergence);
    sorter_.apply(p.liquid_mass);
    sorter_.apply(p.porosity);
    sorter_.apply(p.pore_pressure);
    sorter_.apply(p.conductivity);
    sorter_.apply(p.traction);
    sorter_.apply(p.volumetric_rate);
    sorter_.apply(p.viscous_pressure);
  }
  // The time-step limits of the points as they are now: left by the last step's fused G2P, or
  // computed (two_phase_time_step.hpp).
  const TimeStepLimits& time_step_limits_now() {
    const TwoPhaseSettings& s = this->settings_;
    if (next_limits_current_)
      limits_ = next_limits_;
    else
      limits_ = two_phase_time_step_limits<ExecSpace>(particles_, this->materials_, liquid_,
                                                      s.darcy_gravity, s.bulk_viscosity_linear,
                                                      s.bulk_viscosity_quadratic, grid_.dx());
    next_limits_current_ = false;
    return limits_;
  }
  // The walls of the mirror-image correction, or none (two_phase_p2g.hpp).
  const Boundaries* corrected_walls() const {
    return this->settings_.wall_correction ? &walls_ : nullptr;
  }
  const Boundaries* corrected_liquid_walls() const {
    return this->settings_.wall_correction ? &liquid_walls_ : nullptr;
  }
  // The grid update of both phases with drag and walls (two_phase_grid_update.hpp); the walls'
  // reaction through the mirror images (mirror_reaction.hpp) is taken before it narrows the
  // grid's rectangle.
  void update_grid() {
    const TwoPhaseSettings& s = this->settings_;
    double mirror[2] = {0.0, 0.0};
    if (s.wall_correction) mirror_wall_reaction<ExecSpace>(grid_, particles_, s.gravity, mirror);
    book_grid_update(two_phase_grid_update<ExecSpace>(grid_, walls_, liquid_walls_, this->dt_,
                                                      s.gravity, s.drag),
                     mirror[0], mirror[1]);
  }
  // The grid update's dissipations and wall force, with the mirror images' share of the force.
  void book_grid_update(const GridUpdateReport& gu, const double mirror_x, const double mirror_y) {
    this->boundary_ += gu.wall_dissipation;
    drag_ += gu.drag_dissipation;
    seepage_work_ += gu.seepage_gravity_work;
    this->wall_force_[0] = gu.wall_force[0] + mirror_x;
    this->wall_force_[1] = gu.wall_force[1] + mirror_y;
  }
  // Contact of both phases with the barrier: the solid with the face friction, the liquid
  // without (no shear stress in the pore liquid); the barrier moves under their sum.
  void contact_barrier() {
    const Barrier& b = this->barrier_.barrier();
    const auto& m = b.motion;
    this->barrier_.begin_step(grid_.solid);  // both phases add into the face's rows
    BarrierContactReport both =
        barrier_contact<ExecSpace>(grid_.solid, b.shape, m.displacement, m.velocity,
                                   b.face_friction, this->dt_, this->barrier_.row_impulse());
    const BarrierContactReport l =
        barrier_contact<ExecSpace>(grid_.liquid, b.shape, m.displacement, m.velocity, 0.0,
                                   this->dt_, this->barrier_.row_impulse());
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) both.force[k][d] += l.force[k][d];
    both.work += l.work;
    both.nodes += l.nodes;
    both.upstream_moment += l.upstream_moment;
    this->boundary_ += this->barrier_.apply(both, this->dt_);
  }
  // G2P, the effective stress and (unless the free-surface drainage needs every point's new
  // volume first) the pore pressure and the next step's limits in one pass; then the
  // optional pore-pressure passes.
  TwoPhaseG2PReport g2p_and_point_updates() {
    const TwoPhaseSettings& s = this->settings_;
    TwoPhasePointWork work;
    work.plastic = this->plastic_;
    work.pore_pressure = !(s.free_surface_fill > 0.0);
    work.constants = {liquid_.density,         liquid_.bulk_modulus,       s.darcy_gravity,
                      s.bulk_viscosity_linear, s.bulk_viscosity_quadratic, grid_.dx()};
    const TwoPhaseG2PReport r = two_phase_g2p_update<ExecSpace>(
        particles_, grid_, this->dt_, this->materials_, work, corrected_walls(),
        corrected_liquid_walls(), s.transfer, s.flip_ratio);
    load_work_ += r.load_work;
    if (work.pore_pressure) {
      viscous_ += r.viscous_work;
      next_limits_ = r.limits;
      next_limits_current_ = true;
    } else {
      viscous_ += pore_pressure_update<ExecSpace>(
          particles_, grid_, liquid_, this->dt_, this->materials_,
          BulkViscosity{s.bulk_viscosity_linear, s.bulk_viscosity_quadratic}, s.free_surface_fill);
    }
    if (s.cell_pore_pressure)
      viscous_ += project_pore_pressure<ExecSpace>(particles_, grid_, liquid_.bulk_modulus);
    return r;
  }

  double energy_scale(const TwoPhaseEnergyReport& e) const {
    return this->max_mechanical_ + std::abs(e.plastic) + std::abs(e.boundary) + std::abs(e.drag) +
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
    this->max_mechanical_ = std::max(this->max_mechanical_, e.kinetic() + e.elastic + e.liquid);
    return !(energy_residual(e) <= this->settings_.energy_growth_limit);
  }

  TwoPhaseGrid<Mem> grid_;
  TwoPhaseParticles<Mem> particles_;
  Liquid liquid_;
  Boundaries walls_, liquid_walls_;
  ScatterChoice<ExecSpace, node_field::Count> scatter_;
  PointSorter<ExecSpace> sorter_;
  TimeStepLimits limits_;       // of the last step
  TimeStepLimits next_limits_;  // of the points as they are, when next_limits_current_
  bool next_limits_current_ = false;
  double drag_ = 0.0, seepage_work_ = 0.0, load_work_ = 0.0, viscous_ = 0.0;
  TwoPhaseEnergyReport initial_;
};

}  // namespace lsi::mpm::two_phase
