// A free barrier pushed by the flow at their relative velocity: the momentum-consistent response
// of a sliding barrier to a fixed-barrier force pulse (beyond the paper; docs/theory/models.md,
// "Momentum-consistent barrier").
//
// The flow (mass m1, horizontal velocity v1 from v0) and the barrier (m2, v2 from rest) interact
// through the normal force N on the barrier's face (h, v: its horizontal and downward shares,
// face_resolution.hpp, face friction included); the flow's base may brake it (the paper's F1,
// a deceleration f1 = F1 / m1 while it moves; 0 is the paper's smooth base):
//   m1 dv1/dt = -h N - F1
//   m2 dv2/dt =  c N - tan(delta_b) m2 g   while the barrier slides, c = h - tan(delta_b) v,
// and the barrier sticks while c N <= tan(delta_b) m2 g (never moves upstream). The contact law:
// N is the force of the FIXED-barrier pulse at the moment it has destroyed the same relative
// velocity,
//   N = Phi(w),  w = v0 - (v1 - v2),  Phi(h I_f(t) / m1) = N_f(t)   (I_f the pulse's impulse),
// taken on the rising branch until N reaches the peak and on the decaying one after. Hence:
//  * a barrier that sticks on a smooth flow base receives the fixed pulse itself;
//  * a sliding barrier receives the same peak, sooner, and the pulse progresses as the relative
//    velocity falls from both sides; N = 0 when the flow no longer moves faster than the barrier
//    (w = W, the relative velocity the pulse destroys, W = h J / m1, J its impulse), so the
//    barrier never moves faster than the flow behind it;
//  * after the pulse the flow keeps pushing a barrier that friction slows down, and the two
//    decelerate together until the barrier stops (or the flow, braked harder by its own base,
//    falls behind and the barrier slides on alone);
//  * the total momentum m1 v1 + m2 v2 changes only by the base frictions.
// Integrated in the variables that make every phase smooth: sigma = sqrt(w) on the rising branch
// (N = a sigma) and sigma = sqrt(W - w) on the decaying one (N = b sigma); sticking phases on a
// smooth flow base are linear in t and exact, the others are integrated by a Dormand-Prince 5(4)
// pair with its error controlled to 1e-12 relative and the phase changes located by bisection. No
// allocation: usable in the batched kernels.
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
  double flow_friction = 0.0;              // f1 = F1 / m1, m/s^2: the flow's base braking it
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
  double peak_force = 0.0;                // N/m: the fixed pulse's peak (every path reaches it)
  double rise_time = 0.0;                 // s: when N reaches the peak
  double contact_end = 0.0;               // s: when N returns to zero (+infinity: never)
  double start_time = -1.0;               // s: first instant of sliding (-1: never slides)
  double stop_time = 0.0;                 // s: when the barrier comes to rest (+infinity: never)
  double final_displacement = 0.0;        // m (+infinity without base friction once it slides)
  double final_landslide_velocity = 0.0;  // v1 at the end, m/s
  double largest_barrier_velocity = 0.0;  // m/s
  bool ok = true;                         // false: the integration did not finish (a NaN input)
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

// A fixed-barrier pulse made to destroy no more than the flow's horizontal momentum: where its
// horizontal impulse h J exceeds m1 v0 (the empirical pulse's normal impulse m1 v_n with face
// friction on a steep face: h sin(beta) > 1) it is shortened, peak and tau kept, to
// h J = m1 v0; otherwise it is returned as it is. The momentum-consistent barrier takes such a
// pulse (the flow cannot be pushed back by the face).
KOKKOS_INLINE_FUNCTION ForcePulse momentum_capped_pulse(ForcePulse p, double landslide_mass,
                                                        double velocity, double horizontal) {
  const double J = p.pulse_impulse(), most = landslide_mass * velocity / horizontal;
  if (!(J > most)) return p;
  const double tau = p.rise_time / p.duration;
  p.duration *= most / J;  // residual 0: J = peak T2 / 2, linear in T2
  p.rise_time = tau * p.duration;
  return p;
}

