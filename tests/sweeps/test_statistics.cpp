// Output statistics of `lsi sweep` (sweeps/statistics.hpp): exact small cases, the coverage of the
// confidence intervals by simulation, infinite outputs, and the error messages.
//
// Coverage tolerances: with R = 2000 replicates, the simulated coverage of an interval whose true
// coverage is c has standard deviation sqrt(c (1 - c) / R) = 0.0049 at c = 0.95; we allow 4 of them
// (0.0195), a band a correct interval leaves with probability 6e-5. The replicates draw their data
// from the sweeps' own Philox generator with fixed seeds, so the tests are deterministic.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support/expect_invalid.hpp"
#include "support/tolerances.hpp"
#include "sweeps/counter_rng.hpp"
#include "sweeps/normal_distribution.hpp"
#include "sweeps/statistics.hpp"

namespace {
using namespace lsi::sweeps;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kReplicates = 2000;
using lsi::test::kFewOpsAbs;
using lsi::test::kUnitArithmeticAbs;

// The binomial cdf against mpmath: the incomplete beta's prefactor carries the absolute rounding
// of its lgamma terms (~1e-14 at n = 100; measured 8e-14 relative).
constexpr double kIncompleteBetaRel = 2e-13;
// A coverage from the binomial cdf (the same rounding, on a value near 1), absolute.
constexpr double kBinomialCdfAbs = 1e-13;
// The t quantile against mpmath: bisected to 1e-15 relative on that cdf, relative (absolute for
// the values of a few units compared without a scale).
constexpr double kTQuantileRel = 1e-12;
// A mean's interval on values of a few units: a few ulp of the arithmetic and the t quantile's
// 1e-15, absolute.
constexpr double kMeanCiAbs = 1e-13;
// 3 / 10: one correctly rounded division.
constexpr double kOneDivisionAbs = 1e-16;
const double kCoverageTolerance = 4 * std::sqrt(0.95 * 0.05 / kReplicates);

using lsi::test::expect_invalid;

// n standard normal values of replicate r (Philox + Phi^-1: the same numbers on every platform).
std::vector<double> normal_data(int n, std::uint64_t r, double mean = 0, double sd = 1) {
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[i] = mean + sd * normal_quantile(uniform_open01(r, i, 0));
  return x;
}

// ---------------------------------------------------------------------------------------------
// Special functions behind the intervals

TEST(StatisticsFunctions, BinomialAndStudentAgainstReferences) {
  // References from mpmath (30 digits). The incomplete beta's prefactor exp(a ln x + b ln(1-x) -
  // ln B(a,b)) carries the absolute rounding of the lgamma terms (~1e-14 at n = 100), so we allow
  // 2e-13 relative (measured 8e-14 at n = 100); the t quantile is bisected to 1e-15 relative.
  EXPECT_NEAR(stats::binomial_cdf(3, 20, 0.3), 0.107086804503730998,
              kIncompleteBetaRel * 0.107086804503730998);
  EXPECT_NEAR(stats::binomial_cdf(40, 100, 0.5), 0.0284439668204903958,
              kIncompleteBetaRel * 0.0284439668204903958);
  EXPECT_EQ(stats::binomial_cdf(-1, 10, 0.5), 0.0);
  EXPECT_EQ(stats::binomial_cdf(10, 10, 0.5), 1.0);
  const double nu[] = {1, 2, 4, 5, 9, 30, 1000};
  const double t975[] = {12.7062047361747046, 4.30265272974946385, 2.77644510519779436,
                         2.57058183563631551, 2.26215716279820554, 2.04227245630123831,
                         1.96233908082640848};
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(stats::student_t_quantile(0.975, nu[i]), t975[i], kTQuantileRel * t975[i])
        << "nu " << nu[i];
  EXPECT_NEAR(stats::student_t_quantile(0.025, 4), -2.77644510519779436, kTQuantileRel);
  EXPECT_NEAR(stats::student_t_quantile(0.975, 1e8), 1.959963984540054,
              kTQuantileRel);  // -> normal
}

TEST(StatisticsFunctions, OrderStatisticRanks) {
  // Exact: the classical 95 % interval for the median of n = 20 is [x_(6), x_(15)], coverage
  // P(6 <= B <= 14) = 1 - 2 * 0.020695 = 0.958610 (B ~ Bin(20, 1/2)).
  const auto med = order_statistic_ranks(20, 0.5, 0.95);
  EXPECT_EQ(med.lower, 6);
  EXPECT_EQ(med.upper, 15);
  EXPECT_NEAR(med.coverage, 1 - 2 * 0.020694732666015625, kBinomialCdfAbs);
  // q95 of n = 20: P(B <= 16) = 0.0159 <= 0.025 < P(B <= 17) = 0.0755, so the lower rank is 17; no
  // upper rank reaches 0.975 (P(B <= 19) = 1 - 0.95^20 = 0.64), hence +inf (rank n + 1).
  const auto q95 = order_statistic_ranks(20, 0.95, 0.95);
  EXPECT_EQ(q95.lower, 17);
  EXPECT_EQ(q95.upper, 21);
  // n = 5: too few samples for any finite bound on the median.
  const auto tiny = order_statistic_ranks(5, 0.5, 0.95);
  EXPECT_EQ(tiny.lower, 0);
  EXPECT_EQ(tiny.upper, 6);
  EXPECT_EQ(tiny.coverage, 1.0);
  // Large n: the exact ranks at n = 10^6 and the normal approximation at n = 10^6 + 2 agree to one
  // rank after shifting by one (the median moves by one), and both cover 0.95 to within 1e-3
  // (discreteness of B; its sd is 500 here).
  const auto exact = order_statistic_ranks(1000000, 0.5, 0.95);
  const auto approx = order_statistic_ranks(1000002, 0.5, 0.95);
  EXPECT_LE(std::llabs(exact.lower + 1 - approx.lower), 1);
  EXPECT_LE(std::llabs(exact.upper + 1 - approx.upper), 1);
  EXPECT_NEAR(exact.coverage, 0.95, 1e-3);
  EXPECT_NEAR(approx.coverage, 0.95, 1e-3);
}

// ---------------------------------------------------------------------------------------------
// The order statistics of describe(): the sorted column's values at the ranks, bit for bit

// The values sorted in the order of their keys (as std::sort, with -0 before +0).
std::vector<double> key_sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end(), [](double a, double b) {
    return lsi::sweeps::detail::order_key(a) < lsi::sweeps::detail::order_key(b);
  });
  return v;
}

