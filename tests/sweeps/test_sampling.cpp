// The sampling library of `lsi sweep` (sweeps/counter_rng.hpp, normal_distribution.hpp,
// distribution.hpp, latin_hypercube.hpp, sobol.hpp, sampler.hpp): known answers where they exist
// (Philox, Phi^-1, the unscrambled Sobol points, the grid), exact structural properties where the
// design promises them (strata, nets), and statistical checks elsewhere.
//
// Statistical tolerances: every check of a sample statistic uses 5 standard errors (a two-sided
// 5-sigma band: a correct generator fails it with probability ~6e-7), or, for the KS and chi-square
// tests, the critical value at a significance of 1e-3. All seeds are fixed, so the tests are
// deterministic; the bands say how far from the truth a correct implementation can be.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "support/expect_invalid.hpp"
#include "sweeps/counter_rng.hpp"
#include "sweeps/distribution.hpp"
#include "sweeps/latin_hypercube.hpp"
#include "sweeps/normal_distribution.hpp"
#include "sweeps/sampler.hpp"
#include "sweeps/sobol.hpp"
#include "tests/support/backends.hpp"

namespace {
using namespace lsi::sweeps;
using HostSampler = Sampler<Kokkos::HostSpace>;
constexpr double kPi = 3.14159265358979323846;

using lsi::test::expect_invalid;

DistributionSpec uniform(double a, double b) {
  DistributionSpec s;
  s.kind = DistributionKind::Uniform;
  s.min = a;
  s.max = b;
  return s;
}
DistributionSpec normal(double mean, double sd) {
  DistributionSpec s;
  s.kind = DistributionKind::Normal;
  s.mean = mean;
  s.sd = sd;
  return s;
}
DistributionSpec lognormal(double mean, double sd) {
  DistributionSpec s = normal(mean, sd);
  s.kind = DistributionKind::Lognormal;
  return s;
}
DistributionSpec truncated(double mean, double sd, double a, double b) {
  DistributionSpec s = normal(mean, sd);
  s.kind = DistributionKind::TruncatedNormal;
  s.min = a;
  s.max = b;
  return s;
}
DistributionSpec discrete(std::vector<double> values, std::vector<double> weights) {
  DistributionSpec s;
  s.kind = DistributionKind::Discrete;
  s.values = std::move(values);
  s.weights = std::move(weights);
  return s;
}
DistributionSpec constant(double v) {
  DistributionSpec s;
  s.value = v;
  return s;
}
// The values 1 .. n.
std::vector<double> one_to(int n) {
  std::vector<double> v;
  for (int k = 1; k <= n; ++k) v.push_back(k);
  return v;
}

// All samples [0, n) of a sampler, drawn on the execution space of its memory (the host's
// threads for a HostSampler, also in a CUDA build), as a host matrix.
template <class Mem>
Kokkos::View<double**, Kokkos::LayoutLeft, Kokkos::HostSpace> draw(const Sampler<Mem>& s,
                                                                   std::uint64_t n,
                                                                   std::uint64_t first = 0) {
  Kokkos::View<double**, Kokkos::LayoutLeft, Mem> out("samples", n, s.dimensions());
  sample_batch(typename Mem::execution_space(), s, first, out);
  Kokkos::fence();
  auto host = Kokkos::create_mirror_view(out);
  Kokkos::deep_copy(host, out);
  return host;
}

struct Moments {
  double mean, sd;
};
Moments moments(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) m += v;
  m /= x.size();
  double ss = 0;
  for (double v : x) ss += (v - m) * (v - m);
  return {m, std::sqrt(ss / (x.size() - 1))};
}
double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const Moments a = moments(x), b = moments(y);
  double s = 0;
  for (std::size_t i = 0; i < x.size(); ++i) s += (x[i] - a.mean) * (y[i] - b.mean);
  return s / ((x.size() - 1) * a.sd * b.sd);
}
template <class V>
std::vector<double> column(const V& v, int d) {
  std::vector<double> c(v.extent(0));
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = v(i, d);
  return c;
}
// Kolmogorov-Smirnov statistic of x against U(0,1).
double ks_uniform(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const double n = x.size();
  double d = 0;
  for (std::size_t i = 0; i < x.size(); ++i) d = std::max({d, (i + 1) / n - x[i], x[i] - i / n});
  return d;
}

// ---------------------------------------------------------------------------------------------
// Philox-4x32 and the uniforms