namespace momentum_detail {

enum class Branch { Rise, Decay };

// Constants of one case.
struct Model {
  double m1, m2, v0, h, c, g_friction;  // g_friction = tan(delta_b) g
  double f1;                            // the flow's base friction, m/s^2
  double a, b, W, peak, slip_force;  // N = a sigma (rise), b sigma (decay); slip above slip_force
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
  m.f1 = s.flow_friction;
  m.peak = p.peak;
  m.a = math::sqrt(2.0 * p.peak * m.m1 / (m.h * p.rise_time));
  m.b = math::sqrt(2.0 * p.peak * m.m1 / (m.h * (p.duration - p.rise_time)));
  m.W = m.h * p.pulse_impulse() / m.m1;
  m.can_slide = m.c > 0.0 && m.m2 < math::infinity();
  m.slip_force = m.can_slide ? m.g_friction * m.m2 / m.c : math::infinity();
  return m;
}

// The state of a contact phase: y[0] = sigma, y[1] = I (impulse on the barrier), y[2] = x2,
// y[3] = t. The barrier sticks or slides; N = a sigma or b sigma on the branch.
struct Contact {
  const Model* m;
  Branch branch;
  bool sliding;
  KOKKOS_INLINE_FUNCTION double force(const double* y) const {
    return (branch == Branch::Rise ? m->a : m->b) * y[0];
  }
  KOKKOS_INLINE_FUNCTION double w(const double* y) const {
    return branch == Branch::Rise ? y[0] * y[0] : m->W - y[0] * y[0];
  }
  // v1 = v0 - h I / m1 - f1 t (the flow moves throughout the contact), and v2 = w - (v0 - v1).
  KOKKOS_INLINE_FUNCTION double flow_velocity(const double* y) const {
    return m->v0 - m->h * y[1] / m->m1 - m->f1 * y[3];
  }
  KOKKOS_INLINE_FUNCTION double barrier_velocity(const double* y) const {
    return sliding ? w(y) - (m->v0 - flow_velocity(y)) : 0.0;
  }
  KOKKOS_INLINE_FUNCTION void derivative(const double* y, double* dy) const {
    // w' = kappa N + f1 - g_s, kappa = h / m1 (+ c / m2 while sliding), g_s = tan(delta_b) g while
    // sliding (0 sticking); sigma' = +-w' / (2 sigma) = +-(kappa k / 2 + (f1 - g_s) / (2 sigma)),
    // the last term only where it is not zero (sigma = 0 at a frictionless start).
    const double N = force(y);
    const double k = branch == Branch::Rise ? m->a : m->b;
    const double kappa = m->h / m->m1 + (sliding ? m->c / m->m2 : 0.0);
    const double rest = m->f1 - (sliding ? m->g_friction : 0.0);
    const double extra = rest != 0.0 ? 0.5 * rest / y[0] : 0.0;
    dy[0] = (branch == Branch::Rise ? 1.0 : -1.0) * (0.5 * kappa * k + extra);
    dy[1] = N;
    dy[2] = barrier_velocity(y);
    dy[3] = 1.0;
  }
};

constexpr int kDim = 4;

// One Dormand-Prince 5(4) step of length dt from y: the 5th-order solution in y5, the error
// estimate (5th minus 4th order) in err.
KOKKOS_INLINE_FUNCTION void dp_step(const Contact& f, const double* y, double dt, double* y5,
                                    double* err) {
  double k1[kDim], k2[kDim], k3[kDim], k4[kDim], k5[kDim], k6[kDim], k7[kDim], t[kDim];
  f.derivative(y, k1);
  for (int i = 0; i < kDim; ++i) t[i] = y[i] + dt * (k1[i] / 5.0);
  f.derivative(t, k2);
  for (int i = 0; i < kDim; ++i) t[i] = y[i] + dt * (3.0 / 40.0 * k1[i] + 9.0 / 40.0 * k2[i]);
  f.derivative(t, k3);
  for (int i = 0; i < kDim; ++i)
    t[i] = y[i] + dt * (44.0 / 45.0 * k1[i] - 56.0 / 15.0 * k2[i] + 32.0 / 9.0 * k3[i]);
  f.derivative(t, k4);
  for (int i = 0; i < kDim; ++i)
    t[i] = y[i] + dt * (19372.0 / 6561.0 * k1[i] - 25360.0 / 2187.0 * k2[i] +
                        64448.0 / 6561.0 * k3[i] - 212.0 / 729.0 * k4[i]);
  f.derivative(t, k5);
  for (int i = 0; i < kDim; ++i)
    t[i] = y[i] + dt * (9017.0 / 3168.0 * k1[i] - 355.0 / 33.0 * k2[i] + 46732.0 / 5247.0 * k3[i] +
                        49.0 / 176.0 * k4[i] - 5103.0 / 18656.0 * k5[i]);
  f.derivative(t, k6);
  for (int i = 0; i < kDim; ++i)
    y5[i] = y[i] + dt * (35.0 / 384.0 * k1[i] + 500.0 / 1113.0 * k3[i] + 125.0 / 192.0 * k4[i] -
                         2187.0 / 6784.0 * k5[i] + 11.0 / 84.0 * k6[i]);
  f.derivative(y5, k7);
  for (int i = 0; i < kDim; ++i)
    err[i] =
        dt *
        ((35.0 / 384.0 - 5179.0 / 57600.0) * k1[i] + (500.0 / 1113.0 - 7571.0 / 16695.0) * k3[i] +
         (125.0 / 192.0 - 393.0 / 640.0) * k4[i] + (-2187.0 / 6784.0 + 92097.0 / 339200.0) * k5[i] +
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

// What ends a contact phase.
enum class Event { None, Peak, Slip, Stop, End, Failed };

}  // namespace momentum_detail

// The response, and the state at `count` increasing `sample_times` into `samples` (both may be
// null with count 0). Times after the end repeat the final state.
KOKKOS_INLINE_FUNCTION MomentumBarrierResult
momentum_barrier(const MomentumBarrierSetup& setup, const double* sample_times = nullptr,
                 int count = 0, MomentumBarrierState* samples = nullptr) {
  using namespace momentum_detail;
  const Model m = model_of(setup);
  MomentumBarrierResult r;
  r.peak_force = m.peak;
  auto fail = [&]() {
    r.ok = false;
    r.final_displacement = r.contact_end = r.stop_time = math::quiet_nan();
    return r;
  };
  if (!(setup.fixed_pulse.residual == 0.0) || !(m.h > 0.0) || !(m.m1 > 0.0) || !(m.f1 >= 0.0) ||
      !(m.W <= m.v0 * (1.0 + 1e-12)))
    // A static residual load is not a pulse of destroyed momentum (not modelled); a face that
    // does not push the flow back cannot stop it; a pulse that destroys more than the flow's
    // momentum would push it back (momentum_capped_pulse).
    return fail();
  Recorder rec{sample_times, count, samples};
  const double T1 = setup.fixed_pulse.rise_time, T2 = setup.fixed_pulse.duration;
  const double tol = 1e-12;
  Contact f{&m, Branch::Rise, false};
  double y[kDim] = {0.0, 0.0, 0.0, 0.0};  // sigma, I, x2, t

  if (m.f1 == 0.0 && m.slip_force > 0.0) {
    // Sticking on the rising branch of a smooth flow base: the fixed pulse, N = peak t / T1,
    // exact (sigma = 0 is a rest point of the equations: the pulse has to be started in time).
    const double slope = m.peak / T1;
    const double t_slip = m.slip_force < m.peak ? m.slip_force / slope : math::infinity();
    const double t_end = t_slip < T1 ? t_slip : T1;
    while (rec.wants(t_end)) {
      const double s = rec.next_time(), N = slope * s;
      rec.put(s, N, m.v0 - m.h * 0.5 * N * s / m.m1, 0.0, 0.0);
    }
    y[3] = t_end;
    y[1] = 0.5 * slope * t_end * t_end;
    y[0] = slope * t_end / m.a;
    if (t_slip < T1) {
      f.sliding = true;
      r.start_time = t_end;
    } else {
      r.rise_time = T1;
      f.branch = Branch::Decay;
      y[0] = m.peak / m.b;
    }
  } else if (m.f1 > 0.0) {
    // The flow's base friction destroys relative velocity from the first instant, before the
    // force does: w = f1 t + O(t^3/2). Start a moment later on that (sigma' is infinite at 0).
    const double t0 = 1e-12 * T2;
    y[3] = t0;
    y[0] = math::sqrt(m.f1 * t0);
    y[1] = 2.0 / 3.0 * m.a * math::sqrt(m.f1) * t0 * math::sqrt(t0);
    f.sliding = m.slip_force <= 0.0;
    if (f.sliding) r.start_time = 0.0;
    while (rec.wants(t0)) rec.put(rec.next_time(), 0.0, m.v0, 0.0, 0.0);
  } else {
    f.sliding = true;  // no friction under the barrier: it moves as soon as it is pushed
    r.start_time = 0.0;
  }

  // --- Contact phases, integrated, until the contact ends.
  int guard = 0;
  constexpr int kMaxSteps = 200000;
  bool contact = true;
  while (contact) {
    if (f.branch == Branch::Decay && !f.sliding && m.f1 == 0.0) {
      // Sticking on the decaying branch of a smooth flow base: N = b sigma falls linearly.
      const double rate = m.h * m.b / (2.0 * m.m1);  // -d sigma / dt
      const double t_start = y[3], N0 = m.b * y[0], I0 = y[1];
      const double t_end = t_start + y[0] / rate;
      auto at = [&](double s, double& N, double& impulse) {
        const double u = s - t_start;
        N = math::max(0.0, N0 - m.b * rate * u);  // round-off at the very end
        impulse = I0 + N0 * u - 0.5 * m.b * rate * u * u;
      };
      while (rec.wants(t_end)) {
        const double s = rec.next_time();
        double N, impulse;
        at(s, N, impulse);
        rec.put(s, N, m.v0 - m.h * impulse / m.m1, 0.0, y[2]);
      }
      double N_end;
      at(t_end, N_end, y[1]);
      y[0] = 0.0;
      y[3] = t_end;
      contact = false;
      break;
    }
    const double scale[kDim] = {math::sqrt(m.W), m.m1 * m.W / m.h, 1.0, T2};
    double dt = 1e-3 * T2;
    Event event = Event::None;
    while (event == Event::None) {
      if (++guard > kMaxSteps) return fail();
      // Where the relative velocity's braking outlasts the push (rest > 0), sigma reaches zero
      // with an infinite slope: the last part is integrated with sigma as the variable, in which
      // it is regular: dt/d sigma = -2 sigma / (kappa k sigma + rest).
      const double rest = m.f1 - (f.sliding ? m.g_friction : 0.0);
      if (f.branch == Branch::Decay && rest > 0.0 && y[0] < 1e-3 * (m.peak / m.b)) {
        constexpr int n = 256;
        const double h_sigma = -y[0] / n;
        auto dz = [&](double sigma, const double* z, double* out) {
          double state[kDim] = {sigma, z[1], z[2], z[0]}, d[kDim];
          f.derivative(state, d);  // d[0] = sigma' (its friction term finite for sigma > 0)
          const double kappa = m.h / m.m1 + (f.sliding ? m.c / m.m2 : 0.0);
          const double dt_dsigma = -2.0 * sigma / (kappa * m.b * sigma + rest);
          out[0] = dt_dsigma;
          out[1] = d[1] * dt_dsigma;
          out[2] = d[2] * dt_dsigma;
        };
        double z[3] = {y[3], y[1], y[2]}, sigma = y[0];
        for (int i = 0; i < n; ++i) {
          double k1[3], k2[3], k3[3], k4[3], zt[3];
          dz(sigma, z, k1);
          for (int j = 0; j < 3; ++j) zt[j] = z[j] + 0.5 * h_sigma * k1[j];
          dz(sigma + 0.5 * h_sigma, zt, k2);
          for (int j = 0; j < 3; ++j) zt[j] = z[j] + 0.5 * h_sigma * k2[j];
          dz(sigma + 0.5 * h_sigma, zt, k3);
          for (int j = 0; j < 3; ++j) zt[j] = z[j] + h_sigma * k3[j];
          dz(i + 1 == n ? 0.0 : sigma + h_sigma, zt, k4);
          double znew[3];
          for (int j = 0; j < 3; ++j)
            znew[j] = z[j] + h_sigma / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
          const double sigma_new = i + 1 == n ? 0.0 : sigma + h_sigma;
          while (rec.wants(znew[0])) {  // linear within this last, short stretch
            const double s = rec.next_time(), u = (s - z[0]) / (znew[0] - z[0]);
            const double st[kDim] = {sigma + u * (sigma_new - sigma), z[1] + u * (znew[1] - z[1]),
                                     z[2] + u * (znew[2] - z[2]), s};
            rec.put(s, f.force(st), f.flow_velocity(st), f.barrier_velocity(st), st[2]);
          }
          for (int j = 0; j < 3; ++j) z[j] = znew[j];
          sigma = sigma_new;
        }
        y[0] = 0.0;
        y[1] = z[1];
        y[2] = z[2];
        y[3] = z[0];
        event = Event::End;
        break;
      }
      double y5[kDim], err[kDim];
      dp_step(f, y, dt, y5, err);
      double e = 0.0;
      for (int i = 0; i < kDim; ++i)
        e = math::max(e, math::fabs(err[i]) / (tol * (scale[i] + math::fabs(y5[i]))));
      // On the decaying branch sigma may reach zero (the end of the contact, an event) where the
      // net braking of the relative velocity is not below it; elsewhere a step across zero is
      // too long.
      const bool rest_braking = m.f1 - (f.sliding ? m.g_friction : 0.0) >= 0.0;
      const bool ends = f.branch == Branch::Decay && rest_braking && !(y5[0] > 0.0);
      if (!(e <= 1.0) || (!(y5[0] > 0.0) && !ends)) {
        dt *= (e > 1.0 && e < 1e30) ? math::max(0.1, 0.9 * math::pow(e, -0.2)) : 0.25;
        if (dt < 1e-15 * (T2 + y[3])) return fail();
        continue;
      }
      auto crossed = [&](const double* z) {
        if (f.branch == Branch::Rise && f.force(z) >= m.peak) return Event::Peak;
        if (f.branch == Branch::Rise && !f.sliding && f.force(z) >= m.slip_force)
          return Event::Slip;
        if (f.branch == Branch::Decay && !(z[0] > 0.0) && rest_braking) return Event::End;
        if (f.branch == Branch::Decay && f.sliding && f.barrier_velocity(z) <= 0.0)
          return Event::Stop;
        return Event::None;
      };
      Event ev = crossed(y5);
      double dt_event = dt;
      if (ev != Event::None) {
        double lo = 0.0, hi = dt;
        for (int it = 0; it < 200 && hi - lo > 1e-15 * (y[3] + dt); ++it) {
          const double mid = 0.5 * (lo + hi);
          double ym[kDim], em[kDim];
          dp_step(f, y, mid, ym, em);
          (crossed(ym) == ev ? hi : lo) = mid;
        }
        dt_event = ev == Event::End ? lo : hi;  // the end: sigma still >= 0
        dp_step(f, y, dt_event, y5, err);
        event = ev;
      }
      // Samples inside the step, by a step of their own from its start.
      while (rec.wants(y[3] + dt_event)) {
        const double s = rec.next_time();
        double ys[kDim], es[kDim];
        dp_step(f, y, s - y[3], ys, es);
        rec.put(s, f.force(ys), f.flow_velocity(ys), f.barrier_velocity(ys), ys[2]);
      }
      for (int i = 0; i < kDim; ++i) y[i] = y5[i];
      r.largest_barrier_velocity = math::max(r.largest_barrier_velocity, f.barrier_velocity(y));
      if (event == Event::None) dt *= math::min(5.0, 0.9 * math::pow(math::max(e, 1e-10), -0.2));
    }
    switch (event) {
      case Event::Peak:
        r.rise_time = y[3];
        f.branch = Branch::Decay;
        y[0] = m.peak / m.b;  // N = peak on both branches
        break;
      case Event::Slip:
        f.sliding = true;
        r.start_time = y[3];
        break;
      case Event::Stop:
        f.sliding = false;
        r.stop_time = y[3];
        break;
      default:  // End
        contact = false;
        break;
    }
  }

  // --- After the contact: the barrier, if it still slides, alone against its base friction.
  const double t_end = y[3], x_end = y[2];
  const double v1 = m.v0 - m.h * y[1] / m.m1 - m.f1 * t_end;
  const double v2 = f.barrier_velocity(y);
  r.contact_end = t_end;
  r.final_landslide_velocity = math::max(0.0, v1);
  if (r.start_time < 0.0) r.stop_time = 0.0;
  if (f.sliding && v2 > 0.0) {
    if (m.g_friction == 0.0) {  // slides on for ever with the flow behind it
      r.stop_time = math::infinity();
      r.final_displacement = math::infinity();
      while (rec.wants(math::infinity())) {
        const double s = rec.next_time();
        rec.put(s, 0.0, math::max(0.0, v1 - m.f1 * (s - t_end)), v2, x_end + v2 * (s - t_end));
      }
      return r;
    }
    const double t_stop = t_end + v2 / m.g_friction;
    r.stop_time = t_stop;
    r.final_displacement = x_end + 0.5 * v2 * v2 / m.g_friction;
    while (rec.wants(math::infinity())) {
      const double s = rec.next_time(), u = math::min(s, t_stop) - t_end;
      rec.put(s, 0.0, math::max(0.0, v1 - m.f1 * (s - t_end)), v2 - m.g_friction * u,
              x_end + v2 * u - 0.5 * m.g_friction * u * u);
    }
    return r;
  }
  r.final_displacement = x_end;
  while (rec.wants(math::infinity())) {
    const double s = rec.next_time();
    rec.put(s, 0.0, math::max(0.0, v1 - m.f1 * (s - t_end)), 0.0, x_end);
  }
  return r;
}

}  // namespace lsi
