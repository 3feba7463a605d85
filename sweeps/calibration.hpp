// Calibration of the closed-form impact models against MPM force histories (pure numerics, no I/O).
//
// Analytical (two-body) model, kernels/closed_form/two_body_model.hpp: fits lambda = s1,max/L1,0
// in (0, 1] and tau = T1/T2 in (0, 1) per case by minimising one of two objectives,
//   nrms           normalised RMS misfit of F(t) on the MPM output times of its impact (0 .. the
//                  MPM's impact duration; after it the MPM's force is the static load of the
//                  retained flow, which the models do not have, for as long as the run goes on):
//                  sqrt(mean_i (F_model(t_i) - F_mpm(t_i))^2) / F_peak,mpm
//   peak-duration  relative residuals of the peak force and of the impact duration, plus the rise
//                  time relative to the MPM impact duration. The third residual is needed: peak
//                  and duration alone depend on lambda only (F_peak = 3 mu v0^2 / (4 lambda L1,0),
//                  T2 = 8 lambda L1,0 / (3 v0)), so tau would be undetermined.
//                  misfit = sqrt(sum of the squared residuals).
// Method: a grid scan (the misfit map, default 41 x 41: lambda_i = (i+1)/N, i < N, which ends at
// 1; tau_j = (j+1)/(M+1), inside (0, 1)), then Levenberg-Marquardt (sweeps/levenberg_marquardt.hpp)
// from the best grid node on logistic-transformed parameters (so the bounds hold), the standard
// error from J^T J at the optimum and the residual variance, and the profile range from the map.
//
// Empirical model, kernels/closed_form/empirical_model.hpp (eqs. 1-10): per case the MPM gives
// alpha_MPM = (F_peak,MPM - F_peak,stat) / (rho v_n^2 h) (eqs. 3-4 solved for alpha, v_n =
// v0 sin(beta), F_peak,stat = kappa rho g h^2 / 2 from eq. 5) and Fr = v_n / sqrt(g h) (eq. 1);
// with alpha = alpha_MPM (the pulse's peak is the MPM's) tau is fitted by the same objective (a
// 1-D scan over the tau axis, then LM). a1, a2 of eq. 2 are pooled over the cases of a group by
// least squares on log(alpha) = log(a1) + a2 log(Fr).
//
// Groups: fixed and free barriers; means with Student-t confidence intervals.
#pragma once
#include <limits>
#include <string>
#include <vector>

#include "kernels/closed_form/force_pulse.hpp"