TEST(OrderStatistics, GiveTheSortedColumnsValuesWithTheBuffersKeptFromColumnToColumn) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Wide-ranging values of both signs with zeros, infinities and subnormals (the ranks in many
  // buckets); values in [1, 2) (a sixteenth of them per bucket); a few repeated integers (ties);
  // one value (one bucket holds the column); values within 1e-12 of each other (one bucket, the
  // selection among all).
  auto wide = [&](std::size_t n) {
    std::vector<double> v(n);
    for (auto& x : v) x = (u(g) - 0.5) * std::exp(60.0 * (u(g) - 0.5));
    v[1] = 0.0;
    v[2] = -0.0;
    v[3] = kInf;
    v[4] = 5e-324;
    v[5] = -kInf;
    v[6] = 1e308;
    return v;
  };
  auto one_two = [&](std::size_t n) {
    std::vector<double> v(n);
    for (auto& x : v) x = 1.0 + u(g);
    return v;
  };
  auto few = [&](std::size_t n) {
    std::vector<double> v(n);
    for (auto& x : v) x = std::floor(8.0 * u(g));
    return v;
  };
  auto constant = [&](std::size_t n) { return std::vector<double>(n, 2.5); };
  auto narrow = [&](std::size_t n) {
    std::vector<double> v(n);
    for (auto& x : v) x = 3.0 + 1e-12 * u(g);
    return v;
  };
  // Point masses: most values +0 (the final displacement of barriers that never slide), some -0,
  // a fifth 1 and a tenth the double after it (a large bucket of two values), the rest spread.
  auto point_masses = [&](std::size_t n) {
    std::vector<double> v(n);
    for (auto& x : v) {
      const double p = u(g);
      x = p < 0.55  ? 0.0
          : p < 0.6 ? -0.0
          : p < 0.8 ? 1.0
          : p < 0.9 ? std::nextafter(1.0, 2.0)
                    : std::exp(10.0 * u(g));
    }
    return v;
  };
  OrderScratch scratch;  // kept, as sweep_statistics keeps it
  using Make = std::function<std::vector<double>(std::size_t)>;
  for (const std::size_t n :
       {std::size_t{70000}, std::size_t{4096}, std::size_t{5000}, std::size_t{131073}})
    for (const Make& make :
         {Make(wide), Make(one_two), Make(few), Make(constant), Make(narrow), Make(point_masses)})
      for (const std::size_t rank_count : {std::size_t{14}, std::size_t{200}, std::size_t{300}}) {
        const std::vector<double> v = make(n);
        const std::vector<double> expected = key_sorted(v);
        // The extremes, neighbours and repeats, and random ranks (300: more than the 255 of the
        // selection by buckets, so the selection among all values).
        std::vector<std::size_t> ranks = {0, n - 1, n / 2, n / 2, n / 2 + 1, 1};
        while (ranks.size() < rank_count) ranks.push_back(g() % n);
        std::sort(ranks.begin(), ranks.end());
        std::vector<double> got(ranks.size());
        order_statistics(v.data(), n, ranks.data(), ranks.size(), got.data(), scratch);
        for (std::size_t j = 0; j < ranks.size(); ++j)
          ASSERT_EQ(std::memcmp(&got[j], &expected[ranks[j]], sizeof(double)), 0)
              << "n = " << n << ", rank " << ranks[j] << ": " << got[j] << " against "
              << expected[ranks[j]];
      }
}

