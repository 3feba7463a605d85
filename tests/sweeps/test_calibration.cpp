// Calibration of the closed-form models (sweeps/calibration.hpp): recovery of known parameters
// from synthetic histories made by the models themselves, the misfit map, Levenberg-Marquardt,
// the uncertainty, the Student-t pooling and the a1, a2 regression.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "kernels/closed_form/two_body_model.hpp"
#include "sweeps/calibration.hpp"
#include "sweeps/statistics.hpp"
#include "sweeps/levenberg_marquardt.hpp"
#include "support/tolerances.hpp"

namespace {
using namespace lsi::sweeps;
using lsi::test::kFewOpsAbs;
using lsi::test::kRoundOffAbs;
using lsi::test::kUnitArithmeticAbs;

// The cost of a zero-residual problem after Levenberg-Marquardt: it stops on a relative decrease
// of 1e-12 or a step of 1e-10, so the cost left is below 1e-12.
constexpr double kLmZeroCost = 1e-12;

// A landslide like L1 of the reference study against a barrier like B1 (m2 = 14.4 t/m).
ImpactInputs inputs(bool fixed) {
  ImpactInputs in;
  in.landslide_mass = 54000.0;
  in.velocity = 6.0;
  in.equivalent_length = 15.0;
  in.barrier_mass = fixed ? std::numeric_limits<double>::infinity() : 14400.0;
  in.thickness = 2.0;
  in.density = 1800.0;
  in.face_angle = 80.0 * M_PI / 180.0;
  in.fixed = fixed;
  return in;
}

// The model's own pulse sampled at n uniform times on [0, 1.5 T2] (the MPM runs past the impact).
CalibrationCase synthetic(const ImpactInputs& in, double lambda, double tau, int n,
                          double noise_fraction = 0.0, unsigned seed = 1) {
  CalibrationCase c;
  c.name = "synthetic";
  c.inputs = in;
  const lsi::ForcePulse p = two_body_pulse(in, lambda, tau);
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, noise_fraction * p.peak);
  for (int i = 0; i < n; ++i) {
    const double t = 1.5 * p.duration * i / (n - 1);
    c.time.push_back(t);
    c.force.push_back(p.force(t) + (noise_fraction > 0.0 ? normal(rng) : 0.0));
  }
  // The model's own summaries (the MPM's 10 %-of-peak duration of a sampled triangle is not T2).
  c.peak_force = p.peak;
  c.rise_time = p.rise_time;
  c.impact_duration = p.duration;
  return c;
}

TEST(Calibration, RecoversExactParametersWithTheNrmsObjective) {
  for (bool fixed : {false, true}) {
    // Off the grid (41 x 41 nodes at multiples of 1/41 and 1/42).
    const double lambda = 0.53, tau = 0.23;
    const CalibrationCase c = synthetic(inputs(fixed), lambda, tau, 400);
    const TwoBodyFit f = fit_two_body(c, CalibrationOptions{});
    // Exact data: the misfit is zero at the truth; LM stops on a relative decrease of 1e-12 or a
    // step of 1e-10, so the parameters are recovered to far better than 1e-6.
    EXPECT_NEAR(f.lambda, lambda, 1e-6) << "fixed " << fixed;
    EXPECT_NEAR(f.tau, tau, 1e-6) << "fixed " << fixed;
    EXPECT_LT(f.misfit, 1e-7) << "fixed " << fixed;
    EXPECT_TRUE(f.converged) << f.stop_reason;
    EXPECT_GT(f.iterations, 0);
    // The samples of the impact, t <= T2 = 1.5 T2 x 266 / 399 (the MPM's impact duration).
    EXPECT_EQ(f.residual_count, 267);
  }
}

// The nrms objective compares the impact only: a static load after it (the retained flow of an
// MPM run that goes on until all is at rest) changes nothing, however long it lasts.
TEST(Calibration, NrmsIgnoresTheStaticLoadAfterTheImpact) {
  const double lambda = 0.53, tau = 0.23;
  const CalibrationCase c = synthetic(inputs(true), lambda, tau, 400);
  CalibrationCase tail = c;
  const double dt = tail.time[1] - tail.time[0];
  for (int i = 1; i <= 2000; ++i) {  // four times the impact's length of a 15 % static load
    tail.time.push_back(c.time.back() + i * dt);
    tail.force.push_back(0.15 * c.peak_force);
  }
  const TwoBodyFit a = fit_two_body(c, CalibrationOptions{});
  const TwoBodyFit b = fit_two_body(tail, CalibrationOptions{});
  EXPECT_EQ(a.lambda, b.lambda);
  EXPECT_EQ(a.tau, b.tau);
  EXPECT_EQ(a.misfit, b.misfit);
  EXPECT_EQ(a.residual_count, b.residual_count);
}

