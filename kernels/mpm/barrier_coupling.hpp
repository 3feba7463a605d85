// The barrier as the solvers hold it: the barrier, the contact forces of the last step, the
// contact impulse accumulated since the caller last took it (per face, and per height band of the
// upstream face when the barrier asks for bands), and the step that moves the barrier under the
// step's contact forces. Shared by the dry and the saturated solver.
#pragma once
#include <Kokkos_Core.hpp>
#include <vector>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/barrier.hpp"
#include "kernels/mpm/barrier_contact.hpp"

namespace lsi::mpm {

template <class MemorySpace>
class BarrierCoupling {
  using Exec = typename MemorySpace::execution_space;

 public:
  void attach(const Barrier& b) {
    barrier_ = b;
    active_ = true;
    const int n = b.face_bands();
    if (n > 0) {
      band_force_ = Kokkos::View<double*, MemorySpace>("face_band_force", n);
      band_host_ = Kokkos::create_mirror_view(band_force_);
      band_impulse_.assign(n, 0.0);
    }
  }
  // The upstream face's normal force per height band during the step (N/m), zeroed by
  // begin_step() and filled by the step's barrier_contact calls; empty without bands.
  const Kokkos::View<double*, MemorySpace>& band_force() const { return band_force_; }
  void begin_step() {
    if (!band_impulse_.empty()) fill<Exec>(band_force_, 0.0);
  }
  bool active() const { return active_; }
  const Barrier& barrier() const { return barrier_; }
  // Contact forces on the barrier during the last step, per face (N/m).
  const BarrierContactReport& contact() const { return contact_; }

  // Records the step's contact (the sum over the phases) and moves a free barrier under it.
  // Returns the work the contact took from the material (J/m).
  double apply(const BarrierContactReport& contact, double dt) {
    contact_ = contact;
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) impulse_[k][d] += contact_.force[k][d] * dt;
    moment_impulse_ += contact_.upstream_moment * dt;
    if (!band_impulse_.empty()) {
      copy_and_wait<Exec>(band_host_, band_force_);
      for (std::size_t i = 0; i < band_impulse_.size(); ++i) band_impulse_[i] += band_host_(i) * dt;
    }
    if (!barrier_.fixed) barrier_.motion.advance(contact_.total(0), contact_.total(1), dt);
    return contact_.work;
  }

  // Contact impulse on the barrier per face (N s/m, x and y) since the last call; resets it.
  void take_impulse(double impulse[3][2]) {
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) {
        impulse[k][d] = impulse_[k][d];
        impulse_[k][d] = 0.0;
      }
  }
  // The time integral of the upstream face's overturning moment (N m s/m) since the last call;
  // resets it.
  double take_moment_impulse() {
    const double m = moment_impulse_;
    moment_impulse_ = 0.0;
    return m;
  }
  // The upstream face's normal impulse per height band (N s/m, the lowest band first) since the
  // last call; resets it. Empty without bands.
  std::vector<double> take_band_impulse() {
    std::vector<double> taken(band_impulse_.size(), 0.0);
    taken.swap(band_impulse_);
    return taken;
  }

 private:
  bool active_ = false;
  Barrier barrier_;
  BarrierContactReport contact_;
  double impulse_[3][2] = {{0, 0}, {0, 0}, {0, 0}};
  double moment_impulse_ = 0.0;
  Kokkos::View<double*, MemorySpace> band_force_;
  typename Kokkos::View<double*, MemorySpace>::HostMirror band_host_;
  std::vector<double> band_impulse_;
};

}  // namespace lsi::mpm
