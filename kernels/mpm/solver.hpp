// The explicit MPM solver: one time step is a handful of named kernels,
//   time step -> P2G -> grid update (walls) [-> barrier contact -> barrier motion]
//   -> G2P (+ health) -> stress update,
// with the diagnostics (the transfer dissipation's account) as observers of its stages and the
// plumbing shared with the saturated solver in solver_base.hpp,
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
#include "kernels/mpm/scatter_choice.hpp"
#include "kernels/mpm/solver_base.hpp"
#include "kernels/mpm/solver_settings.hpp"
#include "kernels/mpm/sort_points.hpp"
#include "kernels/mpm/status.hpp"
#include "kernels/mpm/time_step.hpp"
#include "kernels/mpm/transfer_dissipation.hpp"
#include "kernels/common/constants.hpp"

namespace lsi::mpm {

// The dry solver's settings: the shared ones and the small-mass cut.
struct Settings : SolverSettings {
  // Nodes with less mass than this fraction of the lightest point get gravity but no internal
  // force (grid_update.hpp: the small-mass instability at the edge of the B-spline support).
  // 0: off (momentum conserved to round-off); 1e-3 stabilises violent splashing flows.
  double small_mass_fraction = 0.0;
};
template <class ExecSpace>
class Solver : public SolverBase<Solver<ExecSpace>, ExecSpace, Settings> {
  using Base = SolverBase<Solver<ExecSpace>, ExecSpace, Settings>;
  friend Base;

 public:
  using Mem = typename ExecSpace::memory_space;

  Solver(Grid<Mem> grid, Particles<Mem> particles, const std::vector<Material>& materials,
         Boundaries walls, Settings settings)
      : Base(settings),
        grid_(grid),
        particles_(particles),
        walls_(walls),
        scatter_(grid_, settings.atomic_scatter, settings.scatter_tile_points) {
    wave_speed_ = this->prepare_materials(materials, "materials");
    this->prepare_wall_bands(walls_, grid_);
    this->max_speed_ = largest_speed<ExecSpace>(particles_.velocity, particles_.count);
    expansion_ =
        largest_expansion<ExecSpace>(particles_.volume, particles_.volume0, particles_.count);
    initial_ = energy();
    this->max_mechanical_ = initial_.kinetic + initial_.elastic;
    small_mass_ = this->settings_.small_mass_fraction *
                  lightest_mass<ExecSpace>(particles_.mass, particles_.count);
  }

  // Advances one step. Returns Running, or the reason the run must stop.
  Status step() {
    const Settings& s = this->settings_;
    if (!this->take_time_step(stable_time_step(grid_.dx, wave_speed_, expansion_, this->max_speed_,
                                               s.courant, s.max_time_step)))
      return this->status_;
    if (this->sort_due()) sort_points();
    this->observe(StepStage::BeforeP2G);
    scatter_.visit([&](auto& scatter) { p2g(particles_, grid_, scatter, s.gravity); });
    this->observe(StepStage::AfterP2G);
    update_grid();
    if (this->barrier_.active()) contact_barrier();
    this->observe(StepStage::AfterGridUpdate);
    const G2PReport r = g2p_and_stress_update();
    this->observe(StepStage::AfterG2P);
    expansion_ = r.max_expansion;
    return this->end_step(r.max_speed, r.non_finite, r.outside);
  }

  EnergyReport energy() const {
    EnergyReport e =
        particle_energies<ExecSpace>(particles_, this->materials_, this->settings_.gravity);
    e.time = this->time_;
    e.boundary = this->boundary_;
    return e;
  }
  // (total(t) - total(0)) / (largest kinetic + elastic energy seen + dissipated work + change of
  // potential energy): the energy balance residual, relative.
  double energy_residual(const EnergyReport& e) const {
    return (e.total() - initial_.total()) / energy_scale(e);
  }
  // The residual left once the kinetic energy lost in the grid transfers is booked:
  // (total(t) - total(0) + transfer loss) over the same scale as energy_residual().
  double energy_residual_unexplained(const EnergyReport& e) const {
    return (e.total() - initial_.total() + this->transfer_.accumulated) / energy_scale(e);
  }

  // Largest V / V0 of a point after the last step, at least 1 (sets the next step, time_step.hpp).
  double max_expansion() const { return expansion_; }
  const Particles<Mem>& particles() const { return particles_; }
  const Grid<Mem>& grid() const { return grid_; }

 private:
  // The points in cell order (sort_points.hpp).
  void sort_points() {
    if (sorter_.order(particles_.position, particles_.count, grid_.origin[0], grid_.origin[1],
                      grid_.dx, grid_.nx, grid_.ny))
      sorter_.apply(particles_);
  }
  // The grid update with the walls (grid_update.hpp).
  void update_grid() {
    this->wall_force_[0] = this->wall_force_[1] = 0.0;
    this->boundary_ +=
        grid_update<ExecSpace>(grid_, walls_, this->dt_, this->wall_force_, small_mass_,
                               this->settings_.gravity, this->wall_bands_);
  }
  // Contact with the rigid barrier, which moves under it (barrier_coupling.hpp).
  void contact_barrier() {
    const Barrier& b = this->barrier_.barrier();
    this->barrier_.begin_step(grid_);
    this->boundary_ += this->barrier_.apply(
        barrier_contact<ExecSpace>(grid_, b.shape, b.motion.displacement, b.motion.velocity,
                                   b.face_friction, this->dt_, this->barrier_.row_impulse()),
        this->dt_);
  }
  // G2P and the stress update in one pass over the points (g2p.hpp).
  G2PReport g2p_and_stress_update() {
    const Settings& s = this->settings_;
    return this->plastic_
               ? g2p_stress_update<ExecSpace, true>(particles_, grid_, this->materials_, this->dt_,
                                                    s.transfer, s.flip_ratio)
               : g2p_stress_update<ExecSpace, false>(particles_, grid_, this->materials_, this->dt_,
                                                     s.transfer, s.flip_ratio);
  }

  // The diagnostics' kinetic energies (transfer_dissipation.hpp).
  double points_kinetic_energy() const {
    return mpm::points_kinetic_energy<ExecSpace>(particles_.mass, particles_.velocity);
  }
  double grid_kinetic_energy(GridState state) const {
    return mpm::grid_kinetic_energy<ExecSpace>(grid_, state);
  }

  double energy_scale(const EnergyReport& e) const {
    return this->max_mechanical_ + std::abs(e.plastic) + std::abs(e.boundary) +
           std::abs(e.potential - initial_.potential) + 1e-300;
  }
  bool energy_grew() {
    const EnergyReport e = energy();
    this->max_mechanical_ = std::max(this->max_mechanical_, e.kinetic + e.elastic);
    // NaN counts as growth.
    return !(energy_residual(e) <= this->settings_.energy_growth_limit);
  }

  Grid<Mem> grid_;
  Particles<Mem> particles_;
  Boundaries walls_;
  ScatterChoice<ExecSpace> scatter_;
  PointSorter<ExecSpace> sorter_;
  double expansion_ = 1.0;  // largest V / V0 of the last G2P (time_step.hpp)
  double wave_speed_ = 0.0;
  double small_mass_ = 0.0;
  EnergyReport initial_;
};

}  // namespace lsi::mpm
