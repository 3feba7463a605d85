// A column's statistics fed a batch at a time (sweeps/column_accumulator.hpp) against describe()
// of the whole column (sweeps/statistics.hpp): the same numbers bit for bit, however the values
// are handed over, with the column read back only where the values did not come in random order.
#include "sweeps/column_accumulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "sweeps/statistics.hpp"

namespace {
using namespace lsi::sweeps;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Every field of two summaries, bit for bit (NaN included).
void expect_same_bits(const OutputStatistics& a, const OutputStatistics& b,
                      const std::string& why) {
  const double x[] = {a.mean,        a.standard_deviation, a.min,         a.max,
                      a.mean_ci.low, a.mean_ci.high,       a.q05,         a.q50,
                      a.q95,         a.q05_ci.low,         a.q05_ci.high, a.q50_ci.low,
                      a.q50_ci.high, a.q95_ci.low,         a.q95_ci.high};
  const double y[] = {b.mean,        b.standard_deviation, b.min,         b.max,
                      b.mean_ci.low, b.mean_ci.high,       b.q05,         b.q50,
                      b.q95,         b.q05_ci.low,         b.q05_ci.high, b.q50_ci.low,
                      b.q50_ci.high, b.q95_ci.low,         b.q95_ci.high};
  EXPECT_EQ(a.count, b.count) << why;
  EXPECT_EQ(a.infinite_count, b.infinite_count) << why;
  for (std::size_t i = 0; i < sizeof x / sizeof x[0]; ++i)
    EXPECT_EQ(std::memcmp(&x[i], &y[i], sizeof(double)), 0)
        << why << ": field " << i << " " << x[i] << " vs " << y[i];
}

// The columns: normal values, a point mass (most values +0, as the final displacement of barriers
// that never slide), ties (ten integers), +inf among normal values, -0 and +0 among values of
// both signs.
std::vector<std::vector<double>> columns(const std::size_t n, const unsigned seed) {
  std::mt19937_64 g(seed);
  std::normal_distribution<double> normal(3.0e5, 4.0e4);
  std::exponential_distribution<double> tail(2.0);
  std::uniform_int_distribution<int> digit(0, 9);
  std::vector<std::vector<double>> c(5, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    c[0][i] = normal(g);
    c[1][i] = (g() % 100) < 85 ? 0.0 : tail(g);
    c[2][i] = double(digit(g));
    c[3][i] = (g() % 50) == 0 ? kInf : normal(g);
    const int k = digit(g);
    c[4][i] = k == 0 ? -0.0 : k == 1 ? 0.0 : (k < 6 ? -1.0 : 1.0) * tail(g);
  }
  return c;
}

// The values handed over at once, one at a time, and in batches of random sizes.
std::vector<std::vector<std::size_t>> batchings(const std::size_t n) {
  std::vector<std::vector<std::size_t>> b(3);
  b[0] = {n};
  b[1] = std::vector<std::size_t>(n, 1);
  std::mt19937 g(7);
  for (std::size_t left = n; left > 0;) {
    const std::size_t k = std::min<std::size_t>(left, 1 + g() % 700);
    b[2].push_back(k);
    left -= k;
  }
  return b;
}

ColumnAccumulator fed(const std::vector<double>& v, const std::vector<std::size_t>& batches,
                      const std::vector<double>& thresholds, const std::size_t first_values) {
  ColumnAccumulator a(thresholds, 0.95, first_values);
  std::size_t at = 0;
  for (const std::size_t k : batches) {
    a.add(v.data() + at, k);
    at += k;
  }
  return a;
}

TEST(ColumnAccumulator, GivesDescribesNumbersBitForBitHoweverTheValuesArrive) {
  // 3000 values, 500 of them first (the ranges set from them): above describe()'s 4096-value
  // limit of direct selection only where the first values are few, so both paths of
  // order_statistics meet the accumulator's.
  for (const std::size_t n : {3000u, 9000u}) {
    const std::size_t first = 500;
    const auto cols = columns(n, unsigned(n));
    for (std::size_t c = 0; c < cols.size(); ++c) {
      const std::vector<double>& v = cols[c];
      OrderScratch scratch;
      const OutputStatistics want = describe(v, scratch, 0.95, first);
      for (const auto& batches : batchings(n)) {
        ColumnAccumulator a = fed(v, batches, {}, first);
        const std::string why = "column " + std::to_string(c) + ", n " + std::to_string(n) + ", " +
                                std::to_string(batches.size()) + " batches";
        EXPECT_FALSE(a.needs_column()) << why;
        int asked = 0;
        const OutputStatistics got = a.describe(
            [&] {
              ++asked;
              return v;
            },
            scratch);
        EXPECT_EQ(asked, 0) << why;
        expect_same_bits(got, want, why);
        // The values kept: those inside the ranges, under the column. With 500 first values the
        // ranges are wide (w = (z + 6) sqrt(q (1 - q) / 500) + 4 / 500: 0.084 about q05 and q95,
        // 0.186 about the median; 64 % of the values in all, less where ties sit on the ends).
        EXPECT_LT(a.values_kept(), n * 7 / 10) << why;
      }
    }
  }
}

TEST(ColumnAccumulator, DescribesAColumnOfFewerValuesThanTheFirstOnesWhole) {
  const auto cols = columns(300, 3);
  for (const auto& v : cols) {
    ColumnAccumulator a = fed(v, batchings(300)[2], {}, 500);
    OrderScratch scratch;
    expect_same_bits(a.describe([&] { return v; }, scratch), describe(v, scratch), "300 values");
  }
}

TEST(ColumnAccumulator, ReadsTheColumnBackWhereTheValuesCameInOrder) {
  // A column handed over ascending (a grid walked in order): the first values are the least,
  // the ranges lie below the median, and the column is asked for once.
  std::vector<double> v = columns(4000, 11)[0];
  std::sort(v.begin(), v.end());
  ColumnAccumulator a = fed(v, batchings(4000)[2], {}, 500);
  EXPECT_TRUE(a.needs_column());
  int asked = 0;
  OrderScratch scratch;
  const OutputStatistics got = a.describe(
      [&] {
        ++asked;
        return v;
      },
      scratch);
  EXPECT_EQ(asked, 1);
  expect_same_bits(got, describe(v, scratch, 0.95, 500), "ascending");
}

TEST(ColumnAccumulator, CountsTheValuesAboveEachThreshold) {
  const auto cols = columns(5000, 5);
  const std::vector<double> thresholds = {-1.0, 0.0, 0.5, 3.0e5, kInf};
  for (const auto& v : cols) {
    const ColumnAccumulator a = fed(v, batchings(5000)[2], thresholds, 500);
    for (std::size_t j = 0; j < thresholds.size(); ++j) {
      const ExceedanceEstimate want = exceedance(v, thresholds[j]);
      const ExceedanceEstimate got = a.exceedance(j);
      EXPECT_EQ(got.exceed_count, want.exceed_count);
      EXPECT_EQ(got.count, want.count);
      EXPECT_EQ(got.probability, want.probability);
      EXPECT_EQ(got.ci.low, want.ci.low);
      EXPECT_EQ(got.ci.high, want.ci.high);
    }
  }
}

TEST(ColumnAccumulator, RefusesNoValuesAndNaNAsDescribeDoes) {
  ColumnAccumulator none({}, 0.95, 500);
  OrderScratch scratch;
  const auto column = [] { return std::vector<double>{}; };
  try {
    none.describe(column, scratch);
    ADD_FAILURE() << "no values described";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no values"), std::string::npos) << e.what();
  }
  std::vector<double> v = columns(2000, 9)[0];
  v[1500] = std::nan("");
  v[1700] = -kInf;
  ColumnAccumulator bad = fed(v, {2000}, {}, 500);
  EXPECT_EQ(bad.invalid_count(), 2u);
  try {
    bad.describe(column, scratch);
    ADD_FAILURE() << "NaN described";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 values are NaN or -inf"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(ColumnAccumulator({}, 1.0), std::invalid_argument);
}

TEST(ColumnAccumulator, KeepsAFewPerCentOfALargeColumn) {
  // 2^20 normal values with the default first values (2^18): the three ranges hold about 2.9 %
  // of the values (w = 7.96 sqrt(q (1 - q) / 2^18): 1.6 % about the median, 0.7 % about each
  // tail quantile); the sweep's memory check counts 4 %.
  const std::size_t n = std::size_t{1} << 20;
  const std::vector<double> v = columns(n, 13)[0];
  ColumnAccumulator a({}, 0.95);
  for (std::size_t at = 0; at < n; at += 100000)
    a.add(v.data() + at, std::min<std::size_t>(100000, n - at));
  EXPECT_LT(double(a.values_kept()), 0.04 * double(n));
  EXPECT_GT(double(a.values_kept()), 0.02 * double(n));
  OrderScratch scratch;
  EXPECT_FALSE(a.needs_column());
  expect_same_bits(a.describe([&] { return v; }, scratch), describe(v, scratch), "2^20 values");
}

TEST(ColumnAccumulator, TheStandardDeviationAboutTheFirstValuesMeanIsTheTwoPassOne) {
  // Values 1e6 + N(0, 1) (a large mean against the spread): the sums about the mean of the first
  // 500 values against those about the mean of all (two-pass). Both carry the rounding of the
  // differences x - K, about 1e6 eps relative to the spread: 1e-9 relative bounds them.
  std::mt19937_64 g(17);
  std::normal_distribution<double> normal(1.0e6, 1.0);
  std::vector<double> v(20000);
  for (auto& x : v) x = normal(g);
  OrderScratch scratch;
  const double two_pass = describe(v, scratch, 0.95, v.size()).standard_deviation;
  const double shifted = describe(v, scratch, 0.95, 500).standard_deviation;
  EXPECT_NEAR(shifted, two_pass, 1e-9 * two_pass);
  EXPECT_NEAR(two_pass, 1.0, 0.03);  // 20000 draws: the sample's sd within 3 % of 1
}

}  // namespace
