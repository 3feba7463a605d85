// A free barrier pushed by the flow at their relative velocity: the momentum-consistent response
// of a sliding barrier to a fixed-barrier force pulse (beyond the paper; docs/models.md,
// "Momentum-consistent barrier").
//
// The flow (mass m1, horizontal velocity v1 from v0) and the barrier (m2, v2 from rest) interact
// through the normal force N on the barrier's face (h, v: its horizontal and downward shares,
// face_resolution.hpp, face friction included); the flow's base is smooth (the paper's F1 = 0):
//   m1 dv1/dt = -h N
//   m2 dv2/dt =  c N - tan(delta_b) m2 g   while the barrier slides, c = h - tan(delta_b) v,
// and the barrier sticks while c N <= tan(delta_b) m2 g (never moves upstream). The contact law:
// N is the force of the FIXED-barrier pulse at the moment it has destroyed the same relative
// velocity,
//   N = Phi(w),  w = v0 - (v1 - v2),  Phi(h I_f(t) / m1) = N_f(t)   (I_f the pulse's impulse),
// taken on the rising branch until N reaches the peak and on the decaying one after. Hence:
//  * a barrier that sticks receives the fixed pulse itself;
//  * a sliding barrier receives the same peak, sooner, and the pulse progresses as the relative
//    velocity falls from both sides; N = 0 when the flow no longer moves faster than the barrier
//    (w = W, the relative velocity the pulse destroys, W = h J / m1, J its impulse), so the
//    barrier never moves faster than the flow behind it;
//  * after the pulse the flow keeps pushing a barrier that friction slows down, and the two
//    decelerate together, N = tan(delta_b) g / (h / m1 + c / m2), until the barrier stops;
//  * the total momentum m1 v1 + m2 v2 changes only by the base friction.
// Integrated in the variables that make every phase smooth: sigma = sqrt(w) on the rising branch
// (N = a sigma) and sigma = sqrt(W - w) on the decaying one (N = b sigma); sticking phases are
// linear in t and exact, sliding phases are integrated by a Dormand-Prince 5(4) pair with its
// error controlled to 1e-12 relative and the phase changes located by bisection. No allocation:
// usable in the batched kernels.
#pragma once
#include <Kokkos_Macros.hpp>

#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/force_pulse.hpp"
#include "kernels/common/constants.hpp"
#include "kernels/common/math.hpp"

