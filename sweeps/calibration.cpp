// Calibration of the closed-form models against MPM force histories; see calibration.hpp.
#include "sweeps/calibration.hpp"
#include "sweeps/statistics.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kernels/closed_form/empirical_model.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/momentum_barrier.hpp"
#include "kernels/closed_form/two_body_model.hpp"
#include "kernels/common/constants.hpp"
#include "sweeps/levenberg_marquardt.hpp"
#include "kernels/common/math.hpp"

namespace lsi::sweeps {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Bounds by transform: x in (0, 1) <-> u in R, x = 1 / (1 + exp(-u)). u is clipped to +-40 so
// that x stays representable and strictly inside (0, 1).
double logistic(double u) { return 1.0 / (1.0 + std::exp(-std::clamp(u, -40.0, 40.0))); }
double logit(double x) {
  x = std::clamp(x, 1e-12, 1.0 - 1e-12);
  return std::log(x / (1.0 - x));
}

ImpactSummary mpm_summary_of(const CalibrationCase& c) {
  ImpactSummary s = impact_summary(c.time, c.force);
  if (std::isfinite(c.peak_force)) s.peak_force = c.peak_force;
  if (std::isfinite(c.rise_time)) s.rise_time = c.rise_time;
  if (std::isfinite(c.impact_duration)) s.impact_duration = c.impact_duration;
  return s;
}

Eigen::VectorXd to_eigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// Linearised covariance of the parameters theta at the optimum: s^2 (J^T J)^-1 with
// s^2 = sum r^2 / (n - p), J = d r / d theta by central differences (one-sided next to a bound).
//
// Why this is optimistic for force histories: the formula assumes independent residuals. The
// residuals of a fit to a time series are strongly autocorrelated (the misfit is a smooth,
// systematic model error, the triangle against the MPM's rounded pulse, and the MPM samples its
// output every 1/400 of the run, much finer than the pulse's own time scale), so the effective
// number of independent residuals is far smaller than n, and the true uncertainty is larger by
// roughly sqrt(n / n_eff). Model error, not noise, dominates: the profile range of the misfit map
// (within a tolerance of the minimum) is the more honest spread, and both are reported.
template <class ResidualOf>
Eigen::MatrixXd covariance(ResidualOf&& r, const Eigen::VectorXd& theta, const Eigen::VectorXd& lo,
                           const Eigen::VectorXd& hi) {
  const Eigen::VectorXd r0 = r(theta);
  const Eigen::Index n = r0.size(), p = theta.size();
  Eigen::MatrixXd J(n, p);
  for (Eigen::Index k = 0; k < p; ++k) {
    const double h = 1e-6 * std::max(1e-3, std::fabs(theta[k]));
    Eigen::VectorXd a = theta, b = theta;
    a[k] = std::min(theta[k] + h, hi[k]);
    b[k] = std::max(theta[k] - h, lo[k]);
    J.col(k) = (r(a) - r(b)) / (a[k] - b[k]);
  }
  Eigen::MatrixXd cov = Eigen::MatrixXd::Constant(p, p, nan);
  if (n <= p) return cov;
  const double s2 = r0.squaredNorm() / static_cast<double>(n - p);
  const Eigen::MatrixXd A = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  lu.setThreshold(1e-12);
  if (!lu.isInvertible()) return cov;
  return s2 * lu.inverse();
}

// The model pulse is piecewise linear in t, so a residual F(t_i) has a kink in (lambda, tau)
// wherever T1 or T2 crosses a sample time t_i; near a minimum surrounded by such kinks LM keeps
// finding decreases of 1e-9 relative per step and creeps (the reference case L3-B3 moved lambda by
// 4e-5 in 200 iterations, changing the misfit in its 7th digit). An accepted step that lowers the
// sum of squares by less than 1e-8 relative (the misfit in its 9th digit) therefore ends the fit.
LmOptions lm_options(const CalibrationOptions& o) {
  LmOptions lm;
  lm.max_iterations = o.max_iterations;
  lm.f_tol = 1e-8;
  lm.x_tol = 1e-9;
  return lm;
}

// The map resolves the region {misfit <= (1 + tol) min} only to its spacing: the nodes inside it
// (and the best fit) give an inner estimate, and the region's true edge lies between the last
// node inside and the first outside. Widening by one spacing on each side (clipped to the axis's
// interval (0, 1]) gives an outer bracket, which is what we report: for a sharp minimum, between
// nodes, it is still a valid (if coarse) bracket rather than a single point.
Range widen_by_one_cell(Range r, const std::vector<double>& axis) {
  const double step = axis.size() > 1 ? axis[1] - axis[0] : 0.0;
  const double lo = axis.front() - step, hi = axis.back() + step;
  return {std::max(r.low - step, std::max(lo, 0.0)), std::min(r.high + step, std::min(hi, 1.0))};
}

}  // namespace