// ---------------------------------------------------------------------------------------------
// describe(): exact small cases

TEST(Describe, ExactSmallCase) {
  // {5, 1, 4, 2, 3}: mean 3, sd sqrt(2.5), CI 3 -+ t_{0.975,4} sd / sqrt(5) with t = 2.7764451051977944
  // (mpmath: [1.0367568385224423, 4.9632431614775577]); type 7 quantiles 1.2, 3, 4.8 (h = 0.2, 2, 3.8).
  // Tolerances: a few ulp of the arithmetic, and the t quantile's 1e-15.
  const OutputStatistics s = describe({5, 1, 4, 2, 3});
  EXPECT_EQ(s.count, 5u);
  EXPECT_EQ(s.infinite_count, 0u);
  EXPECT_EQ(s.mean, 3.0);
  EXPECT_NEAR(s.standard_deviation, std::sqrt(2.5), kFewOpsAbs);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 5.0);
  EXPECT_NEAR(s.mean_ci.low, 1.0367568385224423, kMeanCiAbs);
  EXPECT_NEAR(s.mean_ci.high, 4.9632431614775577, kMeanCiAbs);
  EXPECT_NEAR(s.q05, 1.2, kFewOpsAbs);
  EXPECT_EQ(s.q50, 3.0);
  EXPECT_NEAR(s.q95, 4.8, kFewOpsAbs);
  // n = 5 is too small for a finite 95 % bound on any of the three quantiles, except the q05's upper
  // bound x_(2) (P(B <= 1) = 0.977 for B ~ Bin(5, 0.05)) and the q95's lower bound x_(4).
  EXPECT_EQ(s.q50_ci.low, -kInf);
  EXPECT_EQ(s.q50_ci.high, kInf);
  EXPECT_EQ(s.q05_ci.low, -kInf);
  EXPECT_EQ(s.q05_ci.high, 2.0);
  EXPECT_EQ(s.q95_ci.low, 4.0);
  EXPECT_EQ(s.q95_ci.high, kInf);
}

TEST(Describe, MeansOfManyValuesAreCompensated) {
  // A million copies of 0.1 sum to 100000 once rounded (the double 0.1 exceeds 1/10 by 5.6e-18,
  // a million of those 5.6e-12, below half an ulp of 1e5): the mean is 0.1 exactly. Half 0.1 and
  // half 0.3 give 0.2 the same way, and the standard deviation 0.1 sqrt(n / (n - 1)) to 1e-15
  // (its sums compensated too). A plain running sum of the million is off by about 1e-11
  // relative.
  const std::size_t n = 1000000;
  EXPECT_EQ(describe(std::vector<double>(n, 0.1)).mean, 0.1);
  std::vector<double> two(n);
  for (std::size_t i = 0; i < n; ++i) two[i] = i < n / 2 ? 0.1 : 0.3;
  const OutputStatistics s = describe(two);
  EXPECT_EQ(s.mean, 0.2);
  EXPECT_NEAR(s.standard_deviation, 0.1 * std::sqrt(double(n) / double(n - 1)), 1e-15);
}