TEST(Calibration, RecoversExactParametersWithThePeakDurationObjective) {
  CalibrationOptions o;
  o.objective = Objective::PeakDuration;
  for (bool fixed : {false, true}) {
    const double lambda = 0.41 + 0.013, tau = 0.25 + 0.007;
    const TwoBodyFit f = fit_two_body(synthetic(inputs(fixed), lambda, tau, 200), o);
    // Three residuals that all vanish at the truth: recovered to LM's tolerance.
    EXPECT_NEAR(f.lambda, lambda, 1e-6);
    EXPECT_NEAR(f.tau, tau, 1e-6);
    EXPECT_LT(f.misfit, 1e-7);
    EXPECT_EQ(f.residual_count, 3);
  }
}

TEST(Calibration, NoisyCoarseHistoryIsRecoveredWithinItsStandardError) {
  // 60 samples over 1.5 T2 (40 in the impact, about 11 in the rise) with white Gaussian noise of 2 % of
  // the peak. For independent residuals the linearised covariance is the right one, so the
  // error of the estimate is within 4 of its standard errors (a 4-sigma band, > 99.99 %).
  const double lambda = 0.47, tau = 0.31, noise = 0.02;
  const int n = 60;
  const int m = 40;  // the samples of the impact, t <= T2 (i <= 59 / 1.5)
  for (unsigned seed : {1u, 2u, 3u}) {
    const TwoBodyFit f = fit_two_body(synthetic(inputs(false), lambda, tau, n, noise, seed), {});
    EXPECT_NEAR(f.lambda, lambda, 4.0 * f.sigma_lambda) << "seed " << seed;
    EXPECT_NEAR(f.tau, tau, 4.0 * f.sigma_tau) << "seed " << seed;
    // The standard errors are not vacuous: a 2 % noise on 60 samples pins lambda to about 1 %.
    EXPECT_LT(f.sigma_lambda, 0.02 * lambda);
    EXPECT_LT(f.sigma_tau, 0.1 * tau);
    EXPECT_GT(f.sigma_lambda, 0.0);
    // The best misfit is the noise level: nrms^2 ~ noise^2 (m - 2) / m with a chi-square spread
    // of relative sd 1/sqrt(2 (m - 2)) = 11 %; 35 % is more than 3 sd.
    const double expected = noise * std::sqrt((m - 2.0) / m);
    EXPECT_NEAR(f.misfit, expected, 0.35 * expected) << "seed " << seed;
    // The profile range (misfit within 10 % of the minimum) brackets the truth.
    EXPECT_LE(f.lambda_range.low, lambda);
    EXPECT_GE(f.lambda_range.high, lambda);
    EXPECT_LE(f.tau_range.low, tau);
    EXPECT_GE(f.tau_range.high, tau);
  }
}

TEST(Calibration, PeakDurationWithPerturbedSummariesFollowsTheLinearisedSolution) {
  // Relative errors e1, e2, e3 on the MPM's peak, duration and rise time. With F_peak ~ 1/lambda
  // and T2 ~ lambda, r1 ~ -d - e1 and r2 ~ d - e2 for lambda = lambda0 (1 + d): the least-squares
  // d = (e2 - e1) / 2, to second order in e (|e| <= 2 %: error below 2 e^2 = 8e-4). The rise
  // time residual can always be zeroed by tau: tau = tau0 (1 + e3) T2(lambda0) / T2(lambda), exact.
  CalibrationOptions o;
  o.objective = Objective::PeakDuration;
  const double lambda0 = 0.6, tau0 = 0.2;
  const double e1 = 0.02, e2 = -0.015, e3 = 0.01;
  CalibrationCase c = synthetic(inputs(true), lambda0, tau0, 100);
  c.peak_force *= 1.0 + e1;
  c.impact_duration *= 1.0 + e2;
  c.rise_time *= 1.0 + e3;
  const TwoBodyFit f = fit_two_body(c, o);
  const double d = f.lambda / lambda0 - 1.0;
  EXPECT_NEAR(d, 0.5 * (e2 - e1), 2.0 * 0.02 * 0.02);
  EXPECT_NEAR(f.tau, tau0 * (1.0 + e3) / (f.lambda / lambda0), 1e-6);
  // Three residuals, two parameters: one residual degree of freedom, standard errors finite.
  EXPECT_TRUE(std::isfinite(f.sigma_lambda));
}