TEST(CounterRng, PhiloxKnownAnswerVectors) {
  // Random123 tests/kat_vectors, "philox4x32 R" lines: counter (4 words), key (2 words) -> output.
  // Exact integer equality: any difference is a bug in the rounds or the key schedule.
  struct Kat {
    int rounds;
    std::uint32_t ctr[4], key[2], out[4];
  };
  const Kat kats[] = {
      {7, {0, 0, 0, 0}, {0, 0}, {0x5f6fb709, 0x0d893f64, 0x4f121f81, 0x4f730a48}},
      {7,
       {0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
       {0xffffffff, 0xffffffff},
       {0x5207ddc2, 0x45165e59, 0x4d8ee751, 0x8c52f662}},
      {7,
       {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
       {0xa4093822, 0x299f31d0},
       {0x4dfccaba, 0x190a87f0, 0xc47362ba, 0xb6b5242a}},
      {10, {0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
      {10,
       {0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
       {0xffffffff, 0xffffffff},
       {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
      {10,
       {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
       {0xa4093822, 0x299f31d0},
       {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
  };
  for (const Kat& k : kats) {
    const Philox4x32Block out =
        philox4x32({{k.ctr[0], k.ctr[1], k.ctr[2], k.ctr[3]}}, k.key[0], k.key[1], k.rounds);
    for (int w = 0; w < 4; ++w)
      EXPECT_EQ(out.v[w], k.out[w]) << "rounds " << k.rounds << " word " << w;
  }
}

TEST(CounterRng, UniformIsOpenAndPure) {
  // The extreme bit patterns map strictly inside (0,1): exact comparisons (the mapping is exact).
  EXPECT_EQ(bits_to_open01(0), std::ldexp(1.0, -54));
  EXPECT_EQ(bits_to_open01(~std::uint64_t{0}), 1.0 - std::ldexp(1.0, -53));
  EXPECT_LT(bits_to_open01(~std::uint64_t{0}), 1.0);
  EXPECT_EQ(bits_to_open01(std::uint64_t{1} << 11), std::ldexp(1.0, -53));  // 53-bit resolution
  double lo = 1, hi = 0;
  for (std::uint64_t i = 0; i < 2000000; ++i) {
    const double u = uniform_open01(12345, i, static_cast<std::uint32_t>(i % 3));
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  // A pure function: the same arguments give the same bits; any argument changed gives others.
  EXPECT_EQ(uniform_open01(7, 99, 4), uniform_open01(7, 99, 4));
  EXPECT_NE(uniform_open01(7, 99, 4), uniform_open01(8, 99, 4));
  EXPECT_NE(uniform_open01(7, 99, 4), uniform_open01(7, 100, 4));
  EXPECT_NE(uniform_open01(7, 99, 4), uniform_open01(7, 99, 5));
  EXPECT_NE(uniform_open01(7, std::uint64_t{1} << 32, 0),
            uniform_open01(7, 0, 0));  // high counter word used
  EXPECT_NE(uniform_open01(std::uint64_t{1} << 32, 0, 0),
            uniform_open01(0, 0, 0));  // high key word used
}

TEST(CounterRng, KolmogorovSmirnovUniformity) {
  // n = 1e5 per (seed, stream): the KS critical value at significance 1e-3 is 1.949 / sqrt(n).
  const int n = 100000;
  for (std::uint64_t seed : {0ull, 1ull, 0xDEADBEEFCAFEull})
    for (std::uint32_t stream : {0u, 1u, 31u}) {
      std::vector<double> x(n);
      for (int i = 0; i < n; ++i) x[i] = uniform_open01(seed, i, stream);
      EXPECT_LT(ks_uniform(x), 1.949 / std::sqrt(double(n)))
          << "seed " << seed << " stream " << stream;
    }
}

TEST(CounterRng, StreamsSeedsAndNeighboursAreUncorrelated) {
  // n = 1e6 pairs: the standard error of Pearson's r under independence is 1/sqrt(n) = 1e-3; 5 SE.
  const int n = 1000000;
  std::vector<double> a(n), b(n), c(n), lag(n);
  for (int i = 0; i < n; ++i) {
    a[i] = uniform_open01(42, i, 0);
    b[i] = uniform_open01(42, i, 1);        // the next stream of the same sample
    c[i] = uniform_open01(43, i, 0);        // the next seed
    lag[i] = uniform_open01(42, i + 1, 0);  // the next sample
  }
  const double tol = 5.0 / std::sqrt(double(n));
  EXPECT_LT(std::fabs(pearson(a, b)), tol);
  EXPECT_LT(std::fabs(pearson(a, c)), tol);
  EXPECT_LT(std::fabs(pearson(a, lag)), tol);
  const Moments m =
      moments(a);  // mean 1/2 (SE 0.2887/1000), sd 1/sqrt(12) (SE 0.2887*sqrt(0.8/4)/1000)
  EXPECT_NEAR(m.mean, 0.5, 5 * 0.28868 / 1000);
  EXPECT_NEAR(m.sd, 1 / std::sqrt(12.0), 5 * 0.28868 * std::sqrt(0.2) / 1000);
}

// ---------------------------------------------------------------------------------------------
// The standard normal

TEST(NormalDistribution, QuantileKnownValues) {
  // References computed with mpmath at 50 digits. AS 241 promises about 1e-16 relative; we allow
  // 4 ulp-scale relative error (1e-15), which the implementation meets.
  struct Case {
    double p, z;
  };
  const Case cases[] = {
      {0.975, 1.9599639845400542355},
      {0.3, -0.52440051270804078404},
      {0.02425, -1.9729610513118848503},
      {1e-10, -6.3613409024040562047},
      {1e-300, -37.047096299361199237},
      {std::ldexp(1.0, -53), -8.2095361516013868556},
      {1.0 - std::ldexp(1.0, -53),
       8.2095361516013868556},  // the largest double below 1 ("1 - 1e-16")
  };
  for (const Case& c : cases)
    EXPECT_NEAR(normal_quantile(c.p), c.z, 1e-15 * std::fabs(c.z)) << "p = " << c.p;
  EXPECT_EQ(normal_quantile(0.5), 0.0);  // exact: q = 0
  EXPECT_EQ(normal_quantile(0.0), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(normal_quantile(1.0), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(normal_quantile(1.5)));
  EXPECT_TRUE(std::isnan(normal_quantile(std::nan(""))));
  // p = 1 - 1e-16 rounds to 1 - 2^-53 in double, hence the same answer as that case.
  EXPECT_EQ(normal_quantile(1 - 1e-16), normal_quantile(1.0 - std::ldexp(1.0, -53)));
}

TEST(NormalDistribution, CdfKnownValues) {
  // mpmath references. erfc keeps relative accuracy in the lower tail; the argument z/sqrt(2)
  // carries a relative rounding of ~1e-16, which moves Phi by a relative z^2 * 1e-16: tolerances
  // 2e-13 at z = -37.5 (z^2 = 1406), 2e-14 at z = -10, 1e-15 elsewhere.
  EXPECT_NEAR(normal_cdf(-37.5), 4.6053530095819548438e-308, 2e-13 * 4.6053530095819548438e-308);
  EXPECT_NEAR(normal_cdf(-10), 7.619853024160526066e-24, 2e-14 * 7.619853024160526066e-24);
  EXPECT_NEAR(normal_cdf(1.5), 0.933192798731141934, 1e-15);
  EXPECT_NEAR(normal_ccdf(10), 7.619853024160526066e-24, 2e-14 * 7.619853024160526066e-24);
  EXPECT_NEAR(normal_cdf(8), 0.9999999999999993779, 1e-16);
  EXPECT_EQ(normal_cdf(0), 0.5);
}

TEST(NormalDistribution, QuantileRoundTrip) {
  // Phi(Phi^-1(p)) = p over p = 1e-300 ... 0.5 and the upper half. The relative error of the
  // quantile and the rounding of the argument z/sqrt(2) of erfc (together up to ~4.5 ulp, measured)
  // are amplified z^2 times through Phi in the tail (d ln Phi / d ln|z| = z^2), and erfc adds a few
  // ulp of its own: tolerance (16 + 6 z^2) * 1.1e-16, relative to min(p, 1 - p).
  for (double e = -300; e <= -0.31; e += 0.37) {
    const double p = std::pow(10.0, e);
    const double z = normal_quantile(p);
    const double tol = (16 + 6 * z * z) * 1.1e-16;
    EXPECT_NEAR(normal_cdf(z) / p, 1.0, tol) << "p = " << p;
    const double q = 1.0 - p;  // upper half: compare the complements
    if (q < 1.0) {
      EXPECT_NEAR(normal_ccdf(normal_quantile(q)) / (1.0 - q), 1.0, tol + 1.1e-16 / (1.0 - q))
          << "q = " << q;
    }
  }
}

TEST(NormalDistribution, QuantileOfAConstantIsItsRunTimeValue) {
  // Where the compiler sees the probability (a confidence level written in the code) it folds
  // Phi^-1 at compile time; the value must be the bits the same call gives at run time, or the
  // statistics of a default confidence would differ from those of the same confidence read in.
  volatile double p[] = {0.975, 0.9, 0.995, 0.025, 1e-12};
  EXPECT_EQ(normal_quantile(0.975), normal_quantile(p[0]));
  EXPECT_EQ(normal_quantile(0.9), normal_quantile(p[1]));
  EXPECT_EQ(normal_quantile(0.995), normal_quantile(p[2]));
  EXPECT_EQ(normal_quantile(0.025), normal_quantile(p[3]));
  EXPECT_EQ(normal_quantile(1e-12), normal_quantile(p[4]));
}

TEST(NormalDistribution, QuantileEachIsQuantileBitForBit) {
  // normal_quantile_each evaluates the central region for all values and the tails' approximations
  // for the values outside it, both vectorised: each value must be normal_quantile's bits, across
  // the region's edges, in both tails' approximations and across their edge, at the edges of
  // [0, 1], outside it, and for counts that do not fill its internal block of 64.
  std::vector<double> p = {0.0,
                           1.0,
                           0.5,
                           0.075,
                           0.925,
                           std::nextafter(0.075, 0.0),
                           std::nextafter(0.925, 1.0),
                           1e-300,
                           std::ldexp(1.0, -1074),
                           1.0 - std::ldexp(1.0, -53),
                           -0.1,
                           1.1,
                           std::nan("")};
  // Both tails' approximations (r <= 5 and beyond, r = 5 at p = 1.4e-11) from both ends.
  for (int e = 2; e <= 320; e += 3) p.push_back(std::pow(10.0, -e));
  for (int e = 2; e <= 16; ++e) p.push_back(1.0 - std::pow(10.0, -e));
  p.push_back(std::exp(-25.0));
  p.push_back(std::nextafter(std::exp(-25.0), 0.0));
  p.push_back(std::nextafter(std::exp(-25.0), 1.0));
  for (std::uint64_t i = 0; p.size() < 331; ++i) p.push_back(uniform_open01(7, i, 0));
  for (int n : {1, 13, 64, 65, 131, 331}) {
    std::vector<double> out(n), in_place(p.begin(), p.begin() + n);
    normal_quantile_each(p.data(), out.data(), n);
    normal_quantile_each(in_place.data(), in_place.data(), n);
    for (int k = 0; k < n; ++k) {
      const double ref = normal_quantile(p[k]);
      if (std::isnan(ref)) {
        EXPECT_TRUE(std::isnan(out[k]) && std::isnan(in_place[k])) << "p = " << p[k];
      } else {
        EXPECT_EQ(out[k], ref) << "n = " << n << ", p = " << p[k];
        EXPECT_EQ(in_place[k], ref) << "in place, n = " << n << ", p = " << p[k];
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Distributions: validation and marginals

TEST(Distribution, ValidationMessagesNameTheParameter) {
  expect_invalid([] { validate(normal(0, -1)); }, "sd = -1: must be > 0");
  expect_invalid([] { validate(uniform(3, 2)); }, "min = 3 >= max = 2");
  expect_invalid([] { validate(discrete({1, 2, 3}, {1, 2})); }, "weights: 2 given for 3 values");
  expect_invalid(
      [] {
        validate(discrete({1, 2}, {1, -0.5}));
      },
      "weights[1] = -0.5: must be finite and >= 0");
  expect_invalid([] { validate(discrete({1, 2}, {0, 0})); }, "weights: all zero");
  expect_invalid([] { validate(discrete({}, {})); }, "values: none given");
  expect_invalid([] { validate(lognormal(-2, 1)); }, "mean = -2: must be > 0");
  expect_invalid([] { validate(constant(std::nan(""))); }, "value = nan: must be finite");
  expect_invalid([] { validate(truncated(0, 1, 40, 41)); }, "no probability");
  expect_invalid([] { validate(truncated(0, 1, 2, 1)); }, "min = 2 >= max = 1");
  expect_invalid([] { validate(uniform(0, std::numeric_limits<double>::infinity())); },
                 "max = inf: must be finite");
  DistributionSpec grid_points = normal(0, 1);
  grid_points.values = {1, std::nan("")};
  expect_invalid([&] { validate(grid_points); }, "values[1] = nan: must be finite");
  // Subnormal numbers are written at their shortest round-trip precision, not an exception
  // (std::stod throws out_of_range on them; fuzzing found it).
  expect_invalid([] { validate(uniform(5e-324, 5e-324)); }, "min = 5e-324 >= max = 5e-324");
  expect_invalid([] { validate(normal(0, -1e-310)); }, "sd = -1e-310: must be > 0");
  // Valid ones pass, including a half-infinite truncation and a far upper tail.
  EXPECT_NO_THROW(validate(truncated(0, 1, 0, std::numeric_limits<double>::infinity())));
  EXPECT_NO_THROW(validate(truncated(0, 1, 30, 31)));
  EXPECT_NO_THROW(validate(discrete({1, 2}, {})));
}

TEST(Distribution, MarginalMomentsFromAMillionSamples) {
  // One Monte Carlo sampler with every kind; N = 1e6. Means within 5 SE = 5 sd / sqrt(N); standard
  // deviations within 5 SE = 5 sd sqrt((kurtosis - 1) / (4 N)) (the delta-method SE of a sample sd).
  const std::uint64_t N = 1000000;
  const std::vector<DistributionSpec> in = {
      uniform(2, 5),
      normal(10, 2),
      lognormal(3, 1.5),
      truncated(1, 2, 0, 3),
      truncated(0, 1, 10, 12),    // upper tail: Phi(10) = 1 - 7.6e-24
      truncated(0, 1, -12, -10),  // lower tail
      constant(4.25)};
  const HostSampler s(in, {}, Design::MonteCarlo, 2024, N);
  const auto x = draw(s, N);
  const double rootN = std::sqrt(double(N));
  {  // Uniform(2,5): mean 3.5, sd 3/sqrt(12), kurtosis 1.8
    const Moments m = moments(column(x, 0));
    const double sd = 3 / std::sqrt(12.0);
    EXPECT_NEAR(m.mean, 3.5, 5 * sd / rootN);
    EXPECT_NEAR(m.sd, sd, 5 * sd * std::sqrt(0.8 / 4) / rootN);
    for (double v : column(x, 0)) ASSERT_TRUE(v >= 2 && v <= 5);
  }
  {  // Normal(10, 2): kurtosis 3
    const Moments m = moments(column(x, 1));
    EXPECT_NEAR(m.mean, 10, 5 * 2 / rootN);
    EXPECT_NEAR(m.sd, 2, 5 * 2 * std::sqrt(2.0 / 4) / rootN);
  }
  {  // Lognormal with mean 3, sd 1.5 (cv 0.5): s^2 = ln 1.25, kurtosis e^{4s2} + 2e^{3s2} + 3e^{2s2} - 3
    const Moments m = moments(column(x, 2));
    const double s2 = std::log(1.25);
    const double kurt = std::exp(4 * s2) + 2 * std::exp(3 * s2) + 3 * std::exp(2 * s2) - 3;
    EXPECT_NEAR(m.mean, 3, 5 * 1.5 / rootN);
    EXPECT_NEAR(m.sd, 1.5, 5 * 1.5 * std::sqrt((kurt - 1) / 4) / rootN);
    for (double v : column(x, 2)) ASSERT_GT(v, 0);
  }
  // Truncated normals: every value inside [min, max]; the mean is mu + sigma (phi(a) - phi(b)) / Z,
  // Z = Phi(b) - Phi(a) (each tail case written with the accurate side); 5 SE with the sample sd.
  auto truncated_mean = [](double mu, double sigma, double lo, double hi) {
    const double a = (lo - mu) / sigma, b = (hi - mu) / sigma;
    const double Z = a > 0 ? normal_ccdf(a) - normal_ccdf(b) : normal_cdf(b) - normal_cdf(a);
    return mu + sigma * (normal_pdf(a) - normal_pdf(b)) / Z;
  };
  const double bounds[3][4] = {{1, 2, 0, 3}, {0, 1, 10, 12}, {0, 1, -12, -10}};
  for (int k = 0; k < 3; ++k) {
    const auto c = column(x, 3 + k);
    for (double v : c) ASSERT_TRUE(v >= bounds[k][2] && v <= bounds[k][3]) << v;
    const Moments m = moments(c);
    EXPECT_NEAR(m.mean, truncated_mean(bounds[k][0], bounds[k][1], bounds[k][2], bounds[k][3]),
                5 * m.sd / rootN)
        << "truncated normal " << k;
  }
  EXPECT_NEAR(truncated_mean(0, 1, 10, 12), 10.098, 1e-3);  // sanity of the reference (~ a + 1/a)
  for (double v : column(x, 6)) ASSERT_EQ(v, 4.25);
}

TEST(Distribution, DiscreteFrequenciesChiSquare) {
  // values {1, 2, 5, 7} with weights {0.2, 0.5, 0.3, 0}: the zero-weight value is never drawn, and
  // the chi-square statistic of the three others (2 degrees of freedom) is below 13.82, its critical
  // value at significance 1e-3. Also an equal-weight discrete (weights empty), 4 values (3 dof):
  // critical value 16.27.
  const std::uint64_t N = 1000000;
  const HostSampler s({discrete({1, 2, 5, 7}, {0.2, 0.5, 0.3, 0}), discrete({-1, 0, 1, 2}, {})}, {},
                      Design::MonteCarlo, 77, N);
  const auto x = draw(s, N);
  double count[4] = {0, 0, 0, 0}, equal[4] = {0, 0, 0, 0};
  for (std::uint64_t i = 0; i < N; ++i) {
    const double v = x(i, 0);
    const int k = v == 1 ? 0 : v == 2 ? 1 : v == 5 ? 2 : v == 7 ? 3 : -1;
    ASSERT_GE(k, 0) << v;
    ++count[k];
    const double w = x(i, 1);
    ASSERT_TRUE(w == -1 || w == 0 || w == 1 || w == 2);
    ++equal[int(w) + 1];
  }
  EXPECT_EQ(count[3], 0);
  const double p[3] = {0.2, 0.5, 0.3};
  double chi2 = 0, chi2_equal = 0;
  for (int k = 0; k < 3; ++k) chi2 += std::pow(count[k] - N * p[k], 2) / (N * p[k]);
  for (int k = 0; k < 4; ++k) chi2_equal += std::pow(equal[k] - N / 4.0, 2) / (N / 4.0);
  EXPECT_LT(chi2, 13.82);
  EXPECT_LT(chi2_equal, 16.27);
}

TEST(Distribution, QuantileEdges) {
  // Exact edge behaviour of the device quantile: u -> 0 / 1 stays inside the support; the discrete
  // search takes the first value whose cumulative probability reaches u.
  std::vector<double> values, cdf;
  const Marginal d = prepare_marginal(discrete({10, 20, 30}, {1, 1, 2}), values, cdf);
  ASSERT_EQ(cdf.size(), 3u);
  EXPECT_EQ(cdf[2], 1.0);
  EXPECT_EQ(marginal_quantile(d, 1e-300, 0, false, values.data(), cdf.data()), 10);
  EXPECT_EQ(marginal_quantile(d, 0.25, 0, false, values.data(), cdf.data()),
            10);  // cdf = 0.25 exactly
  EXPECT_EQ(marginal_quantile(d, 0.2500001, 0, false, values.data(), cdf.data()), 20);
  EXPECT_EQ(marginal_quantile(d, 1.0, 0, false, values.data(), cdf.data()), 30);
  const Marginal t = prepare_marginal(truncated(0, 1, 10, 12), values, cdf);
  for (double u : {1e-300, 1e-16, 0.5, 1 - 1e-16, 1.0}) {
    const double v = marginal_quantile(t, u, 0, false, values.data(), cdf.data());
    EXPECT_TRUE(v >= 10 && v <= 12) << u << " -> " << v;
  }
  const Marginal ln = prepare_marginal(lognormal(3, 1.5), values, cdf);
  // The median of the lognormal is exp(mu) = mean / sqrt(1 + cv^2): 3 / sqrt(1.25), to rounding.
  EXPECT_NEAR(marginal_quantile(ln, 0.5, 0, false, values.data(), cdf.data()), 3 / std::sqrt(1.25),
              1e-14);
}

TEST(Distribution, QuantileEachIsQuantileBitForBit) {
  // marginal_quantile_each against marginal_quantile for every kind, with and without a given
  // score, at the edges of (0, 1), at u equal to a cumulative weight (where the discrete search
  // and the counted index must both take the lower value), and in place.
  std::vector<double> values, cdf;
  std::vector<Marginal> marginals;
  for (const DistributionSpec& spec :
       {constant(4), uniform(-1, 5), normal(10, 2), lognormal(3, 1), truncated(0, 1, -3, -0.5),
        truncated(0, 1, 0.5, 3), truncated(2, 1, 0, 4), discrete({10, 20, 30, 40}, {1, 0, 1, 2}),
        discrete(one_to(40), {})})
    marginals.push_back(prepare_marginal(spec, values, cdf));
  std::vector<double> u = {1e-300, std::ldexp(1.0, -54),       0.25,     0.5,           0.075,
                           0.925,  1.0 - std::ldexp(1.0, -53), 1.0 / 40, 0.5 + 1.0 / 40};
  for (std::uint64_t i = 0; u.size() < 100; ++i) u.push_back(uniform_open01(5, i, 1));
  std::vector<double> z(u.size());
  for (std::size_t k = 0; k < u.size(); ++k) z[k] = normal_quantile(u[k]);
  const int n = static_cast<int>(u.size());
  for (std::size_t m = 0; m < marginals.size(); ++m)
    for (bool has_z : {false, true}) {
      std::vector<double> out(u.size()), in_place = u;
      marginal_quantile_each(marginals[m], u.data(), z.data(), has_z, values.data(), cdf.data(),
                             out.data(), n);
      marginal_quantile_each(marginals[m], in_place.data(), z.data(), has_z, values.data(),
                             cdf.data(), in_place.data(), n);
      for (int k = 0; k < n; ++k) {
        const double ref =
            marginal_quantile(marginals[m], u[k], z[k], has_z, values.data(), cdf.data());
        EXPECT_EQ(out[k], ref) << "marginal " << m << ", u = " << u[k] << ", has_z " << has_z;
        EXPECT_EQ(in_place[k], ref) << "in place, marginal " << m << ", u = " << u[k];
      }
    }
}

// ---------------------------------------------------------------------------------------------
// Latin hypercube

TEST(LatinHypercube, PermutationIsABijection) {
  // Exact: every n tried, pi(0..n-1) hits each of 0..n-1 once.
  for (std::uint64_t n : {1ull, 2ull, 3ull, 5ull, 17ull, 64ull, 1000ull, 4097ull}) {
    const PermutationDomain p = make_permutation_domain(n);
    for (std::uint64_t key : {0ull, 1ull, 0x123456789ABCDEFull}) {
      std::vector<int> hit(n, 0);
      for (std::uint64_t i = 0; i < n; ++i) {
        const std::uint64_t j = permute_index(i, key, p);
        ASSERT_LT(j, n);
        ++hit[j];
      }
      for (std::uint64_t j = 0; j < n; ++j)
        ASSERT_EQ(hit[j], 1) << "n " << n << " key " << key << " j " << j;
    }
  }
}

TEST(LatinHypercube, EveryStratumHitOncePerDimension) {
  // Exact: for N samples, floor(u N) over the N samples is a permutation of 0..N-1 in every
  // dimension; N a power of two (exact strata) and not.
  for (std::uint64_t N : {1ull, 2ull, 7ull, 1000ull, 1024ull, 4099ull}) {
    const std::vector<DistributionSpec> in(5, uniform(0, 1));
    const HostSampler s(in, {}, Design::LatinHypercube, 99, N);
    const auto x = draw(s, N);
    for (int d = 0; d < 5; ++d) {
      std::vector<int> hit(N, 0);
      for (std::uint64_t i = 0; i < N; ++i) {
        const double u = x(i, d);
        ASSERT_TRUE(u > 0 && u < 1);
        const auto k = static_cast<std::uint64_t>(std::floor(u * N));
        ASSERT_LT(k, N);
        ++hit[k];
      }
      for (std::uint64_t k = 0; k < N; ++k)
        ASSERT_EQ(hit[k], 1) << "N " << N << " dim " << d << " stratum " << k;
    }
    if (N >= 1000) {  // the dimensions use different permutations (identical ones would be a bug)
      int same = 0;
      for (std::uint64_t i = 0; i < N; ++i)
        same += std::floor(x(i, 0) * N) == std::floor(x(i, 1) * N);
      EXPECT_LT(same, 20);  // ~1 expected for independent permutations
    }
  }
}

TEST(LatinHypercube, DimensionsAreUncorrelatedAndMarginalsExact) {
  // N = 1e5: Pearson's r between dimensions within 5/sqrt(N); the mean of an LHS-sampled normal is
  // far more precise than Monte Carlo's (stratification): within 0.2 MC standard errors.
  const std::uint64_t N = 100000;
  const HostSampler s({uniform(0, 1), uniform(0, 1), normal(5, 2)}, {}, Design::LatinHypercube, 3,
                      N);
  const auto x = draw(s, N);
  EXPECT_LT(std::fabs(pearson(column(x, 0), column(x, 1))), 5 / std::sqrt(double(N)));
  EXPECT_LT(std::fabs(pearson(column(x, 0), column(x, 2))), 5 / std::sqrt(double(N)));
  EXPECT_NEAR(moments(column(x, 2)).mean, 5, 0.2 * 2 / std::sqrt(double(N)));
}

// ---------------------------------------------------------------------------------------------
// Sobol

TEST(Sobol, UnscrambledFirstPointsMatchTheKnownSequence) {
  // The Sobol sequence in Gray-code order (Joe & Kuo's generator, and scipy's Sobol with
  // scramble=False): exact dyadic values.
  const double expected[8][3] = {{0, 0, 0},
                                 {0.5, 0.5, 0.5},
                                 {0.75, 0.25, 0.25},
                                 {0.25, 0.75, 0.75},
                                 {0.375, 0.375, 0.625},
                                 {0.875, 0.875, 0.125},
                                 {0.625, 0.125, 0.875},
                                 {0.125, 0.625, 0.375}};
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(sobol_unscrambled(i, d), expected[i][d]) << "point " << i << " dim " << d;
}

TEST(Sobol, EveryDimensionIsStratifiedAndTheTableIsWellFormed) {
  // Exact: the first 2^m unscrambled points of each of the 32 dimensions hit each interval
  // [k/2^m, (k+1)/2^m) once (a (0,m,1)-net); and the table's initial m_k are odd and < 2^k.
  for (const SobolPolynomial& p : sobol_joe_kuo_6_21201)
    for (int k = 0; k < p.s; ++k) {
      EXPECT_EQ(p.m[k] % 2, 1u) << "dim " << p.d;
      EXPECT_LT(p.m[k], 1u << (k + 1)) << "dim " << p.d;
    }
  const auto V = sobol_direction_numbers(sobol_max_dimensions);
  const int m = 12;
  for (int d = 0; d < sobol_max_dimensions; ++d) {
    std::vector<int> hit(1 << m, 0);
    for (std::uint64_t i = 0; i < (1u << m); ++i)
      ++hit[sobol_word(V.data() + d * sobol_bits, i) >> (64 - m)];
    for (int k = 0; k < (1 << m); ++k) ASSERT_EQ(hit[k], 1) << "dim " << d;
  }
}

TEST(Sobol, ScrambledPointsFormA0m2Net) {
  // Exact: Owen scrambling keeps the net property. For 2^m scrambled points in dimensions 1-2,
  // every elementary box [i/2^a, (i+1)/2^a) x [j/2^(m-a), (j+1)/2^(m-a)), a = 0..m, holds one point.
  const int m = 10;
  const std::uint64_t N = 1u << m;
  for (std::uint64_t seed : {1ull, 2ull, 0xFEEDull}) {
    const HostSampler s({uniform(0, 1), uniform(0, 1)}, {}, Design::Sobol, seed, N);
    const auto x = draw(s, N);
    for (int a = 0; a <= m; ++a) {
      std::vector<int> hit(N, 0);
      for (std::uint64_t i = 0; i < N; ++i) {
        const double u = x(i, 0), v = x(i, 1);
        ASSERT_TRUE(u > 0 && u < 1 && v > 0 && v < 1);
        const auto bi = static_cast<std::uint64_t>(std::ldexp(u, a));
        const auto bj = static_cast<std::uint64_t>(std::ldexp(v, m - a));
        ++hit[(bi << (m - a)) | bj];
      }
      for (std::uint64_t b = 0; b < N; ++b) ASSERT_EQ(hit[b], 1) << "seed " << seed << " a " << a;
    }
    // The scrambling is seed-keyed: another seed moves the points.
    const HostSampler other({uniform(0, 1), uniform(0, 1)}, {}, Design::Sobol, seed + 100, N);
    double a[2], b[2];
    s.sample(5, a);
    other.sample(5, b);
    EXPECT_NE(a[0], b[0]);
  }
}

TEST(Sobol, IntegrationErrorFarBelowMonteCarlo) {
  // f(u) = prod_{d<5} (pi/2) sin(pi u_d), integral 1, variance (pi^2/8)^5 - 1 = 1.86: at N = 2^14
  // Monte Carlo's standard error is 0.0107. Scrambled Sobol's root-mean-square error over 8 seeds
  // must be below 0.1 of it (10x better). Measured while writing this test: ~3e-4 (35x better),
  // the same as with an exact per-digit Owen scramble (~5e-4 over 10 seeds) and with the
  // unscrambled points (9e-4), so the hash-based scramble costs nothing; a broken table or scramble
  // gives Monte Carlo-like errors (~1e-2).
  const std::uint64_t N = 1u << 14;
  const double mc_se = std::sqrt(std::pow(kPi * kPi / 8, 5) - 1) / std::sqrt(double(N));
  const std::vector<DistributionSpec> in(5, uniform(0, 1));
  double sum_sq = 0;
  const int seeds = 8;
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    const HostSampler s(in, {}, Design::Sobol, seed, N);
    const auto x = draw(s, N);
    double sum = 0;
    for (std::uint64_t i = 0; i < N; ++i) {
      double f = 1;
      for (int d = 0; d < 5; ++d) f *= 0.5 * kPi * std::sin(kPi * x(i, d));
      sum += f;
    }
    sum_sq += std::pow(sum / N - 1, 2);
  }
  const double rms = std::sqrt(sum_sq / seeds);
  EXPECT_LT(rms, 0.1 * mc_se) << "Sobol RMS error " << rms << ", MC standard error " << mc_se;
  // Monte Carlo itself, for contrast, is within 5 SE of the integral (not far below it).
  const HostSampler mc(in, {}, Design::MonteCarlo, 1, N);
  const auto y = draw(mc, N);
  double sum = 0;
  for (std::uint64_t i = 0; i < N; ++i) {
    double f = 1;
    for (int d = 0; d < 5; ++d) f *= 0.5 * kPi * std::sin(kPi * y(i, d));
    sum += f;
  }
  EXPECT_LT(std::fabs(sum / N - 1), 5 * mc_se);
}

TEST(Sobol, TooManyDimensionsThrow) {
  const std::vector<DistributionSpec> in(33, uniform(0, 1));
  expect_invalid([&] { HostSampler(in, {}, Design::Sobol, 1, 8); }, "at most 32");
  expect_invalid([&] { sobol_direction_numbers(33); }, "at most 32");
}

// ---------------------------------------------------------------------------------------------
// Grid

TEST(Grid, FullFactorialFirstInputFastest) {
  // Exact: 2 x 3 x 1 points; sample i has digits (i mod 2, (i / 2) mod 3), the constant contributes
  // its value as its one point.
  DistributionSpec a = uniform(0, 1), b = normal(0, 1);
  a.values = {1, 2};
  b.values = {10, 20, 30};
  const HostSampler s({a, b, constant(7)}, {}, Design::Grid, 0, 6);
  const auto x = draw(s, 6);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(x(i, 0), a.values[i % 2]) << i;
    EXPECT_EQ(x(i, 1), b.values[(i / 2) % 3]) << i;
    EXPECT_EQ(x(i, 2), 7) << i;
  }
  // Every combination exactly once.
  std::set<std::pair<double, double>> seen;
  for (int i = 0; i < 6; ++i) seen.insert({x(i, 0), x(i, 1)});
  EXPECT_EQ(seen.size(), 6u);
  expect_invalid(
      [&] {
        HostSampler({a, b}, {}, Design::Grid, 0, 5);
      },
      "full factorial has 6 points (2 x 3)");
  expect_invalid(
      [&] {
        HostSampler({a, normal(0, 1)}, {}, Design::Grid, 0, 2);
      },
      "input 1 (normal): no grid points");
  expect_invalid(
      [&] {
        HostSampler({a, b}, {{1, 0}, {0, 1}}, Design::Grid, 0, 6);
      },
      "not allowed with the Grid design");
}

// ---------------------------------------------------------------------------------------------
// Copula

TEST(Copula, NormalScoreCorrelationMatchesRho) {
  // Three marginals (normal, lognormal, uniform) under a 3x3 correlation of their normal scores;
  // N = 1e6 Monte Carlo. The scores are recovered exactly from the values (z = (x - m)/s,
  // (ln x - mu)/sigma, Phi^-1((x - a)/w)); Pearson's r of normal pairs has SE (1 - rho^2)/sqrt(N):
  // each within 5 SE.
  const std::uint64_t N = 1000000;
  const std::vector<std::vector<double>> R = {{1, 0.5, -0.3}, {0.5, 1, 0.2}, {-0.3, 0.2, 1}};
  const HostSampler s({normal(1, 2), lognormal(3, 1.5), uniform(-1, 1)}, R, Design::MonteCarlo, 11,
                      N);
  EXPECT_TRUE(s.correlated());
  const auto x = draw(s, N);
  const double s2 = std::log(1.25), mu = std::log(3.0) - 0.5 * s2;
  std::vector<double> z[3];
  for (auto& c : z) c.resize(N);
  for (std::uint64_t i = 0; i < N; ++i) {
    z[0][i] = (x(i, 0) - 1) / 2;
    z[1][i] = (std::log(x(i, 1)) - mu) / std::sqrt(s2);
    z[2][i] = normal_quantile((x(i, 2) + 1) / 2);
  }
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      const double rho = R[a][b];
      EXPECT_NEAR(pearson(z[a], z[b]), rho, 5 * (1 - rho * rho) / std::sqrt(double(N)))
          << a << "," << b;
    }
  // The first input's row of L is the identity's: its values are bitwise those of the independent
  // sampler with the same seed.
  const HostSampler independent({normal(1, 2), lognormal(3, 1.5), uniform(-1, 1)}, {},
                                Design::MonteCarlo, 11, N);
  double p[3], q[3];
  for (std::uint64_t i = 0; i < 1000; ++i) {
    s.sample(i, p);
    independent.sample(i, q);
    ASSERT_EQ(p[0], q[0]);
  }
}

TEST(Copula, WorksWithDiscreteAndQmcDesigns) {
  // A discrete marginal under the copula keeps its frequencies (the copula only reorders which
  // samples get which value): p(1) = 0.3 within 5 SE = 5 sqrt(0.21/N); and Sobol with a correlation
  // gives the normal-score correlation within the MC tolerance too.
  const std::uint64_t N = 1u << 18;
  const std::vector<std::vector<double>> R = {{1, 0.8}, {0.8, 1}};
  for (Design design : {Design::MonteCarlo, Design::LatinHypercube, Design::Sobol}) {
    const HostSampler s({normal(0, 1), discrete({1, 2}, {0.3, 0.7})}, R, design, 5, N);
    const auto x = draw(s, N);
    double ones = 0;
    std::vector<double> z0(N), d(N);
    for (std::uint64_t i = 0; i < N; ++i) {
      ones += x(i, 1) == 1;
      z0[i] = x(i, 0);
      d[i] = x(i, 1);
    }
    EXPECT_NEAR(ones / N, 0.3, 5 * std::sqrt(0.21 / N)) << to_string(design);
    // The discrete value is 2 exactly when the correlated score is above Phi^-1(0.3): positive
    // dependence, Pearson's r well above 0 (for rho = 0.8 it is about 0.8 * phi(z_0.3) / sqrt(0.21)
    // = 0.8 * 0.3477 / 0.4583 = 0.607).
    EXPECT_NEAR(pearson(z0, d), 0.8 * normal_pdf(normal_quantile(0.3)) / std::sqrt(0.21), 0.01)
        << to_string(design);
  }
}

TEST(Copula, InvalidMatricesThrowWithTheProblem) {
  const std::vector<DistributionSpec> in = {normal(0, 1), normal(0, 1), normal(0, 1)};
  auto make = [&](std::vector<std::vector<double>> R) {
    HostSampler(in, R, Design::MonteCarlo, 1, 10);
  };
  expect_invalid([&] { make({{1, 0}, {0, 1}}); }, "2 rows given for 3 inputs");
  expect_invalid(
      [&] {
        make({{1, 0, 0}, {0, 1}, {0, 0, 1}});
      },
      "correlation[1]: 2 entries given for 3 inputs");
  expect_invalid([&] { make({{1, 0.5, 0}, {0.4, 1, 0}, {0, 0, 1}}); }, "must be symmetric");
  expect_invalid(
      [&] {
        make({{1, 1.2, 0}, {1.2, 1, 0}, {0, 0, 1}});
      },
      "correlation[0][1] = 1.2: must be in [-1, 1]");
  expect_invalid(
      [&] {
        make({{1, 0, 0}, {0, 0.9, 0}, {0, 0, 1}});
      },
      "correlation[1][1] = 0.9: the diagonal");
  expect_invalid(
      [&] {
        make({{1, 0.9, -0.9}, {0.9, 1, 0.9}, {-0.9, 0.9, 1}});
      },
      "not positive definite");
  expect_invalid([&] { make({{1, 1, 0}, {1, 1, 0}, {0, 0, 1}}); }, "not positive definite");
  expect_invalid(
      [&] {
        make({{1, std::nan(""), 0}, {0, 1, 0}, {0, 0, 1}});
      },
      "correlation[0][1] = nan: must be finite");
  EXPECT_NO_THROW(make({{1, 0.9, 0.8}, {0.9, 1, 0.85}, {0.8, 0.85, 1}}));
}

TEST(Sampler, ConstructorErrors) {
  expect_invalid(
      [] {
        HostSampler({normal(0, 1), normal(0, -1)}, {}, Design::MonteCarlo, 1, 10);
      },
      "input 1 (normal): sd = -1: must be > 0");
  expect_invalid([] { HostSampler({normal(0, 1)}, {}, Design::LatinHypercube, 1, 0); },
                 "sample_count = 0");
  const std::vector<DistributionSpec> many(33, normal(0, 1));
  expect_invalid([&] { HostSampler(many, {}, Design::MonteCarlo, 1, 10); }, "at most 32");
  const HostSampler s({normal(0, 1), uniform(0, 1)}, {}, Design::MonteCarlo, 1, 10);
  EXPECT_EQ(s.dimensions(), 2);
  EXPECT_EQ(s.sample_count(), 10u);
  Kokkos::View<double**, Kokkos::LayoutLeft, Kokkos::HostSpace> wrong("wrong", 4, 3);
  expect_invalid([&] { sample_batch(Kokkos::DefaultHostExecutionSpace(), s, 0, wrong); },
                 "3 columns for 2 inputs");
}

// ---------------------------------------------------------------------------------------------
// Reproducibility, once per backend compiled in

template <class ExecSpace>
class SamplerReproducibility : public ::testing::Test {};

template <class Mem>
constexpr bool on_host = Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
// A device's sample against the host's: a few roundings of the quantile functions, relative to the
// value (a discrete or grid value is exact unless an input falls within that of a step).
constexpr double kDeviceTolerance = 1e-13;
double relative_difference(double a, double b) {
  if (a == b) return 0.0;
  return std::fabs(a - b) / std::max(std::fabs(a), std::fabs(b));
}
TYPED_TEST_SUITE(SamplerReproducibility, lsi::test::Backends);

TEST(Sampler, BlockIsSampleBitForBit) {
  // sample_block runs each stage for a block of samples; every input of every sample must be
  // sample()'s bits: every marginal kind, with and without the copula (so Normal and Lognormal
  // both from the copula's score and from their own Phi^-1), the truncated normal in its lower
  // tail, upper tail and on both sides, a short discrete table (counted) and a long one (searched),
  // every design, and blocks across 2^32 and beyond it.
  const std::vector<DistributionSpec> independent = {constant(4),
                                                     normal(10, 2),
                                                     lognormal(3, 1),
                                                     uniform(-1, 5),
                                                     truncated(0, 1, -3, -0.5),
                                                     truncated(0, 1, 0.5, 3),
                                                     truncated(2, 1, 0, 4),
                                                     discrete({1, 2, 3, 4}, {1, 0, 2, 1}),
                                                     discrete(one_to(40), {})};
  std::vector<std::vector<double>> correlated(independent.size(),
                                              std::vector<double>(independent.size(), 0.0));
  for (std::size_t d = 0; d < independent.size(); ++d) correlated[d][d] = 1.0;
  correlated[1][2] = correlated[2][1] = 0.5;   // normal ~ lognormal: both take the copula's score
  correlated[3][5] = correlated[5][3] = -0.3;  // uniform ~ truncated: Phi of the mixed score
  // lognormal ~ truncated: row 5 reads row 2's score, which the rows, run from the last up, must
  // not have overwritten yet.
  correlated[2][5] = correlated[5][2] = 0.3;
  constexpr int B = HostSampler::block_size;
  const int dims = static_cast<int>(independent.size());
  std::vector<double> block(static_cast<std::size_t>(dims) * B);
  double ref[HostSampler::max_dimensions];
  const auto expect_block_is_sample = [&](const HostSampler& s, std::uint64_t first,
                                          const std::string& what) {
    s.sample_block(first, block.data());
    for (int k = 0; k < B; ++k) {
      s.sample(first + k, ref);
      for (int d = 0; d < dims; ++d)
        ASSERT_EQ(block[static_cast<std::size_t>(d) * B + k], ref[d])
            << what << ", sample " << first + k << ", input " << d;
    }
  };
  for (Design design : {Design::MonteCarlo, Design::LatinHypercube, Design::Sobol, Design::Grid})
    for (bool with_copula : {false, true}) {
      std::vector<DistributionSpec> in = independent;
      std::uint64_t n = 64 * 40;
      if (design == Design::Grid) {
        if (with_copula) continue;
        for (auto& spec : in) spec.values = {1, 2};
        n = std::uint64_t{1} << in.size();
      }
      const HostSampler s(in, with_copula ? correlated : std::vector<std::vector<double>>{}, design,
                          99, n);
      std::vector<std::uint64_t> firsts;
      for (std::uint64_t f = 0; f + B <= n; f += B) firsts.push_back(f);
      firsts.push_back(n - B - 3);  // not a multiple of the block
      if (design == Design::MonteCarlo || design == Design::Sobol) {
        firsts.push_back((std::uint64_t{1} << 32) - 5);  // the counter's high word changes inside
        firsts.push_back((std::uint64_t{1} << 33) + 5);
      }
      for (std::uint64_t first : firsts)
        expect_block_is_sample(s, first,
                               std::string(to_string(design)) + (with_copula ? " + copula" : ""));
    }
  std::vector<double> rows;  // the Points design: given rows
  for (int i = 0; i < 3 * B * dims; ++i) rows.push_back(0.5 * i - 7);
  const HostSampler given(rows, dims, 3 * B);
  for (std::uint64_t first : {0, B + 3}) expect_block_is_sample(given, first, "points");
}

TYPED_TEST(SamplerReproducibility, SampleIIsTheSameInEveryBatch) {
  // Sample i from (a) the host scalar call, (b) a batch of N starting at 0, (c) batches of 1, 7 and
  // 50 starting at i or elsewhere, on this execution space. (b) and (c) agree bitwise everywhere
  // (what resuming and sharding a sweep rely on). (a) and (b) agree bitwise on the host's spaces
  // (so Serial and OpenMP agree bitwise with each other) and within kDeviceTolerance on a device,
  // whose math library (log, exp, erfc) and fused multiply-adds round differently.
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  double worst = 0.0;  // largest relative difference from the host call
  const std::uint64_t N = 1000;
  const std::vector<std::vector<double>> R = {
      {1, 0.6, 0, 0, 0}, {0.6, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}, {0, 0, 0, 0, 1}};
  const std::vector<DistributionSpec> specs = {normal(10, 2), lognormal(3, 1), uniform(0, 5),
                                               truncated(0, 1, 0.5, 3),
                                               discrete({1, 2, 3}, {1, 2, 1})};
  for (Design design : {Design::MonteCarlo, Design::LatinHypercube, Design::Sobol, Design::Grid}) {
    std::vector<DistributionSpec> in = specs;
    std::uint64_t n = N;
    std::vector<std::vector<double>> corr = R;
    if (design == Design::Grid) {
      for (auto& spec : in) spec.values = {1, 2, 3, 4};
      n = 4 * 4 * 4 * 4 * 4;
      corr.clear();
    }
    const Sampler<Mem> s(in, corr, design, 0xABCDEF, n);
    const HostSampler host(in, corr, design, 0xABCDEF, n);
    Kokkos::View<double**, Kokkos::LayoutLeft, Mem> all("all", n, 5);
    sample_batch(Exec(), s, 0, all);
    Exec().fence();
    const auto all_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), all);
    double ref[5];
    for (std::uint64_t i = 0; i < n; ++i) {
      host.sample(i, ref);
      for (int d = 0; d < 5; ++d) {
        if (on_host<Mem>) {
          ASSERT_EQ(all_h(i, d), ref[d]) << to_string(design) << " sample " << i << " dim " << d;
        } else {
          worst = std::max(worst, relative_difference(all_h(i, d), ref[d]));
          ASSERT_LE(relative_difference(all_h(i, d), ref[d]), kDeviceTolerance)
              << to_string(design) << " sample " << i << " dim " << d << ": " << all_h(i, d)
              << " on the device, " << ref[d] << " on the host";
        }
      }
    }
    for (std::uint64_t first : {0ull, 137ull, 500ull, 999ull})
      for (std::uint64_t size : {1ull, 7ull, 50ull}) {
        const std::uint64_t m = std::min(size, n - first);
        Kokkos::View<double**, Kokkos::LayoutLeft, Mem> part("part", m, 5);
        sample_batch(Exec(), s, first, part);
        Exec().fence();
        const auto part_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), part);
        for (std::uint64_t i = 0; i < m; ++i)
          for (int d = 0; d < 5; ++d)
            ASSERT_EQ(part_h(i, d), all_h(first + i, d))
                << to_string(design) << " first " << first << " i " << i;
      }
  }
  if (!on_host<Mem>) std::cout << "largest relative difference from the host: " << worst << "\n";
}

TYPED_TEST(SamplerReproducibility, MonteCarloAndSobolAcceptAnyIndex) {
  // Indices beyond sample_count and beyond 2^32 are valid for Monte Carlo and Sobol: values inside
  // the support, identical on this backend and in the host scalar call.
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  for (Design design : {Design::MonteCarlo, Design::Sobol}) {
    const Sampler<Mem> s({uniform(0, 1), normal(0, 1)}, {}, design, 3, 16);
    const HostSampler host({uniform(0, 1), normal(0, 1)}, {}, design, 3, 16);
    const std::uint64_t first = (std::uint64_t{1} << 40) + 12345;
    Kokkos::View<double**, Kokkos::LayoutLeft, Mem> out("out", 64, 2);
    sample_batch(Exec(), s, first, out);
    Exec().fence();
    const auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
    double ref[2];
    for (std::uint64_t i = 0; i < 64; ++i) {
      host.sample(first + i, ref);
      for (int d = 0; d < 2; ++d) {
        if (on_host<Mem>)
          ASSERT_EQ(h(i, d), ref[d]) << i;
        else
          ASSERT_LE(relative_difference(h(i, d), ref[d]), kDeviceTolerance) << i;
      }
      ASSERT_TRUE(ref[0] > 0 && ref[0] < 1 && std::isfinite(ref[1]));
    }
  }
}

}  // namespace
