// Test support: direct numerical integration of the sliding barrier's equation of motion,
//   m2 dv/dt = c N(t) - tan(delta_b) m2 g   while sliding,   stick while c N <= tan(delta_b) m2 g,
// by classical RK4 with fixed steps aligned to the force's breakpoints and with the stick -> slip
// and slip -> stick instants located by bisection. It shares no code with the closed forms it
// checks (only the block's parameters).
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace lsi::test {

struct OdeState {
  double v = 0.0, x = 0.0;
};

struct SlidingOde {
  std::function<double(double)> normal_force;  // N(t)
  double mass, base_friction, drive;
  double g = 9.81;

  double accel(double t) const { return drive * normal_force(t) / mass - base_friction * g; }

  // One RK4 step of (x, v)' = (v, a(t)).
  OdeState rk4(OdeState s, double t, double h) const {
    const double a1 = accel(t), a2 = accel(t + 0.5 * h), a4 = accel(t + h);
    const double k1x = s.v, k2x = s.v + 0.5 * h * a1, k3x = s.v + 0.5 * h * a2, k4x = s.v + h * a2;
    OdeState r;
    r.x = s.x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    r.v = s.v + h / 6.0 * (a1 + 4 * a2 + a4);
    return r;
  }

  // Integrates from 0 to t_end through the given breakpoints with about `steps` steps; returns
  // the state at t_end and (through `stop_time`) the last instant it came to rest.
  OdeState integrate(double t_end, std::vector<double> breakpoints, int steps,
                     double* stop_time = nullptr) const {
    std::erase_if(breakpoints, [&](double b) { return !(b < t_end); });
    breakpoints.push_back(t_end);
    std::sort(breakpoints.begin(), breakpoints.end());
    OdeState s;
    bool sliding = false;
    double t = 0.0;
    const double h_max = t_end / steps;
    for (double tb : breakpoints) {
      if (tb <= t) continue;
      const int n = std::max(1, static_cast<int>(std::ceil((tb - t) / h_max)));
      const double h = (tb - t) / n;
      const double t_seg = t;
      for (int k = 0; k < n; ++k) {
        double ta = t_seg + k * h, tn = (k + 1 == n) ? tb : t_seg + (k + 1) * h;
        while (ta < tn) {
          if (!sliding) {
            if (accel(ta) > 0.0) {
              sliding = true;
              continue;
            }
            if (accel(tn) <= 0.0) {
              ta = tn;
              break;
            }
            double lo = ta, hi = tn;  // bisection for the start of sliding
            for (int it = 0; it < 200 && hi - lo > 1e-16 * (1 + hi); ++it) {
              const double mid = 0.5 * (lo + hi);
              (accel(mid) > 0.0 ? hi : lo) = mid;
            }
            ta = hi;
            sliding = true;
            continue;
          }
          OdeState next = rk4(s, ta, tn - ta);
          if (next.v >= 0.0) {
            s = next;
            ta = tn;
            break;
          }
          double lo = 0.0, hi = tn - ta;  // bisection for the stop
          for (int it = 0; it < 200 && hi - lo > 1e-16 * (1 + hi); ++it) {
            const double mid = 0.5 * (lo + hi);
            (rk4(s, ta, mid).v > 0.0 ? lo : hi) = mid;
          }
          s = rk4(s, ta, hi);
          s.v = 0.0;
          ta += hi;
          sliding = false;
          if (stop_time) *stop_time = ta;
        }
      }
      t = tb;
    }
    return s;
  }
};

}  // namespace lsi::test