TEST(Describe, MedianIntervalOfTwentyValues) {
  // 1..20 in a shuffled order: the median CI is [x_(6), x_(15)] = [6, 15] (exact binomial ranks).
  std::vector<double> v;
  for (int i = 0; i < 20; ++i) v.push_back((i * 7) % 20 + 1);
  const OutputStatistics s = describe(v);
  EXPECT_EQ(s.q50, 10.5);
  EXPECT_EQ(s.q50_ci.low, 6.0);
  EXPECT_EQ(s.q50_ci.high, 15.0);
  EXPECT_EQ(s.q95_ci.low, 17.0);
  EXPECT_EQ(s.q95_ci.high, kInf);
}

TEST(Describe, InfiniteValues) {
  // +inf ("the barrier never stops") is a valid output: it counts, makes the mean and sd +inf, sits
  // on top of the order statistics; type 7 quantiles interpolating towards it are +inf.
  const OutputStatistics s = describe({1, kInf, 2});
  EXPECT_EQ(s.count, 3u);
  EXPECT_EQ(s.infinite_count, 1u);
  EXPECT_EQ(s.mean, kInf);
  EXPECT_EQ(s.standard_deviation, kInf);
  EXPECT_EQ(s.mean_ci.low, kInf);
  EXPECT_EQ(s.mean_ci.high, kInf);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, kInf);
  EXPECT_NEAR(s.q05, 1.1, kFewOpsAbs);
  EXPECT_EQ(s.q50, 2.0);
  EXPECT_EQ(s.q95, kInf);
  // Finite values whose sum overflows: an infinite mean (not the NaN of a compensation).
  EXPECT_EQ(describe(std::vector<double>(9, 1e308)).mean, kInf);
  const OutputStatistics all_inf = describe({kInf, kInf});
  EXPECT_EQ(all_inf.q50, kInf);
  EXPECT_EQ(all_inf.min, kInf);
  // One value: no spread to estimate.
  const OutputStatistics one = describe({4.5});
  EXPECT_EQ(one.mean, 4.5);
  EXPECT_TRUE(std::isnan(one.standard_deviation));
  EXPECT_EQ(one.mean_ci.low, -kInf);
  EXPECT_EQ(one.mean_ci.high, kInf);
  EXPECT_EQ(one.q05, 4.5);
}

TEST(Describe, ErrorMessages) {
  expect_invalid([] { describe({}); }, "no values");
  expect_invalid([] { describe({1, 2, std::nan("")}); }, "values[2] = nan");
  expect_invalid([] { describe({-kInf, 2}); }, "values[0] = -inf");
  expect_invalid([] { describe({1, 2}, 1.5); }, "confidence = 1.5: must be in (0, 1)");
  expect_invalid([] { exceedance({}, 1); }, "no values");
  expect_invalid([] { exceedance({1, std::nan("")}, 1); }, "values[1] = nan");
  expect_invalid([] { exceedance({1, 2}, std::nan("")); }, "threshold = nan");
  expect_invalid([] { exceedance({1, 2}, 1, 0); }, "confidence = 0");
}

// ---------------------------------------------------------------------------------------------
// exceedance(): exact cases

TEST(Exceedance, WilsonExactCases) {
  // 3 of 10 above 7: Wilson 95 % = [0.107791267406301034, 0.603221852538854648] (mpmath);
  // 0 of 10: [0, z^2 / (n + z^2)] = [0, 0.277532799862889205]; 10 of 10: [1 - 0.2775..., 1].
  // Tolerance 1e-14: double arithmetic on O(1) numbers.
  std::vector<double> v;
  for (int i = 1; i <= 10; ++i) v.push_back(i);
  const ExceedanceEstimate e = exceedance(v, 7);
  EXPECT_EQ(e.exceed_count, 3u);
  EXPECT_EQ(e.count, 10u);
  EXPECT_EQ(e.threshold, 7.0);
  EXPECT_NEAR(e.probability, 0.3, kOneDivisionAbs);
  EXPECT_NEAR(e.ci.low, 0.107791267406301034, kUnitArithmeticAbs);
  EXPECT_NEAR(e.ci.high, 0.603221852538854648, kUnitArithmeticAbs);
  const ExceedanceEstimate none = exceedance(v, 10);  // strictly greater: 10 does not exceed 10
  EXPECT_EQ(none.exceed_count, 0u);
  EXPECT_EQ(none.ci.low, 0.0);
  EXPECT_NEAR(none.ci.high, 0.277532799862889205, kUnitArithmeticAbs);
  const ExceedanceEstimate all = exceedance(v, 0);
  EXPECT_EQ(all.ci.high, 1.0);
  EXPECT_NEAR(all.ci.low, 1 - 0.277532799862889205, kUnitArithmeticAbs);
  // +inf exceeds every threshold.
  EXPECT_EQ(exceedance({1, kInf, kInf}, 1e300).exceed_count, 2u);
}