TEST(Calibration, MisfitMapMinimumCellContainsTheTruthAndLmImprovesOnIt) {
  const double lambda = 0.53, tau = 0.23;
  const CalibrationCase c = synthetic(inputs(false), lambda, tau, 400);
  const TwoBodyFit f = fit_two_body(c, {});
  ASSERT_EQ(f.map.lambda.size(), 41u);
  ASSERT_EQ(f.map.tau.size(), 41u);
  ASSERT_EQ(f.map.misfit.size(), 41u * 41u);
  EXPECT_DOUBLE_EQ(f.map.lambda.front(), 1.0 / 41);
  EXPECT_DOUBLE_EQ(f.map.lambda.back(), 1.0);
  EXPECT_DOUBLE_EQ(f.map.tau.front(), 1.0 / 42);
  EXPECT_DOUBLE_EQ(f.map.tau.back(), 41.0 / 42);
  // The truth lies in a grid cell that has the minimum node as a corner: within one spacing.
  EXPECT_LE(std::fabs(f.grid_lambda - lambda), 1.0 / 41 + kRoundOffAbs);
  EXPECT_LE(std::fabs(f.grid_tau - tau), 1.0 / 42 + kRoundOffAbs);
  // The map's value at the best node is what grid_misfit reports.
  double min_cell = f.map.misfit[0];
  for (double m : f.map.misfit) min_cell = std::min(min_cell, m);
  EXPECT_DOUBLE_EQ(f.grid_misfit, min_cell);
  // LM improves on the grid: the grid node is off the truth by up to a spacing (misfit of order
  // 1e-2), LM reaches the exact zero (1e-7, far below 1e-3 of the grid's).
  EXPECT_GT(f.grid_misfit, 1e-3);
  EXPECT_LT(f.misfit, 1e-3 * f.grid_misfit);
}

TEST(Calibration, TruthOnAGridNodeIsTheMapMinimum) {
  // lambda = 20/41, tau = 10/42 are nodes: the map's minimum is there with misfit ~ 0 (rounding).
  const double lambda = 20.0 / 41, tau = 10.0 / 42;
  const TwoBodyFit f = fit_two_body(synthetic(inputs(true), lambda, tau, 300), {});
  EXPECT_DOUBLE_EQ(f.grid_lambda, lambda);
  EXPECT_DOUBLE_EQ(f.grid_tau, tau);
  EXPECT_LT(f.grid_misfit, kRoundOffAbs);
  EXPECT_LE(f.misfit, f.grid_misfit);  // LM never accepts an increase
}

TEST(Calibration, LevenbergMarquardtSolvesRosenbrock) {
  // r = (10 (y - x^2), 1 - x): minimum 0 at (1, 1), a curved valley.
  auto r = [](const Eigen::VectorXd& x) {
    Eigen::VectorXd v(2);
    v << 10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0];
    return v;
  };
  Eigen::VectorXd x0(2);
  x0 << -1.2, 1.0;
  const LmResult res = levenberg_marquardt(r, x0);
  EXPECT_TRUE(res.converged) << res.reason;
  EXPECT_NEAR(res.x[0], 1.0, 1e-6);  // the zero residual is reached to LM's tolerance
  EXPECT_NEAR(res.x[1], 1.0, 1e-6);
  EXPECT_LT(res.cost, kLmZeroCost);
  EXPECT_LT(res.iterations, 100);
}

TEST(Calibration, EmpiricalTauAndAlphaRecoveredFromTheEmpiricalPulse) {
  ImpactInputs in = inputs(true);
  const double alpha = 1.2, tau = 0.14;
  const lsi::ForcePulse p = empirical_pulse(in, alpha, tau);
  CalibrationCase c;
  c.name = "empirical";
  c.inputs = in;
  for (int i = 0; i < 300; ++i) {
    const double t = 1.5 * p.duration * i / 299;
    c.time.push_back(t);
    c.force.push_back(p.force(t));
  }
  c.peak_force = p.peak;
  c.rise_time = p.rise_time;
  c.impact_duration = p.duration;
  for (Objective o : {Objective::NormalisedRms, Objective::PeakDuration}) {
    CalibrationOptions opt;
    opt.objective = o;
    const EmpiricalFit f = fit_empirical(c, opt);
    // alpha_MPM is eqs. 3-4 solved for alpha: exact to rounding.
    EXPECT_NEAR(f.alpha, alpha, kRoundOffAbs);
    EXPECT_NEAR(f.froude, 6.0 * std::sin(in.face_angle) / std::sqrt(9.81 * 2.0), kRoundOffAbs);
    EXPECT_NEAR(f.tau, tau, 1e-6) << objective_name(o);
    EXPECT_LT(f.misfit, 1e-7);
    EXPECT_TRUE(f.converged);
  }
}

