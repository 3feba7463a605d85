// x^y without a library call (kernels/common/pow_nonnegative.hpp), both ways (tables on the host,
// series on a GPU, both compiled here), against long double libm over the range the empirical
// model uses it in (alpha = a1 Fr^a2) and over the whole double range, its special values against
// pow, the tables' way for eight lanes against its scalar instance bit for bit, and its tables
// (kernels/common/pow_tables.hpp) against long double libm.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

#include "kernels/common/pow_nonnegative.hpp"

namespace {

using lsi::math::pow_detail::pow_by_series;

double pow_by_tables(double x, double y) { return lsi::math::pow_detail::pow_by_tables(x, y); }

// The two ways as one test parameter.
struct Way {
  const char* name;
  double (*pow)(double, double);
};
const Way kWays[] = {{"tables", pow_by_tables}, {"series", pow_by_series}};

class PowNonnegative : public ::testing::TestWithParam<Way> {};

// Distance from `value` to `exact` in units in the last place of `exact` (long double libm: its
// 64-bit significand makes its own error ~1/2000 of a double ulp, negligible here).
double ulps(double value, long double exact) {
  const double e = static_cast<double>(exact);
  const long double ulp = std::nextafter(std::fabs(e), INFINITY) - std::fabs(e);
  // In long double: near the smallest normal the distance can be below the smallest subnormal.
  return static_cast<double>(std::fabs(static_cast<long double>(value) - exact) / ulp);
}

// The largest error over n draws of x = 10^U(lo, hi), y = U(y_lo, y_hi), keeping the results
// that are normal doubles.
double worst_ulps(double (*pow_nonnegative)(double, double), double log10_lo, double log10_hi,
                  double y_lo, double y_hi, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(log10_lo, log10_hi), uy(y_lo, y_hi);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = std::pow(10.0, ux(rng)), y = uy(rng);
    const long double exact = std::pow(static_cast<long double>(x), static_cast<long double>(y));
    if (!(std::fabs(exact) >= std::numeric_limits<double>::min() &&
          std::fabs(exact) <= std::numeric_limits<double>::max()))
      continue;
    worst = std::fmax(worst, ulps(pow_nonnegative(x, y), exact));
  }
  return worst;
}

TEST_P(PowNonnegative, WithinOneUlpOverTheEmpiricalModelsRange) {
  // Fr from 1e-3 to 1e3 (a flow 1e6 times faster or slower than its wave speed covers every
  // scene), a2 in [-5, 5] (the range the scene parser allows). 1 ulp: log and exp carry their
  // arguments in two doubles, so only the final rounding (1/2 ulp) and the polynomials' round-off
  // remain.
  const double worst = worst_ulps(GetParam().pow, -3, 3, -5, 5, 1 << 20, 1);
  std::printf("[ pow_nonnegative, %s ] worst error, Fr in [1e-3, 1e3], a2 in [-5, 5]: %.3f ulp\n",
              GetParam().name, worst);
  EXPECT_LE(worst, 1.0);
}

TEST_P(PowNonnegative, WithinOneUlpOverTheDoubleRange) {
  // x over every normal exponent (and subnormals), y such that x^y stays finite and normal: the
  // exponent y log x reaches 709; carried in two doubles, its error stays far below an ulp of the
  // result, so 1 ulp holds here too.
  const auto pow_nonnegative = GetParam().pow;
  double worst = worst_ulps(pow_nonnegative, -307, 308, -2, 2, 1 << 19, 2);
  worst =
      std::fmax(worst, worst_ulps(pow_nonnegative, -320, -308, -1, 1, 1 << 16, 3));     // subnormal
  worst = std::fmax(worst, worst_ulps(pow_nonnegative, -1, 1, -300, 300, 1 << 18, 4));  // large |y|
  // x within 2^-20 of 1, where log x is small and y large: the exponent's relative accuracy.
  worst = std::fmax(worst, worst_ulps(pow_nonnegative, -2.6e-7, 2.6e-7, -1e8, 1e8, 1 << 16, 5));
  // x in the tables' sub-interval around 1 (|x - 1| < 2^-5), y up to 2^14.3: the exponent up
  // to 709 from a log near its largest relative round-off.
  worst = std::fmax(worst, worst_ulps(pow_nonnegative, -0.0136, 0.0136, -2e4, 2e4, 1 << 18, 6));
  std::printf("[ pow_nonnegative, %s ] worst error over the double range: %.3f ulp\n",
              GetParam().name, worst);
  EXPECT_LE(worst, 1.0);
}

