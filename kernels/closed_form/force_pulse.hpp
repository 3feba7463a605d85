// The piecewise-linear impact force pulse shared by the empirical and the analytical model:
// F rises linearly from 0 at t = 0 to `peak` at the rise time T1, decays linearly to `residual` at
// the impact duration T2, and stays at `residual` afterwards (the static load of the deposit;
// zero in the analytical model). Time t is measured from the first contact (t_imp = 0).
#pragma once
#include <Kokkos_Macros.hpp>

namespace lsi {

struct ForcePulse {
  double peak = 0.0;       // F_peak, N/m
  double rise_time = 0.0;  // T1, s
  double duration = 0.0;   // T2, s (> T1)
  double residual = 0.0;   // F(t >= T2), N/m

  // F(t), N/m.
  KOKKOS_INLINE_FUNCTION double force(double t) const {
    if (t <= 0.0) return 0.0;
    if (t <= rise_time) return peak * (t / rise_time);
    if (t < duration) return peak + (residual - peak) * ((t - rise_time) / (duration - rise_time));
    return residual;
  }

  // Impulse I(t) = integral of F from 0 to t, N s/m. Integrated exactly (the printed eq. 8 of the
  // paper is not the integral of its own pulse; see docs/theory/models.md, "Empirical model").
  KOKKOS_INLINE_FUNCTION double impulse(double t) const {
    if (t <= 0.0) return 0.0;
    if (t <= rise_time) return 0.5 * peak * t * t / rise_time;
    const double rise = 0.5 * peak * rise_time;
    if (t < duration) {
      const double u = t - rise_time;
      return rise + peak * u + 0.5 * (residual - peak) * u * u / (duration - rise_time);
    }
    return rise + 0.5 * (peak + residual) * (duration - rise_time) + residual * (t - duration);
  }

  // Impulse delivered by the end of the pulse, I(T2).
  KOKKOS_INLINE_FUNCTION double pulse_impulse() const { return impulse(duration); }
};

}  // namespace lsi