const char* objective_name(Objective o) {
  return o == Objective::NormalisedRms ? "nrms" : "peak-duration";
}

ImpactSummary impact_summary(const std::vector<double>& time, const std::vector<double>& force) {
  ImpactSummary s{nan, nan, nan};
  const size_t n = std::min(time.size(), force.size());
  if (n == 0) return s;
  const size_t peak = std::max_element(force.begin(), force.begin() + n) - force.begin();
  s.peak_force = force[peak];
  s.rise_time = time[peak];
  const size_t tail = std::max<size_t>(1, n / 20);
  double final_force = 0.0;
  for (size_t i = n - tail; i < n; ++i) final_force += force[i] / tail;
  s.impact_duration = time[peak];
  for (size_t i = peak; i < n; ++i)
    if (std::fabs(force[i] - final_force) > 0.1 * s.peak_force) s.impact_duration = time[i];
  return s;
}

void validate(const CalibrationOptions& o) {
  if (o.lambda_cells < 2 || o.lambda_cells > 2001)
    throw std::invalid_argument("grid lambda cells = " + std::to_string(o.lambda_cells) +
                                ": must be in [2, 2001]");
  if (o.tau_cells < 2 || o.tau_cells > 2001)
    throw std::invalid_argument("grid tau cells = " + std::to_string(o.tau_cells) +
                                ": must be in [2, 2001]");
  if (o.max_iterations < 0)
    throw std::invalid_argument("max_iterations = " + std::to_string(o.max_iterations) +
                                ": must be >= 0");
  if (!(o.profile_tolerance >= 0.0))
    throw std::invalid_argument("profile_tolerance = " + num(o.profile_tolerance) +
                                ": must be >= 0");
}

void validate(const CalibrationCase& c) {
  const ImpactInputs& in = c.inputs;
  auto positive = [&](const char* what, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw std::invalid_argument(c.name + ": " + what + " = " + num(v) +
                                  ": must be finite and > 0");
  };
  positive("landslide_mass", in.landslide_mass);
  positive("velocity", in.velocity);
  positive("equivalent_length", in.equivalent_length);
  positive("thickness", in.thickness);
  positive("density", in.density);
  if (!(in.barrier_mass > 0.0))
    throw std::invalid_argument(c.name + ": barrier_mass = " + num(in.barrier_mass) +
                                ": must be > 0 (+inf for a fixed barrier)");
  if (!(in.face_angle > 0.0 && in.face_angle <= math::pi() / 2 + 1e-12))
    throw std::invalid_argument(c.name + ": face_angle = " + num(in.face_angle) +
                                ": must be in (0, pi/2] rad");
  if (c.time.size() != c.force.size())
    throw std::invalid_argument(c.name + ": time has " + std::to_string(c.time.size()) +
                                " samples and force " + std::to_string(c.force.size()) +
                                ": must be equal");
  if (c.time.size() < 3)
    throw std::invalid_argument(c.name + ": MPM history has " + std::to_string(c.time.size()) +
                                " samples: must have >= 3");
  for (size_t i = 0; i < c.time.size(); ++i) {
    if (!std::isfinite(c.time[i]) || !std::isfinite(c.force[i]))
      throw std::invalid_argument(c.name + ": MPM history sample " + std::to_string(i) +
                                  " is not finite");
    if (i > 0 && !(c.time[i] > c.time[i - 1]))
      throw std::invalid_argument(c.name + ": MPM time must increase (sample " + std::to_string(i) +
                                  ")");
  }
  const ImpactSummary s = mpm_summary_of(c);
  if (!(s.peak_force > 0.0))
    throw std::invalid_argument(c.name + ": MPM peak force = " + num(s.peak_force) +
                                ": must be > 0");
  if (!(s.impact_duration > 0.0))
    throw std::invalid_argument(c.name + ": MPM impact duration = " + num(s.impact_duration) +
                                ": must be > 0");
}