// ---------------------------------------------------------------------------------------------
// Coverage by simulation

TEST(Coverage, MeanIntervalStudentT) {
  // Normal data, n = 10: the t interval is exact, coverage 0.95 within the binomial tolerance.
  // Uniform data, n = 30: nearly exact (symmetric, light tails).
  for (int n : {10, 30}) {
    int covered = 0;
    for (int r = 0; r < kReplicates; ++r) {
      std::vector<double> x = normal_data(n, 1000 + r, 5, 2);
      double truth = 5;
      if (n == 30) {
        for (int i = 0; i < n; ++i) x[i] = uniform_open01(5000 + r, i, 1);
        truth = 0.5;
      }
      const OutputStatistics s = describe(x);
      covered += s.mean_ci.low <= truth && truth <= s.mean_ci.high;
    }
    EXPECT_NEAR(double(covered) / kReplicates, 0.95, kCoverageTolerance) << "n " << n;
  }
}

TEST(Coverage, QuantileIntervalsOrderStatistics) {
  // Standard normal data; the true quantiles are Phi^-1(q). The order-statistic intervals are
  // conservative by the discreteness of B: the simulated coverage must match the exact coverage
  // of the ranks (order_statistic_ranks) within the binomial tolerance (4 sd at that coverage),
  // and that exact coverage is >= 0.95 by construction.
  for (int n : {60, 400}) {
    const double q[3] = {0.05, 0.5, 0.95};
    int covered[3] = {0, 0, 0};
    for (int r = 0; r < kReplicates; ++r) {
      const OutputStatistics s = describe(normal_data(n, 70000 + r));
      const Interval ci[3] = {s.q05_ci, s.q50_ci, s.q95_ci};
      for (int k = 0; k < 3; ++k) {
        const double truth = normal_quantile(q[k]);
        covered[k] += ci[k].low <= truth && truth <= ci[k].high;
      }
    }
    for (int k = 0; k < 3; ++k) {
      const double c = order_statistic_ranks(n, q[k], 0.95).coverage;
      EXPECT_GE(c, 0.95);
      EXPECT_NEAR(double(covered[k]) / kReplicates, c, 4 * std::sqrt(c * (1 - c) / kReplicates))
          << "n " << n << " q " << q[k] << " exact coverage " << c;
    }
  }
}

TEST(Coverage, ExceedanceWilson) {
  // Bernoulli(p) data through exceedance(): the simulated coverage matches the exact coverage of
  // the Wilson interval (sum of the binomial probabilities of the k whose interval holds p, here
  // from mpmath: 0.95666 for n = 50, p = 0.3; 0.933077 for n = 200, p = 0.02) within 4 sd.
  struct Case {
    int n;
    double p, exact;
  };
  for (const Case& c : {Case{50, 0.3, 0.95666}, Case{200, 0.02, 0.933077}}) {
    int covered = 0;
    for (int r = 0; r < kReplicates; ++r) {
      std::vector<double> x(c.n);
      for (int i = 0; i < c.n; ++i) x[i] = uniform_open01(900000 + r, i, 2) < c.p ? 1.0 : 0.0;
      const ExceedanceEstimate e = exceedance(x, 0.5);
      covered += e.ci.low <= c.p && c.p <= e.ci.high;
    }
    EXPECT_NEAR(double(covered) / kReplicates, c.exact,
                4 * std::sqrt(c.exact * (1 - c.exact) / kReplicates))
        << "n " << c.n << " p " << c.p;
  }
}

}  // namespace
