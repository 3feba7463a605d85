// The barrier as the solvers hold it: the barrier, the contact forces of the last step, the
// contact impulse accumulated since the caller last took it, and the step that moves the barrier
// under the step's contact forces. Shared by the dry and the saturated solver.
#pragma once
#include "kernels/mpm/barrier.hpp"
#include "kernels/mpm/barrier_contact.hpp"

namespace lsi::mpm {

class BarrierCoupling {
 public:
  void attach(const Barrier& b) {
    barrier_ = b;
    active_ = true;
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

 private:
  bool active_ = false;
  Barrier barrier_;
  BarrierContactReport contact_;
  double impulse_[3][2] = {{0, 0}, {0, 0}, {0, 0}};
  double moment_impulse_ = 0.0;
};

}  // namespace lsi::mpm