std::vector<double> lambda_axis(int n) {
  std::vector<double> a(n);
  for (int i = 0; i < n; ++i) a[i] = double(i + 1) / n;
  return a;
}

std::vector<double> tau_axis(int m) {
  std::vector<double> a(m);
  for (int j = 0; j < m; ++j) a[j] = double(j + 1) / (m + 1);
  return a;
}

ForcePulse two_body_pulse(const ImpactInputs& in, double lambda, double tau) {
  return two_body_impact(in.landslide_mass, in.velocity, in.equivalent_length,
                         in.fixed ? std::numeric_limits<double>::infinity() : in.barrier_mass,
                         TwoBodyCoefficients{lambda, tau})
      .pulse;
}

ForcePulse empirical_pulse(const ImpactInputs& in, double alpha, double tau) {
  EmpiricalCoefficients c;
  c.a1 = alpha;  // alpha = a1 Fr^0
  c.a2 = 0.0;
  c.tau = tau;
  c.kappa = in.kappa;
  return empirical_impact(in.thickness, in.velocity, in.density, in.landslide_mass, in.face_angle,
                          c)
      .pulse;
}

double froude_number(const ImpactInputs& in) {
  return in.velocity * std::sin(in.face_angle) / std::sqrt(gravity * in.thickness);
}

double mpm_alpha(const ImpactInputs& in, double mpm_peak_force) {
  // eq. 3: F_peak = F_dyn + F_stat; eq. 4: F_dyn = alpha rho v_n^2 h; eq. 5: F_stat = kappa rho g h^2/2.
  const double vn = in.velocity * std::sin(in.face_angle);
  const double f_stat = 0.5 * in.kappa * in.density * gravity * in.thickness * in.thickness;
  return (mpm_peak_force - f_stat) / (in.density * vn * vn * in.thickness);
}

size_t compared_samples(const CalibrationCase& c, const ImpactSummary& mpm) {
  // The samples up to the MPM's impact duration (at least the first two). What follows is the
  // static load of the retained flow, outside the models, and as long as the run goes on at rest.
  size_t n = 0;
  while (n < c.time.size() && c.time[n] <= mpm.impact_duration) ++n;
  return std::max<size_t>(n, 2);
}

ModelHistory two_body_history(const CalibrationCase& c, size_t samples, double lambda, double tau,
                              bool momentum) {
  const ImpactInputs& in = c.inputs;
  ModelHistory h;
  h.force.resize(samples);
  if (!momentum) {
    const ForcePulse p = two_body_pulse(in, lambda, tau);
    for (size_t i = 0; i < samples; ++i) h.force[i] = p.force(c.time[i]);
    h.peak = p.peak;
    h.rise_time = p.rise_time;
    h.duration = p.duration;
    return h;
  }
  MomentumBarrierSetup s;
  s.face = resolve_face_force(in.face_angle, in.face_friction);
  s.fixed_pulse = momentum_two_body_pulse(in.landslide_mass, in.velocity, in.equivalent_length,
                                          lambda, tau, s.face.horizontal);
  s.landslide_mass = in.landslide_mass;
  s.velocity = in.velocity;
  s.barrier_mass = in.fixed ? std::numeric_limits<double>::infinity() : in.barrier_mass;
  s.base_friction = in.base_friction;
  s.flow_friction = in.flow_friction;
  std::vector<MomentumBarrierState> st(samples);
  const MomentumBarrierResult r =
      momentum_barrier(s, c.time.data(), static_cast<int>(samples), st.data());
  for (size_t i = 0; i < samples; ++i) h.force[i] = st[i].force;
  h.peak = r.peak_force;
  h.rise_time = r.rise_time;
  h.duration = r.contact_end;
  return h;
}