TEST(Calibration, StudentTQuantilesMatchTables) {
  // Two-sided 95 % critical values from standard tables (6 significant digits).
  EXPECT_NEAR(stats::student_t_quantile(0.975, 1), 12.7062, 1e-4);
  EXPECT_NEAR(stats::student_t_quantile(0.975, 2), 4.30265, 1e-5);
  EXPECT_NEAR(stats::student_t_quantile(0.975, 4), 2.77645, 1e-5);
  EXPECT_NEAR(stats::student_t_quantile(0.975, 8), 2.30600, 1e-5);
  EXPECT_NEAR(stats::student_t_quantile(0.975, 30), 2.04227, 1e-5);
  EXPECT_NEAR(stats::student_t_quantile(0.975, 1e7), 1.95996, 1e-5);  // the normal limit
  EXPECT_NEAR(stats::student_t_quantile(0.025, 8), -2.30600, 1e-5);   // symmetry
  EXPECT_NEAR(stats::student_t_cdf(0.0, 3), 0.5, kFewOpsAbs);
}

TEST(Calibration, PooledMeanHasTheStudentTInterval) {
  // 1..5: mean 3, s = sqrt(2.5), half-width t_{0.975,4} s / sqrt(5) = 2.776445 * 0.707107.
  const GroupStatistic g = pooled_mean({1, 2, 3, 4, 5});
  EXPECT_EQ(g.n, 5);
  EXPECT_DOUBLE_EQ(g.mean, 3.0);
  EXPECT_NEAR(g.stddev, std::sqrt(2.5), kUnitArithmeticAbs);
  EXPECT_NEAR(g.ci.low, 3.0 - 2.776445 * std::sqrt(0.5), 1e-5);  // 6-digit table value
  EXPECT_NEAR(g.ci.high, 3.0 + 2.776445 * std::sqrt(0.5), 1e-5);
  // Values near the edge of their domain: tau in (0, 1). 0.02, 0.03, 0.5: mean 0.18333,
  // s = 0.27429, half-width t_{0.975,2} s / sqrt(3) = 4.302653 * 0.15836 = 0.68137: the whole
  // interval reaches -0.498, cut at 0; the high end stays.
  const GroupStatistic edge = pooled_mean({0.02, 0.03, 0.5}, 0.95, {0.0, 1.0});
  const double s =
      std::sqrt(((0.02 - 0.55 / 3) * (0.02 - 0.55 / 3) + (0.03 - 0.55 / 3) * (0.03 - 0.55 / 3) +
                 (0.5 - 0.55 / 3) * (0.5 - 0.55 / 3)) /
                2.0);
  EXPECT_EQ(edge.ci.low, 0.0);
  EXPECT_NEAR(edge.ci.high, 0.55 / 3 + 4.302653 * s / std::sqrt(3.0), 1e-5);  // table value
  // The default domain cuts nothing.
  EXPECT_NEAR(pooled_mean({0.02, 0.03, 0.5}).ci.low, 0.55 / 3 - 4.302653 * s / std::sqrt(3.0),
              1e-5);
  // One value: a mean but no interval.
  const GroupStatistic one = pooled_mean({0.4});
  EXPECT_EQ(one.n, 1);
  EXPECT_DOUBLE_EQ(one.mean, 0.4);
  EXPECT_TRUE(std::isnan(one.ci.low));
}