namespace lsi {

struct MomentumBarrierSetup {
  ForcePulse fixed_pulse;                  // the force on a FIXED barrier (residual 0)
  double landslide_mass = 0.0;             // m1, kg/m
  double velocity = 0.0;                   // v0, m/s (horizontal)
  double barrier_mass = math::infinity();  // m2, kg/m (+infinity: fixed)
  double base_friction = 0.0;              // tan(delta_b)
  FaceResolution face;                     // h, v of the normal force
};

// The state at a time; what the histories record.
struct MomentumBarrierState {
  double time = 0.0;                  // s
  double force = 0.0;                 // N, normal to the face, N/m
  double landslide_velocity = 0.0;    // v1, m/s
  double barrier_velocity = 0.0;      // v2, m/s
  double barrier_displacement = 0.0;  // m
};

struct MomentumBarrierResult {
  double peak_force = 0.0;           // N/m: the fixed pulse's peak (every path reaches it)
  double rise_time = 0.0;            // s: when N reaches the peak
  double contact_end = 0.0;          // s: when N returns to zero (+infinity: never)
  double start_time = -1.0;          // s: first instant of sliding (-1: never slides)
  double stop_time = 0.0;            // s: when the barrier comes to rest (+infinity: never)
  double final_displacement = 0.0;   // m (+infinity without base friction once it slides)
  double final_landslide_velocity = 0.0;   // v1 at the end, m/s
  double largest_barrier_velocity = 0.0;   // m/s
  bool ok = true;                    // false: the integration did not finish (a NaN input)
};

// The fixed-barrier pulse of the momentum-consistent analytical model: the two-body triangle of
// duration T2 = (8/3) lambda L1,0 / v0 (eq. 12) and rise tau T2 (eq. 7), whose horizontal impulse
// stops the flow, h F_peak T2 / 2 = m1 v0 (the paper's F_peak = 3/4 m1 v0^2 / s1,max when h = 1).
KOKKOS_INLINE_FUNCTION ForcePulse momentum_two_body_pulse(double landslide_mass, double velocity,
                                                          double equivalent_length, double lambda,
                                                          double tau, double horizontal) {
  ForcePulse p;
  p.duration = 8.0 / 3.0 * lambda * equivalent_length / velocity;
  p.rise_time = tau * p.duration;
  p.peak = 2.0 * landslide_mass * velocity / (horizontal * p.duration);
  p.residual = 0.0;
  return p;
}

namespace momentum_detail {

enum class Branch { Rise, Decay };

// Constants of one case.
struct Model {
  double m1, m2, v0, h, c, g_friction;   // g_friction = tan(delta_b) g
  double a, b, W, peak, slip_force;      // N = a sigma (rise), b sigma (decay); slip above slip_force
  bool can_slide;
};

KOKKOS_INLINE_FUNCTION Model model_of(const MomentumBarrierSetup& s) {
  Model m;
  const ForcePulse& p = s.fixed_pulse;
  m.m1 = s.landslide_mass;
  m.m2 = s.barrier_mass;
  m.v0 = s.velocity;
  m.h = s.face.horizontal;
  m.c = s.face.sliding_drive(s.base_friction);
  m.g_friction = s.base_friction * gravity;
  m.peak = p.peak;
  m.a = math::sqrt(2.0 * p.peak * m.m1 / (m.h * p.rise_time));
  m.b = math::sqrt(2.0 * p.peak * m.m1 / (m.h * (p.duration - p.rise_time)));
  m.W = m.h * p.pulse_impulse() / m.m1;
  m.can_slide = m.c > 0.0 && m.m2 < math::infinity();
  m.slip_force = m.can_slide ? m.g_friction * m.m2 / m.c : math::infinity();
  return m;
}

// State of a sliding phase: y[0] = sigma, y[1] = I (impulse on the barrier), y[2] = x2.
struct Sliding {
  const Model* m;
  Branch branch;
  KOKKOS_INLINE_FUNCTION double force(const double* y) const {
    return (branch == Branch::Rise ? m->a : m->b) * y[0];
  }
  KOKKOS_INLINE_FUNCTION double w(const double* y) const {
    return branch == Branch::Rise ? y[0] * y[0] : m->W - y[0] * y[0];
  }
  // v2 = w - h I / m1 (from w = v0 - v1 + v2 and v1 = v0 - h I / m1).
  KOKKOS_INLINE_FUNCTION double barrier_velocity(const double* y) const {
    return w(y) - m->h * y[1] / m->m1;
  }
  KOKKOS_INLINE_FUNCTION void derivative(const double* y, double* dy) const {
    const double N = force(y);
    // w' = kappa N - tan(delta_b) g with kappa = h / m1 + c / m2, and sigma' = +-w' / (2 sigma):
    // with N = k sigma, sigma' = +-(kappa k / 2 - tan(delta_b) g / (2 sigma)) (the friction term
    // only where there is friction: sigma = 0 at the start of a frictionless slide).
    const double k = branch == Branch::Rise ? m->a : m->b;
    const double kappa = m->h / m->m1 + m->c / m->m2;
    const double friction = m->g_friction > 0.0 ? 0.5 * m->g_friction / y[0] : 0.0;
    dy[0] = (branch == Branch::Rise ? 1.0 : -1.0) * (0.5 * kappa * k - friction);
    dy[1] = N;
    dy[2] = barrier_velocity(y);
  }
};

// One Dormand-Prince 5(4) step of length dt from y: the 5th-order solution in y5, the error
// estimate (5th minus 4th order) in err.
KOKKOS_INLINE_FUNCTION void dp_step(const Sliding& f, const double* y, double dt, double* y5,
                                    double* err) {
  double k1[3], k2[3], k3[3], k4[3], k5[3], k6[3], k7[3], t[3];
  f.derivative(y, k1);
  for (int i = 0; i < 3; ++i) t[i] = y[i] + dt * (k1[i] / 5.0);
  f.derivative(t, k2);
  for (int i = 0; i < 3; ++i) t[i] = y[i] + dt * (3.0 / 40.0 * k1[i] + 9.0 / 40.0 * k2[i]);
  f.derivative(t, k3);
  for (int i = 0; i < 3; ++i)
    t[i] = y[i] + dt * (44.0 / 45.0 * k1[i] - 56.0 / 15.0 * k2[i] + 32.0 / 9.0 * k3[i]);
  f.derivative(t, k4);
  for (int i = 0; i < 3; ++i)
    t[i] = y[i] + dt * (19372.0 / 6561.0 * k1[i] - 25360.0 / 2187.0 * k2[i] +
                        64448.0 / 6561.0 * k3[i] - 212.0 / 729.0 * k4[i]);
  f.derivative(t, k5);
  for (int i = 0; i < 3; ++i)
    t[i] = y[i] + dt * (9017.0 / 3168.0 * k1[i] - 355.0 / 33.0 * k2[i] + 46732.0 / 5247.0 * k3[i] +
                        49.0 / 176.0 * k4[i] - 5103.0 / 18656.0 * k5[i]);
  f.derivative(t, k6);
  for (int i = 0; i < 3; ++i)
    y5[i] = y[i] + dt * (35.0 / 384.0 * k1[i] + 500.0 / 1113.0 * k3[i] + 125.0 / 192.0 * k4[i] -
                         2187.0 / 6784.0 * k5[i] + 11.0 / 84.0 * k6[i]);
  f.derivative(y5, k7);
  for (int i = 0; i < 3; ++i)
    err[i] = dt * ((35.0 / 384.0 - 5179.0 / 57600.0) * k1[i] +
                   (500.0 / 1113.0 - 7571.0 / 16695.0) * k3[i] +
                   (125.0 / 192.0 - 393.0 / 640.0) * k4[i] +
                   (-2187.0 / 6784.0 + 92097.0 / 339200.0) * k5[i] +
                   (11.0 / 84.0 - 187.0 / 2100.0) * k6[i] - 1.0 / 40.0 * k7[i]);
}

// The recorder of the histories: the state at each requested time.
struct Recorder {
  const double* times;
  int count;
  MomentumBarrierState* out;
  int next = 0;
  KOKKOS_INLINE_FUNCTION bool wants(double t) const { return next < count && times[next] <= t; }
  KOKKOS_INLINE_FUNCTION double next_time() const {
    return next < count ? times[next] : math::infinity();
  }
  KOKKOS_INLINE_FUNCTION void put(double t, double N, double v1, double v2, double x2) {
    out[next] = MomentumBarrierState{t, N, v1, v2, x2};
    ++next;
  }
};

}  // namespace momentum_detail

// The response, and the state at `count` increasing `sample_times` into `samples` (both may be
// null with count 0). Times after the end repeat the final state.
KOKKOS_INLINE_FUNCTION MomentumBarrierResult momentum_barrier(const MomentumBarrierSetup& setup,
                                                              const double* sample_times = nullptr,
                                                              int count = 0,
                                                              MomentumBarrierState* samples = nullptr) {
  using namespace momentum_detail;
  const Model m = model_of(setup);
  MomentumBarrierResult r;
  r.peak_force = m.peak;
  if (!(setup.fixed_pulse.residual == 0.0) || !(m.h > 0.0) || !(m.m1 > 0.0)) {
    // A static residual load is not a pulse of destroyed momentum (not modelled); a face that
    // does not push the flow back cannot stop it.
    r.ok = false;
    r.final_displacement = r.contact_end = r.stop_time = math::quiet_nan();
    return r;
  }
  Recorder rec{sample_times, count, samples};
  double t = 0.0, I = 0.0, x2 = 0.0;
  const double T1 = setup.fixed_pulse.rise_time, T2 = setup.fixed_pulse.duration;
  const double tol = 1e-12;
  auto v1_of = [&](double impulse) { return m.v0 - m.h * impulse / m.m1; };

  // --- Sticking on the rising branch: the fixed pulse, N = peak t / T1.
  const double slope = m.peak / T1;
  const double t_slip = m.slip_force < m.peak ? m.slip_force / slope : math::infinity();
  const double t_rise_end = t_slip < T1 ? t_slip : T1;
  while (rec.wants(t_rise_end)) {
    const double s = rec.next_time(), N = slope * s;
    rec.put(s, N, v1_of(0.5 * N * s), 0.0, 0.0);
  }
  t = t_rise_end;
  I = 0.5 * slope * t * t;
  Branch branch = Branch::Rise;
  bool sliding = t_slip < T1;
  double sigma;   // the phase variable of the current branch
  if (sliding) {
    r.start_time = t;
    sigma = slope * t / m.a;
  } else {
    r.rise_time = T1;
    branch = Branch::Decay;
    sigma = m.peak / m.b;
  }

  // --- Sliding phases (rise, then decay), integrated.
  int guard = 0;
  while (sliding && guard < 200000) {
    Sliding f{&m, branch};
    double y[3] = {sigma, I, x2};
    const double scale[3] = {math::sqrt(m.W), m.m1 * m.W / m.h, 1.0};
    double dt = 1e-3 * T2;
    bool phase_over = false;
    while (!phase_over && guard++ < 200000) {
      double y5[3], err[3];
      dp_step(f, y, dt, y5, err);
      double e = 0.0;
      for (int i = 0; i < 3; ++i) {
        const double sc = tol * (scale[i] + math::fabs(y5[i]));
        e = math::max(e, math::fabs(err[i]) / sc);
      }
      // Without friction sigma falls linearly to zero on the decaying branch (the end of the
      // contact, an event); with friction it cannot reach zero, and a step that crosses it is
      // too long.
      const bool frictionless_end =
          branch == Branch::Decay && m.g_friction == 0.0 && !(y5[0] > 0.0);
      if (!(e <= 1.0) || (!(y5[0] > 0.0) && !frictionless_end)) {
        dt *= (e > 1.0 && e < 1e30) ? math::max(0.1, 0.9 * math::pow(e, -0.2)) : 0.25;
        if (dt < 1e-15 * (T2 + t)) { guard = 200000; break; }
        continue;
      }
      // The events of the step: the peak (rise), the barrier's stop or the end of a frictionless
      // contact (decay).
      const bool peak_crossed = branch == Branch::Rise && f.force(y5) >= m.peak;
      const bool stopped = branch == Branch::Decay && !frictionless_end &&
                           f.barrier_velocity(y5) <= 0.0;
      double dt_event = dt;
      if (peak_crossed || stopped || frictionless_end) {
        double lo = 0.0, hi = dt;
        for (int it = 0; it < 200 && hi - lo > 1e-15 * (t + dt); ++it) {
          const double mid = 0.5 * (lo + hi);
          double ym[3], em[3];
          dp_step(f, y, mid, ym, em);
          const bool past = peak_crossed ? f.force(ym) >= m.peak
                            : stopped    ? f.barrier_velocity(ym) <= 0.0
                                         : !(ym[0] > 0.0);
          (past ? hi : lo) = mid;
        }
        dt_event = frictionless_end ? lo : hi;   // the end of the contact: sigma still >= 0
        dp_step(f, y, dt_event, y5, err);
        phase_over = true;
      }
      // Samples inside the step, by a step of their own from its start.
      while (rec.wants(t + dt_event)) {
        const double s = rec.next_time();
        double ys[3], es[3];
        dp_step(f, y, s - t, ys, es);
        rec.put(s, f.force(ys), v1_of(ys[1]), f.barrier_velocity(ys), ys[2]);
      }
      t += dt_event;
      for (int i = 0; i < 3; ++i) y[i] = y5[i];
      r.largest_barrier_velocity = math::max(r.largest_barrier_velocity, f.barrier_velocity(y));
      if (peak_crossed) {
        r.rise_time = t;
        branch = Branch::Decay;
        sigma = m.peak / m.b;   // N = peak on both branches
      } else if (stopped) {
        sliding = false;
        r.stop_time = t;
        sigma = y[0];
      } else if (frictionless_end) {
        // No base friction: the pulse ends with the two moving together; they never stop.
        sigma = 0.0;
      } else {
        dt *= math::min(5.0, 0.9 * math::pow(math::max(e, 1e-10), -0.2));
      }
      I = y[1];
      x2 = y[2];
      if (phase_over && !peak_crossed && !stopped) {   // frictionless: slides on forever
        const double v2 = f.barrier_velocity(y);
        r.contact_end = t;
        r.stop_time = math::infinity();
        r.final_displacement = math::infinity();
        r.final_landslide_velocity = v1_of(I);
        while (rec.wants(math::infinity())) {
          const double s = rec.next_time();
          rec.put(s, 0.0, v1_of(I), v2, x2 + v2 * (s - t));
        }
        return r;
      }
    }
    if (guard >= 200000) {
      r.ok = false;
      r.final_displacement = r.contact_end = r.stop_time = math::quiet_nan();
      return r;
    }
  }

  // --- Sticking on the decaying branch: N = b sigma falls linearly to zero.
  const double rate = m.h * m.b / (2.0 * m.m1);   // -d sigma / dt
  const double t_end = t + sigma / rate;
  const double N0 = m.b * sigma;
  auto state_at = [&](double s, double& N, double& impulse) {
    const double u = s - t;
    N = math::max(0.0, N0 - m.b * rate * u);   // round-off at the very end
    impulse = I + N0 * u - 0.5 * m.b * rate * u * u;
  };
  while (rec.wants(t_end)) {
    const double s = rec.next_time();
    double N, impulse;
    state_at(s, N, impulse);
    rec.put(s, N, v1_of(impulse), 0.0, x2);
  }
  double N_end, I_end;
  state_at(t_end, N_end, I_end);
  r.contact_end = t_end;
  if (r.start_time < 0.0) r.stop_time = 0.0;
  r.final_displacement = x2;
  r.final_landslide_velocity = v1_of(I_end);
  while (rec.wants(math::infinity())) rec.put(rec.next_time(), 0.0, v1_of(I_end), 0.0, x2);
  return r;
}

}  // namespace lsi