std::vector<double> residuals(const CalibrationCase& c, const ImpactSummary& mpm,
                              const ModelHistory& h, Objective o) {
  if (o == Objective::NormalisedRms) {
    // sum r_i^2 = mean (F_model - F_mpm)^2 / F_peak^2 = nrms^2, over the MPM's impact.
    const size_t n = h.force.size();
    const double scale = 1.0 / (mpm.peak_force * std::sqrt(static_cast<double>(n)));
    std::vector<double> r(n);
    for (size_t i = 0; i < n; ++i) r[i] = (h.force[i] - c.force[i]) * scale;
    return r;
  }
  return {(h.peak - mpm.peak_force) / mpm.peak_force,
          (h.duration - mpm.impact_duration) / mpm.impact_duration,
          (h.rise_time - mpm.rise_time) / mpm.impact_duration};
}

std::vector<double> residuals(const CalibrationCase& c, const ImpactSummary& mpm,
                              const ForcePulse& p, Objective o) {
  ModelHistory h;
  h.force.resize(o == Objective::NormalisedRms ? compared_samples(c, mpm) : 0);
  for (size_t i = 0; i < h.force.size(); ++i) h.force[i] = p.force(c.time[i]);
  h.peak = p.peak;
  h.rise_time = p.rise_time;
  h.duration = p.duration;
  return residuals(c, mpm, h, o);
}

double misfit(const CalibrationCase& c, const ImpactSummary& mpm, const ForcePulse& p,
              Objective o) {
  double s = 0.0;
  for (double r : residuals(c, mpm, p, o)) s += r * r;
  return std::sqrt(s);
}

TwoBodyFit fit_two_body(const CalibrationCase& c, const CalibrationOptions& o) {
  validate(o);
  validate(c);
  TwoBodyFit f;
  f.mpm = mpm_summary_of(c);
  const size_t samples = o.objective == Objective::NormalisedRms ? compared_samples(c, f.mpm) : 0;
  auto model_residuals = [&](double lambda, double tau) {
    return residuals(c, f.mpm, two_body_history(c, samples, lambda, tau, o.momentum), o.objective);
  };
  auto model_misfit = [&](double lambda, double tau) {
    double s = 0.0;
    for (double r : model_residuals(lambda, tau)) s += r * r;
    return std::sqrt(s);
  };

  // 1. Grid scan: the misfit map.
  f.map.lambda = lambda_axis(o.lambda_cells);
  f.map.tau = tau_axis(o.tau_cells);
  f.map.misfit.resize(f.map.lambda.size() * f.map.tau.size());
  size_t best = 0;
  for (size_t i = 0; i < f.map.lambda.size(); ++i)
    for (size_t j = 0; j < f.map.tau.size(); ++j) {
      const size_t k = i * f.map.tau.size() + j;
      f.map.misfit[k] = model_misfit(f.map.lambda[i], f.map.tau[j]);
      if (f.map.misfit[k] < f.map.misfit[best]) best = k;
    }
  f.grid_lambda = f.map.lambda[best / f.map.tau.size()];
  f.grid_tau = f.map.tau[best % f.map.tau.size()];
  f.grid_misfit = f.map.misfit[best];

  // 2. Levenberg-Marquardt from the best node, on u = logit(theta) (bounds by transform).
  auto r_of_theta = [&](const Eigen::VectorXd& th) {
    return to_eigen(model_residuals(th[0], th[1]));
  };
  auto r_of_u = [&](const Eigen::VectorXd& u) {
    Eigen::VectorXd th(2);
    th << logistic(u[0]), logistic(u[1]);
    return r_of_theta(th);
  };
  Eigen::VectorXd u0(2);
  u0 << logit(f.grid_lambda), logit(f.grid_tau);
  const LmResult res = levenberg_marquardt(r_of_u, u0, lm_options(o));
  f.lambda = logistic(res.x[0]);
  f.tau = logistic(res.x[1]);
  f.misfit = std::sqrt(res.cost);
  if (f.grid_misfit <= f.misfit) {  // logit/logistic round-off can make LM's start a hair worse
    f.lambda = f.grid_lambda;
    f.tau = f.grid_tau;
    f.misfit = f.grid_misfit;
  }
  f.iterations = res.iterations;
  f.converged = res.converged;
  f.stop_reason = res.reason;
  f.residual_count = static_cast<int>(r_of_theta(Eigen::Vector2d(f.lambda, f.tau)).size());

  // 3. Uncertainty: linearised (optimistic, see covariance()) and the profile range of the map.
  Eigen::VectorXd th(2), lo(2), hi(2);
  th << f.lambda, f.tau;
  lo << 1e-9, 1e-9;
  hi << 1.0, 1.0 - 1e-9;
  const Eigen::MatrixXd cov = covariance(r_of_theta, th, lo, hi);
  f.sigma_lambda = std::sqrt(cov(0, 0));
  f.sigma_tau = std::sqrt(cov(1, 1));
  f.correlation = cov(0, 1) / (f.sigma_lambda * f.sigma_tau);
  const double threshold = (1.0 + o.profile_tolerance) * std::min(f.misfit, f.grid_misfit);
  f.lambda_range = {f.lambda, f.lambda};
  f.tau_range = {f.tau, f.tau};
  for (size_t i = 0; i < f.map.lambda.size(); ++i)
    for (size_t j = 0; j < f.map.tau.size(); ++j)
      if (f.map.misfit[i * f.map.tau.size() + j] <= threshold) {
        f.lambda_range.low = std::min(f.lambda_range.low, f.map.lambda[i]);
        f.lambda_range.high = std::max(f.lambda_range.high, f.map.lambda[i]);
        f.tau_range.low = std::min(f.tau_range.low, f.map.tau[j]);
        f.tau_range.high = std::max(f.tau_range.high, f.map.tau[j]);
      }
  f.lambda_range = widen_by_one_cell(f.lambda_range, f.map.lambda);
  f.tau_range = widen_by_one_cell(f.tau_range, f.map.tau);
  return f;
}