TEST_P(PowNonnegative, SpecialValuesAsPow) {
  const auto pow_nonnegative = GetParam().pow;
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double xs[] = {0.0, 1.0, 2.0, 0.5, 1e-310, inf, nan};
  const double ys[] = {0.0, -0.0, 1.0, -1.0, 0.5, -0.515, 1e6, -1e6, inf, -inf, nan};
  for (double x : xs)
    for (double y : ys) {
      const double expected = std::pow(x, y), got = pow_nonnegative(x, y);
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(got)) << x << "^" << y << " = " << got;
      } else if (std::isinf(expected) || expected == 0.0) {
        EXPECT_EQ(got, expected) << x << "^" << y;
      } else {
        EXPECT_LE(ulps(got, std::pow(static_cast<long double>(x), static_cast<long double>(y))),
                  1.0)
            << x << "^" << y << " = " << got << ", pow: " << expected;
      }
    }
  // Overflow and underflow, and results near them.
  EXPECT_EQ(pow_nonnegative(10.0, 400.0), inf);
  EXPECT_EQ(pow_nonnegative(10.0, -400.0), 0.0);
  EXPECT_LE(ulps(pow_nonnegative(2.0, 1023.5), std::pow(2.0L, 1023.5L)), 1.0);
  EXPECT_LE(ulps(pow_nonnegative(2.0, -1021.5), std::pow(2.0L, -1021.5L)), 1.0);
  // Exact powers of two come out exact.
  EXPECT_EQ(pow_nonnegative(2.0, 10.0), 1024.0);
  EXPECT_EQ(pow_nonnegative(4.0, 0.5), 2.0);
  // A negative base is outside the function's domain: NaN (pow gives (-2)^2 = 4).
  EXPECT_TRUE(std::isnan(pow_nonnegative(-2.0, 2.0)));
  EXPECT_TRUE(std::isnan(pow_nonnegative(-inf, 0.5)));
  EXPECT_EQ(pow_nonnegative(-2.0, 0.0), 1.0);
}

INSTANTIATE_TEST_SUITE_P(BothWays, PowNonnegative, ::testing::ValuesIn(kWays),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(PowTablesEightLanes, GiveTheScalarBitsInEveryLane) {
#if LSI_HOST_SIMD_LANES
  // The tables' way instantiated for eight lanes must give, in every lane, the bits of its scalar
  // instance (the batched empirical model relies on it). Lanes mix ordinary operands with
  // special ones (0, inf, NaN, negative, subnormal, results beyond the double range).
  namespace lanes = lsi::math::lanes;
  const double inf = std::numeric_limits<double>::infinity();
  const double special[] = {
      0.0,    1.0,   inf,          -2.0,        std::numeric_limits<double>::quiet_NaN(),
      1e-310, 1e300, 1.0 - 0x1p-6, 1.0 + 0x1p-5};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(-320, 308), uy(-4, 4), pick(0, 1);
  int compared = 0;
  for (int round = 0; round < (1 << 16); ++round) {
    double x[8], y[8], lane[8];
    for (int k = 0; k < 8; ++k) {
      x[k] = pick(rng) < 0.1 ? special[rng() % std::size(special)] : std::pow(10.0, ux(rng));
      y[k] = pick(rng) < 0.05 ? 0.0 : uy(rng) * std::pow(10.0, uy(rng) / 2);
    }
    lanes::store8(lane, lsi::math::pow_detail::pow_by_tables(lanes::load8(x), lanes::load8(y)));
    for (int k = 0; k < 8; ++k, ++compared) {
      const double scalar = pow_by_tables(x[k], y[k]);
      ASSERT_EQ(std::memcmp(&scalar, &lane[k], sizeof scalar), 0)
          << x[k] << "^" << y[k] << ": lane " << lane[k] << ", scalar " << scalar;
    }
  }
  // pow_nonnegative_each: eight at a time and the rest one at a time, as pow_nonnegative.
  std::vector<double> xs(37), out(37);
  for (double& v : xs) v = std::pow(10.0, ux(rng) / 100);
  lsi::math::pow_nonnegative_each(xs.data(), -0.515, out.data(), int(xs.size()));
  for (std::size_t k = 0; k < xs.size(); ++k)
    EXPECT_EQ(out[k], lsi::math::pow_nonnegative(xs[k], -0.515)) << k;
  EXPECT_EQ(compared, 8 << 16);
#else
  GTEST_SKIP() << "no eight-lane instance on this build (LSI_HOST_SIMD_LANES is 0)";
#endif
}

TEST(PowTables, EntriesAgreeWithLongDoubleLibm) {
  // Each log entry: 1/c and log c = -log(1/c) in two doubles; each exp entry: 2^(j/16) in two
  // doubles. Tolerance 2^-62 of the value: long double libm's own error (64-bit significand)
  // is ~2^-64; an entry off by more than that would show up as pow errors well above 1/2 ulp.
  using namespace lsi::math::pow_detail;
  for (int i = 0; i < (1 << log_table_bits); ++i) {
    const double inverse_centre = log_inverse_centre[i];
    const long double exact = -std::log(static_cast<long double>(inverse_centre));
    const long double stored =
        static_cast<long double>(log_centre_hi[i]) + static_cast<long double>(log_centre_lo[i]);
    EXPECT_LE(std::fabs(stored - exact), std::ldexp(std::fabs(exact), -62) + 0x1p-120L) << i;
    // The entry's sub-interval: z / c - 1 within the bound the series is truncated for.
    for (const double end : {0.0, 1.0}) {
      const std::uint64_t bits =
          log_table_offset + ((static_cast<std::uint64_t>(i) + static_cast<std::uint64_t>(end))
                              << (52 - log_table_bits));
      double z;
      std::memcpy(&z, &bits, sizeof z);
      EXPECT_LE(std::fabs(static_cast<long double>(z) * inverse_centre - 1.0L), 1.01L * 0x1p-5L)
          << i;
    }
  }
  for (int j = 0; j < (1 << exp_table_bits); ++j) {
    const long double exact = std::exp2(static_cast<long double>(j) / (1 << exp_table_bits));
    const long double stored = static_cast<long double>(exp_power_hi[j]) + exp_power_lo[j];
    EXPECT_LE(std::fabs(stored - exact), std::ldexp(exact, -62)) << j;
  }
}

}  // namespace
