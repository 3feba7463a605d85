// What the dry (solver.hpp) and the saturated (two_phase/two_phase_solver.hpp) MPM solver share:
// the clock (time, step, step count, status), the time-step bounds, the material table, the
// walls' reaction, the rigid barrier, the diagnostics that watch a step, and the output loop.
// Each solver adds its fields, its step() and its energy account. CRTP: Derived provides
//   Status step();  bool energy_grew();
//   double points_kinetic_energy() const;  double grid_kinetic_energy(GridState) const;
#pragma once
#include <Kokkos_Core.hpp>
#include <array>
#include <functional>
#include <vector>

#include "kernels/mpm/barrier_coupling.hpp"
#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/run_loop.hpp"
#include "kernels/mpm/status.hpp"
#include "kernels/mpm/transfer_dissipation.hpp"
#include "kernels/mpm/wall_bands.hpp"

namespace lsi::mpm {

// The stages of a step at which diagnostics look at the state; none of them changes it.
enum class StepStage { BeforeP2G, AfterP2G, AfterGridUpdate, AfterG2P };

template <class Derived, class ExecSpace, class SettingsT>
class SolverBase {
 public:
  using Mem = typename ExecSpace::memory_space;

  // Runs to end_time with outputs (run_loop.hpp): on_output at t = 0, every output_interval and
  // at the end, energy growth checked there, `done` may end the run early (Finished).
  Status run(double end_time, double output_interval,
             const std::function<void(const Derived&)>& on_output = {},
             const std::function<bool(const Derived&)>& done = {}) {
    Derived& self = derived();
    return status_ = run_loop(
               self, end_time, output_interval, settings_.max_time_step, user_max_dt_,
               settings_.min_time_step, [&self] { return self.step(); },
               [&self] { return self.energy_grew(); }, on_output, done);
  }

  // Kinetic energy lost in the grid transfers since the start (J/m; 0 unless
  // settings().track_transfer_dissipation).
  double transfer_dissipation() const { return transfer_.accumulated; }

  // The rigid barrier (barrier_coupling.hpp): attach before the first step.
  void attach_barrier(const Barrier& b) { barrier_.attach(b); }
  bool has_barrier() const { return barrier_.active(); }
  const Barrier& barrier() const { return barrier_.barrier(); }
  const BarrierContactReport& barrier_contact_report() const { return barrier_.contact(); }
  void take_barrier_impulse(double impulse[3][2]) { barrier_.take_impulse(impulse); }
  double take_barrier_moment_impulse() { return barrier_.take_moment_impulse(); }
  // The upstream face's normal impulse per height band since the last call (Barrier::
  // face_band_height; empty without bands).
  std::vector<double> take_barrier_band_impulse() { return barrier_.take_band_impulse(); }

  // The walls' normal impulse per wall (left, right, bottom, top) and band since the last call
  // (N s/m; wall_bands.hpp); empty vectors without bands or for an inactive wall.
  std::array<std::vector<double>, 4> take_wall_band_impulse() {
    return mpm::take_wall_band_impulse(wall_bands_);
  }
  const WallBands<Mem>& wall_bands() const { return wall_bands_; }

  double time() const { return time_; }
  double time_step() const { return dt_; }
  long steps() const { return steps_; }
  Status status() const { return status_; }
  const double* wall_force() const { return wall_force_; }  // N/m on the walls, last step
  const SettingsT& settings() const { return settings_; }
  bool has_plasticity() const { return plastic_; }

 protected:
  explicit SolverBase(const SettingsT& settings)
      : settings_(settings), user_max_dt_(settings.max_time_step) {}

  Derived& derived() { return static_cast<Derived&>(*this); }

  // The walls' bands (settings().wall_band > 0) for a grid with these walls.
  template <class GridT>
  void prepare_wall_bands(const Boundaries& walls, const GridT& grid) {
    wall_bands_ = make_wall_bands<Mem>(walls, grid, settings_.wall_band);
  }

  // The materials on the device; notes whether any is plastic. Returns the largest elastic wave
  // speed among them (m/s).
  double prepare_materials(const std::vector<Material>& materials, const char* label) {
    Kokkos::View<PreparedMaterial*, Mem> table(std::string(label), materials.size());
    auto host = Kokkos::create_mirror_view(table);
    double wave_speed = 0.0;
    for (size_t i = 0; i < materials.size(); ++i) {
      host(i) = PreparedMaterial(materials[i]);
      wave_speed = std::max(wave_speed, materials[i].wave_speed());
      plastic_ = plastic_ || materials[i].model == Material::Model::MohrCoulomb;
    }
    Kokkos::deep_copy(table, host);
    materials_ = table;
    return wave_speed;
  }

  // Whether this step begins with a sort of the points (SolverSettings::sort_interval): the
  // first step and every sort_interval-th after it.
  bool sort_due() const {
    return settings_.sort_interval > 0 && steps_ % settings_.sort_interval == 0;
  }

  // Takes dt as the step's time step; false where it has collapsed (the status says so).
  bool take_time_step(double dt) {
    dt_ = dt;
    if (dt_ >= settings_.min_time_step) return true;
    status_ = Status::TimeStepCollapse;
    return false;
  }

  // The diagnostics of a step at each stage: the transfer dissipation's account, when tracked.
  void observe(StepStage stage) {
    if (!settings_.track_transfer_dissipation) return;
    const Derived& self = derived();
    switch (stage) {
      case StepStage::BeforeP2G:
        if (!transfer_.points_before_current)
          transfer_.points_before = self.points_kinetic_energy();
        break;
      case StepStage::AfterP2G:
        transfer_.grid_after_p2g = self.grid_kinetic_energy(GridState::AfterP2G);
        break;
      case StepStage::AfterGridUpdate:
        transfer_.grid_after_update = self.grid_kinetic_energy(GridState::AfterUpdate);
        break;
      case StepStage::AfterG2P:
        transfer_.close_step(self.points_kinetic_energy());
        break;
    }
  }

  // Closes a step: the clock advances, the points' health decides the status.
  Status end_step(double max_speed, int non_finite, int outside) {
    time_ += dt_;
    ++steps_;
    max_speed_ = max_speed;
    if (non_finite > 0) return status_ = Status::NonFinite;
    if (outside > 0) return status_ = Status::LeftGrid;
    return status_ = Status::Running;
  }

  SettingsT settings_;
  double user_max_dt_;
  Kokkos::View<const PreparedMaterial*, Mem> materials_;
  bool plastic_ = false;
  double max_speed_ = 0.0, dt_ = 0.0, time_ = 0.0;
  double boundary_ = 0.0;  // J/m, work dissipated by the walls and the barrier
  double wall_force_[2] = {0.0, 0.0};
  long steps_ = 0;
  Status status_ = Status::Running;
  double max_mechanical_ = 0.0;  // largest kinetic + stored energy seen (J/m)
  BarrierCoupling<Mem> barrier_;
  WallBands<Mem> wall_bands_;
  TransferDissipation transfer_;
};

}  // namespace lsi::mpm