EmpiricalFit fit_empirical(const CalibrationCase& c, const CalibrationOptions& o) {
  validate(o);
  validate(c);
  EmpiricalFit f;
  const ImpactSummary mpm = mpm_summary_of(c);
  const ImpactInputs& in = c.inputs;
  f.froude = froude_number(in);
  f.alpha = mpm_alpha(in, mpm.peak_force);
  if (!(f.alpha > 0.0))
    throw std::invalid_argument(c.name + ": alpha_MPM = " + num(f.alpha) +
                                ": must be > 0 (the MPM peak force must exceed the static part "
                                "kappa rho g h^2 / 2)");
  f.tau_axis = tau_axis(o.tau_cells);
  f.misfit_profile.resize(f.tau_axis.size());
  size_t best = 0;
  for (size_t j = 0; j < f.tau_axis.size(); ++j) {
    f.misfit_profile[j] = misfit(c, mpm, empirical_pulse(in, f.alpha, f.tau_axis[j]), o.objective);
    if (f.misfit_profile[j] < f.misfit_profile[best]) best = j;
  }
  f.grid_tau = f.tau_axis[best];
  f.grid_misfit = f.misfit_profile[best];
  auto r_of_tau = [&](const Eigen::VectorXd& t) {
    return to_eigen(residuals(c, mpm, empirical_pulse(in, f.alpha, t[0]), o.objective));
  };
  auto r_of_u = [&](const Eigen::VectorXd& u) {
    return r_of_tau(Eigen::VectorXd::Constant(1, logistic(u[0])));
  };
  const LmResult res =
      levenberg_marquardt(r_of_u, Eigen::VectorXd::Constant(1, logit(f.grid_tau)), lm_options(o));
  f.tau = logistic(res.x[0]);
  f.misfit = std::sqrt(res.cost);
  f.iterations = res.iterations;
  f.converged = res.converged;
  const Eigen::MatrixXd cov =
      covariance(r_of_tau, Eigen::VectorXd::Constant(1, f.tau), Eigen::VectorXd::Constant(1, 1e-9),
                 Eigen::VectorXd::Constant(1, 1.0 - 1e-9));
  f.sigma_tau = std::sqrt(cov(0, 0));
  const double threshold = (1.0 + o.profile_tolerance) * std::min(f.misfit, f.grid_misfit);
  f.tau_range = {f.tau, f.tau};
  for (size_t j = 0; j < f.tau_axis.size(); ++j)
    if (f.misfit_profile[j] <= threshold) {
      f.tau_range.low = std::min(f.tau_range.low, f.tau_axis[j]);
      f.tau_range.high = std::max(f.tau_range.high, f.tau_axis[j]);
    }
  f.tau_range = widen_by_one_cell(f.tau_range, f.tau_axis);
  return f;
}

// ---------------------------------------------------------------------------------------------
// Statistics.