TEST(Calibration, PowerLawA1A2RecoveredFromSyntheticAlpha) {
  std::vector<double> fr, al;
  for (int i = 0; i < 9; ++i) {
    fr.push_back(0.8 + 0.4 * i);
    al.push_back(1.781 * std::pow(fr.back(), -0.515));
  }
  const PowerLawFit exact = fit_power_law(fr, al);
  // Exact power law: least squares in log-log space is exact up to rounding.
  EXPECT_NEAR(exact.a1, 1.781, kRoundOffAbs);
  EXPECT_NEAR(exact.a2, -0.515, kRoundOffAbs);
  EXPECT_LT(exact.rms_log_residual, kRoundOffAbs);
  // Multiplicative noise of +-5 % (log residuals up to 0.05): the 95 % intervals contain the
  // truth, and a2 is within a few of its standard errors (the CI half-width is t_7 ~ 2.36 of them).
  std::vector<double> noisy = al;
  const double wiggle[9] = {0.05, -0.03, 0.01, -0.05, 0.04, -0.02, 0.03, -0.04, 0.0};
  for (int i = 0; i < 9; ++i) noisy[i] *= std::exp(wiggle[i]);
  const PowerLawFit f = fit_power_law(fr, noisy);
  EXPECT_EQ(f.n, 9);
  EXPECT_LE(f.a2_ci.low, -0.515);
  EXPECT_GE(f.a2_ci.high, -0.515);
  EXPECT_LE(f.a1_ci.low, 1.781);
  EXPECT_GE(f.a1_ci.high, 1.781);
  EXPECT_NEAR(f.a2, -0.515, 0.1);  // log-noise 0.05 over a log(Fr) span of 1.6: a2 to ~0.03
}

TEST(Calibration, GroupSummaryPoolsTheFits) {
  std::vector<TwoBodyFit> tb(3);
  std::vector<EmpiricalFit> em(3);
  const double lam[3] = {0.4, 0.45, 0.5}, tau[3] = {0.2, 0.25, 0.3};
  for (int i = 0; i < 3; ++i) {
    tb[i].lambda = lam[i];
    tb[i].tau = tau[i];
    em[i].tau = 0.1 + 0.02 * i;
    em[i].froude = 1.0 + i;
    em[i].alpha = 2.0 * std::pow(1.0 + i, -0.5);
  }
  const GroupSummary g = summarize_group(false, {"a", "b", "c"}, tb, em);
  EXPECT_EQ(g.lambda.n, 3);
  EXPECT_NEAR(g.lambda.mean, 0.45, kFewOpsAbs);
  // s = 0.05, t_{0.975,2} = 4.302653: half-width 4.302653 * 0.05 / sqrt(3).
  EXPECT_NEAR(g.lambda.ci.high - g.lambda.mean, 4.302653 * 0.05 / std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(g.tau.mean, 0.25, kFewOpsAbs);
  EXPECT_NEAR(g.empirical_tau.mean, 0.12, kFewOpsAbs);
  EXPECT_NEAR(g.power_law.a1, 2.0, kRoundOffAbs);
  EXPECT_NEAR(g.power_law.a2, -0.5, kRoundOffAbs);
  EXPECT_DOUBLE_EQ(g.paper.lambda, 0.41);  // free barriers
  EXPECT_DOUBLE_EQ(g.paper.tau, 0.25);
  EXPECT_DOUBLE_EQ(paper_values(true).lambda, 0.72);
  EXPECT_DOUBLE_EQ(paper_values(true).tau, 0.17);
}

TEST(Calibration, InvalidOptionsAndCasesAreRejected) {
  const CalibrationCase c = synthetic(inputs(false), 0.5, 0.2, 50);
  CalibrationOptions o;
  o.lambda_cells = 1;
  EXPECT_THROW(fit_two_body(c, o), std::invalid_argument);
  o = {};
  o.tau_cells = 0;
  EXPECT_THROW(fit_two_body(c, o), std::invalid_argument);
  CalibrationCase bad = c;
  bad.force.pop_back();
  EXPECT_THROW(fit_two_body(bad, {}), std::invalid_argument);
  bad = c;
  bad.inputs.velocity = 0.0;
  EXPECT_THROW(fit_two_body(bad, {}), std::invalid_argument);
  bad = c;
  bad.time[3] = bad.time[2];
  EXPECT_THROW(fit_two_body(bad, {}), std::invalid_argument);
}

TEST(Calibration, ImpactSummaryUsesTheMpmRunnersDefinitions) {
  // A triangle 0 -> 10 at t = 1 -> 0 at t = 3, then 0 to t = 6 (601 samples): peak 10 at 1; the
  // force is last more than 1 (10 % of the peak) from its final value 0 at t just below 2.8.
  std::vector<double> t, f;
  for (int i = 0; i <= 600; ++i) {
    t.push_back(0.01 * i);
    const double x = t.back();
    f.push_back(x <= 1 ? 10 * x : (x < 3 ? 10 - 5 * (x - 1) : 0.0));
  }
  const ImpactSummary s = impact_summary(t, f);
  EXPECT_DOUBLE_EQ(s.peak_force, 10.0);
  EXPECT_DOUBLE_EQ(s.rise_time, 1.0);
  EXPECT_NEAR(s.impact_duration, 2.79, 1e-9);  // the last sample with F > 1
}

}  // namespace