namespace lsi::sweeps {

enum class Objective { NormalisedRms, PeakDuration };
const char* objective_name(Objective o);  // "nrms", "peak-duration"

// The model inputs of one case (SI; per metre of barrier width).
struct ImpactInputs {
  double landslide_mass = 0.0;                                    // m1, kg/m
  double velocity = 0.0;                                          // v0 = v1,0, m/s (horizontal)
  double equivalent_length = 0.0;                                 // L1,0, m
  double barrier_mass = std::numeric_limits<double>::infinity();  // m2, kg/m (+inf: fixed)
  double thickness = 0.0;                                         // h, m
  double density = 0.0;                                           // rho_m, kg/m^3
  double face_angle = 0.0;                                        // beta, rad
  double kappa = 0.0;  // static coefficient of the empirical model (eq. 5)
  bool fixed = true;
  // The momentum-consistent barrier (kernels/closed_form/momentum_barrier.hpp) only:
  double base_friction = 0.0;  // tan(delta_b)
  double face_friction = 0.0;  // tan(delta) on the face
  double flow_friction = 0.0;  // F1 / m1, m/s^2
};

// One MPM history and its inputs. peak_force / rise_time / impact_duration are the MPM's own
// summaries (model/mpm_runner.cpp); NaN means "derive them from the history" with the same
// definitions (impact_summary below).
struct CalibrationCase {
  std::string name;
  ImpactInputs inputs;
  std::vector<double> time;   // s, increasing, from first contact
  std::vector<double> force;  // N/m, normal to the face
  double peak_force = std::numeric_limits<double>::quiet_NaN();
  double rise_time = std::numeric_limits<double>::quiet_NaN();
  double impact_duration = std::numeric_limits<double>::quiet_NaN();
};

// The MPM runner's definitions: peak and its time; impact duration = last time the force differs
// from its final value (mean of the last 5 % of the samples) by more than 10 % of the peak.
struct ImpactSummary {
  double peak_force, rise_time, impact_duration;
};
ImpactSummary impact_summary(const std::vector<double>& time, const std::vector<double>& force);

struct CalibrationOptions {
  Objective objective = Objective::NormalisedRms;
  // The analytical model fitted: the paper's two-body pulse (false) or the momentum-consistent
  // barrier under the fixed-barrier two-body pulse (true), whose force on a free barrier is not
  // a triangle (docs/theory/models.md).
  bool momentum = false;
  int lambda_cells = 41;            // N: lambda axis (i+1)/N, i = 0..N-1
  int tau_cells = 41;               // M: tau axis (j+1)/(M+1), j = 0..M-1
  int max_iterations = 200;         // LM
  double profile_tolerance = 0.10;  // profile range: misfit <= (1 + tol) * best misfit
};

// Throws std::invalid_argument naming the field and the allowed range.
void validate(const CalibrationOptions& o);
void validate(const CalibrationCase& c);

std::vector<double> lambda_axis(int n);
std::vector<double> tau_axis(int m);

// Model pulses for given parameters.
ForcePulse two_body_pulse(const ImpactInputs& in, double lambda, double tau);
// Empirical pulse with a given alpha (a1 = alpha, a2 = 0 in eq. 2) and tau.
ForcePulse empirical_pulse(const ImpactInputs& in, double alpha, double tau);
double froude_number(const ImpactInputs& in);                     // eq. 1, Fr = v_n / sqrt(g h)
double mpm_alpha(const ImpactInputs& in, double mpm_peak_force);  // eqs. 3-5 solved for alpha

// A model's force at the first `force.size()` MPM output times and its summaries.
struct ModelHistory {
  std::vector<double> force;
  double peak = 0.0, rise_time = 0.0, duration = 0.0;
};
// The MPM samples the nrms objective compares: those of its impact (at least two).
size_t compared_samples(const CalibrationCase& c, const ImpactSummary& mpm);
// The analytical model's history for (lambda, tau): the paper's pulse, or the force the
// momentum-consistent barrier receives.
ModelHistory two_body_history(const CalibrationCase& c, size_t samples, double lambda, double tau,
                              bool momentum);

// The objective's residual vector and misfit for one pulse (or model history) against one case.
std::vector<double> residuals(const CalibrationCase& c, const ImpactSummary& mpm,
                              const ForcePulse& p, Objective o);
std::vector<double> residuals(const CalibrationCase& c, const ImpactSummary& mpm,
                              const ModelHistory& h, Objective o);
double misfit(const CalibrationCase& c, const ImpactSummary& mpm, const ForcePulse& p, Objective o);

struct MisfitMap {
  std::vector<double> lambda;  // N
  std::vector<double> tau;     // M
  std::vector<double> misfit;  // N x M, row-major: misfit[i * M + j] at (lambda[i], tau[j])
  double at(int i, int j) const { return misfit[static_cast<size_t>(i) * tau.size() + j]; }
};

struct Range {
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
};

struct TwoBodyFit {
  double lambda = 0.0, tau = 0.0;                               // best fit (after LM)
  double misfit = 0.0;                                          // objective at the best fit
  double grid_lambda = 0.0, grid_tau = 0.0, grid_misfit = 0.0;  // best node of the map
  // Linearised standard errors: covariance s^2 (J^T J)^-1, s^2 = sum r^2 / (n - 2). NaN when
  // n <= 2 or J^T J is singular. Optimistic for time series: see calibration.cpp.
  double sigma_lambda = 0.0, sigma_tau = 0.0, correlation = 0.0;
  // Profile ranges: the extent of the map nodes with misfit <= (1 + profile_tolerance) x the
  // minimum (and the best fit), widened by one grid spacing on each side, so that they bracket the
  // region at the map's resolution even when it is narrower than a cell; clipped to [0, 1].
  Range lambda_range, tau_range;
  int residual_count = 0;
  int iterations = 0;  // LM Jacobian evaluations
  bool converged = false;
  std::string stop_reason;
  MisfitMap map;
  ImpactSummary mpm{};  // the MPM summaries the fit used
};
TwoBodyFit fit_two_body(const CalibrationCase& c, const CalibrationOptions& o);

struct EmpiricalFit {
  double froude = 0.0, alpha = 0.0;  // Fr and alpha_MPM of the case
  double tau = 0.0, misfit = 0.0, grid_tau = 0.0, grid_misfit = 0.0;
  double sigma_tau = 0.0;
  Range tau_range;  // as TwoBodyFit's, on the 1-D scan
  int iterations = 0;
  bool converged = false;
  std::vector<double> tau_axis, misfit_profile;  // the 1-D scan
};
// Throws std::invalid_argument if alpha_MPM <= 0 (MPM peak not above the static part).
EmpiricalFit fit_empirical(const CalibrationCase& c, const CalibrationOptions& o);

// Mean with a two-sided Student-t confidence interval: mean +- t_{(1+conf)/2, n-1} s / sqrt(n),
// cut to the values' domain [domain.low, domain.high] (a mean of values in the domain lies in
// it, so the cut interval covers it as often as the whole one: e.g. tau's interval stays in
// [0, 1] when a few values lie near 0). n = 1: the interval is NaN (no spread can be estimated).
struct GroupStatistic {
  int n = 0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double stddev = std::numeric_limits<double>::quiet_NaN();  // sample (n - 1)
  Range ci;
  double confidence = 0.95;
};
GroupStatistic pooled_mean(const std::vector<double>& values, double confidence = 0.95,
                           Range domain = {-std::numeric_limits<double>::infinity(),
                                           std::numeric_limits<double>::infinity()});

// (Student's t quantiles: sweeps/statistics.hpp, stats::student_t_quantile.)

// alpha = a1 Fr^a2 by least squares on log(alpha) = log(a1) + a2 log(Fr).
struct PowerLawFit {
  int n = 0;
  double a1 = std::numeric_limits<double>::quiet_NaN();
  double a2 = std::numeric_limits<double>::quiet_NaN();
  Range a1_ci, a2_ci;  // Student-t with n - 2 degrees of freedom (NaN when n <= 2)
  double rms_log_residual = std::numeric_limits<double>::quiet_NaN();
  double confidence = 0.95;
};
// Throws std::invalid_argument for non-positive values or mismatched sizes; NaN a2 when fewer
// than 2 distinct Froude numbers.
PowerLawFit fit_power_law(const std::vector<double>& froude, const std::vector<double>& alpha,
                          double confidence = 0.95);

// The paper's calibrated values (Cuomo et al. 2022; empirical: Di Perna et al. 2022).
struct PaperValues {
  double lambda, tau;            // two-body
  double a1, a2, empirical_tau;  // empirical (the same for both groups)
};
PaperValues paper_values(bool fixed);

struct GroupSummary {
  bool fixed = false;
  std::vector<std::string> cases;
  GroupStatistic lambda, tau, empirical_tau;
  PowerLawFit power_law;
  PaperValues paper{};
};
// Pools the fits of the cases of one group (all vectors of the same length, in case order).
GroupSummary summarize_group(bool fixed, const std::vector<std::string>& names,
                             const std::vector<TwoBodyFit>& two_body,
                             const std::vector<EmpiricalFit>& empirical, double confidence = 0.95);

}  // namespace lsi::sweeps