GroupStatistic pooled_mean(const std::vector<double>& v, double confidence, Range domain) {
  GroupStatistic s;
  s.confidence = confidence;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double ss = 0.0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.stddev = std::sqrt(ss / (s.n - 1));
  const double half =
      stats::student_t_quantile(0.5 * (1.0 + confidence), s.n - 1) * s.stddev / std::sqrt(s.n);
  s.ci = {std::max(s.mean - half, domain.low), std::min(s.mean + half, domain.high)};
  return s;
}

PowerLawFit fit_power_law(const std::vector<double>& froude, const std::vector<double>& alpha,
                          double confidence) {
  if (froude.size() != alpha.size())
    throw std::invalid_argument("fit_power_law: " + std::to_string(froude.size()) +
                                " Froude numbers and " + std::to_string(alpha.size()) +
                                " alphas: must be equal");
  PowerLawFit f;
  f.confidence = confidence;
  f.n = static_cast<int>(froude.size());
  for (int i = 0; i < f.n; ++i)
    if (!(froude[i] > 0.0) || !(alpha[i] > 0.0))
      throw std::invalid_argument("fit_power_law: Fr = " + num(froude[i]) + ", alpha = " +
                                  num(alpha[i]) + ": both must be > 0 (log-log fit)");
  if (f.n < 2) return f;
  Eigen::MatrixXd X(f.n, 2);
  Eigen::VectorXd y(f.n);
  for (int i = 0; i < f.n; ++i) {
    X(i, 0) = 1.0;
    X(i, 1) = std::log(froude[i]);
    y[i] = std::log(alpha[i]);
  }
  const Eigen::MatrixXd A = X.transpose() * X;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  lu.setThreshold(1e-12);
  if (!lu.isInvertible()) return f;  // all Froude numbers equal: a2 undetermined
  const Eigen::VectorXd b = lu.solve(X.transpose() * y);
  f.a1 = std::exp(b[0]);
  f.a2 = b[1];
  const Eigen::VectorXd res = y - X * b;
  f.rms_log_residual = std::sqrt(res.squaredNorm() / f.n);
  if (f.n <= 2) return f;
  const double s2 = res.squaredNorm() / (f.n - 2);
  const Eigen::MatrixXd cov = s2 * lu.inverse();
  const double t = stats::student_t_quantile(0.5 * (1.0 + confidence), f.n - 2);
  const double h0 = t * std::sqrt(cov(0, 0)), h1 = t * std::sqrt(cov(1, 1));
  f.a1_ci = {std::exp(b[0] - h0), std::exp(b[0] + h0)};
  f.a2_ci = {b[1] - h1, b[1] + h1};
  return f;
}

PaperValues paper_values(bool fixed) {
  const TwoBodyCoefficients c = default_two_body_coefficients(fixed);
  const EmpiricalCoefficients e;
  return {c.lambda, c.tau, e.a1, e.a2, e.tau};
}

GroupSummary summarize_group(bool fixed, const std::vector<std::string>& names,
                             const std::vector<TwoBodyFit>& two_body,
                             const std::vector<EmpiricalFit>& empirical, double confidence) {
  if (two_body.size() != names.size() || empirical.size() != names.size())
    throw std::invalid_argument("summarize_group: " + std::to_string(names.size()) + " names, " +
                                std::to_string(two_body.size()) + " two-body and " +
                                std::to_string(empirical.size()) +
                                " empirical fits: must be equal");
  GroupSummary g;
  g.fixed = fixed;
  g.cases = names;
  g.paper = paper_values(fixed);
  std::vector<double> lam, tau, etau, fr, al;
  for (size_t i = 0; i < names.size(); ++i) {
    lam.push_back(two_body[i].lambda);
    tau.push_back(two_body[i].tau);
    etau.push_back(empirical[i].tau);
    fr.push_back(empirical[i].froude);
    al.push_back(empirical[i].alpha);
  }
  const double inf = std::numeric_limits<double>::infinity();
  g.lambda = pooled_mean(lam, confidence, {0.0, inf});  // lambda = s1,max / L1,0 > 0
  g.tau = pooled_mean(tau, confidence, {0.0, 1.0});     // tau = T1 / T2 in (0, 1)
  g.empirical_tau = pooled_mean(etau, confidence, {0.0, 1.0});
  g.power_law = fit_power_law(fr, al, confidence);
  return g;
}

}  // namespace lsi::sweeps
