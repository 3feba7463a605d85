// Statistics of the outputs of a sweep (host; header-only): summary with confidence intervals
// (describe) and exceedance probabilities (exceedance).
//
// * Mean: the sample mean, its standard deviation with n - 1, and the CI mean +- t s / sqrt(n) with
//   Student's t of n - 1 degrees of freedom (exact for normal outputs, and it tends to the normal
//   interval as n grows, so no switch is needed; beyond 10^7 degrees of freedom the normal quantile
//   is used). n = 1: standard_deviation is NaN and mean_ci is (-inf, inf).
// * Quantiles q05, q50, q95: Hyndman & Fan type 7 (linear interpolation between order statistics at
//   h = (n - 1) q, the default of R and numpy).
// * Quantile CIs: distribution-free, from order statistics. With B ~ Binomial(n, q) the number of
//   outputs at or below the true quantile xi_q, P(x_(l) <= xi_q <= x_(u)) = P(l <= B <= u - 1), for
//   any continuous distribution. We take the equal-tailed ranks: l the largest with P(B < l) <= a/2
//   and u the smallest with P(B >= u) <= a/2 (a = 1 - confidence), so the coverage is at least
//   `confidence` (more, by the discreteness of B: order_statistic_ranks() returns the exact value).
//   Exact binomial probabilities (regularised incomplete beta) for n <= 10^6, the normal
//   approximation with continuity correction above. When too few samples exist, the bound is
//   infinite (l = 0: -inf; u = n + 1: +inf), e.g. q05 with n < 72 has no finite lower bound at 95 %.
// * Exceedance P(value > threshold): the Wilson score interval, which behaves at p = 0 and 1
//   (k = 0 gives [0, z^2 / (n + z^2)]), unlike the Wald interval.
// * +inf outputs (e.g. "the barrier never stops") are valid: they count, exceed every threshold, sit
//   at the top of the order statistics, and make mean and standard deviation +inf. NaN, -inf or no
//   values throw: the caller excludes failed samples first.
//
// All these intervals assume independent, identically distributed samples, i.e. plain Monte Carlo.
// For Latin hypercube or scrambled Sobol designs the samples are negatively dependent by
// construction: the estimators stay unbiased but their variance is (usually much) smaller, so these
// intervals are conservative there; a proper CI for QMC needs independent replicates (several
// seeds) and the spread of their means.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sweeps/distribution.hpp"
#include "sweeps/normal_distribution.hpp"
#include "sweeps/order_statistics.hpp"

namespace lsi::sweeps {

struct Interval {
  double low, high;
};

struct OutputStatistics {
  std::size_t count = 0;  // finite + infinite values used
  std::size_t infinite_count =
      0;  // +inf values (e.g. "barrier never stops"); mean/sd are +inf if > 0
  double mean = 0, standard_deviation = 0, min = 0, max = 0;
  Interval mean_ci{0, 0};            // Student t, at `confidence`
  double q05 = 0, q50 = 0, q95 = 0;  // Hyndman-Fan type 7
  Interval q05_ci{0, 0}, q50_ci{0, 0},
      q95_ci{0, 0};  // distribution-free, from binomial order statistics
};

struct ExceedanceEstimate {
  double threshold;
  std::size_t exceed_count, count;
  double probability;
  Interval ci;
};

namespace stats {

constexpr double inf = std::numeric_limits<double>::infinity();

// Regularised incomplete beta I_x(a, b), a, b > 0, x in [0,1]: the continued fraction (modified Lentz)
// on the side where it converges fast, the symmetry I_x(a,b) = 1 - I_{1-x}(b,a) on the other.
inline double incomplete_beta(double a, double b, double x) {
  if (x <= 0) return 0.0;
  if (x >= 1) return 1.0;
  if (x > (a + 1) / (a + b + 2)) return 1.0 - incomplete_beta(b, a, 1.0 - x);
  const double log_front =
      a * std::log(x) + b * std::log1p(-x) - (std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b));
  constexpr double tiny = 1e-300, eps = 1e-16;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1);
  if (std::fabs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double f = d;
  const int max_iterations = 200000;
  for (int m = 1; m <= max_iterations; ++m) {
    const double m2 = 2.0 * m;
    double num = m * (b - m) * x / ((a + m2 - 1) * (a + m2));  // even step
    d = 1.0 + num * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + num / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    f *= d * c;
    num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1));  // odd step
    d = 1.0 + num * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + num / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    f *= delta;
    if (std::fabs(delta - 1.0) < eps) break;
  }
  return std::exp(log_front) * f / a;
}

// P(B <= k) for B ~ Binomial(n, p).
inline double binomial_cdf(long long k, long long n, double p) {
  if (k < 0) return 0.0;
  if (k >= n) return 1.0;
  if (p <= 0) return 1.0;
  if (p >= 1) return 0.0;
  return incomplete_beta(static_cast<double>(n - k), static_cast<double>(k + 1), 1.0 - p);
}

// P(T <= t) for Student's t with nu degrees of freedom.
inline double student_t_cdf(double t, double nu) {
  if (std::isinf(t)) return t > 0 ? 1.0 : 0.0;
  const double tail = 0.5 * incomplete_beta(0.5 * nu, 0.5, nu / (nu + t * t));
  return t >= 0 ? 1.0 - tail : tail;
}

// The p-quantile of Student's t (p in (0,1)), by bisection on the CDF.
inline double student_t_quantile(double p, double nu) {
  if (!(p > 0 && p < 1)) throw std::invalid_argument("student_t_quantile: p must be in (0,1)");
  if (nu > 1e7) return normal_quantile(p);
  if (p < 0.5) return -student_t_quantile(1.0 - p, nu);
  double hi = 1.0;
  while (student_t_cdf(hi, nu) < p) hi *= 2;
  double lo = 0.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (student_t_cdf(mid, nu) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

inline void check_confidence(double confidence) {
  if (!(confidence > 0 && confidence < 1))
    throw std::invalid_argument("confidence = " + detail::format_number(confidence) +
                                ": must be in (0, 1)");
}

}  // namespace stats

// The ranks (1-based) of the order statistics that bound the q-quantile with at least `confidence`:
// lower = 0 means -inf, upper = n + 1 means +inf; coverage = P(lower <= B <= upper - 1) exactly
// (n <= 10^6) or by the normal approximation (larger n).
struct OrderStatisticRanks {
  long long lower, upper;
  double coverage;
};

inline OrderStatisticRanks order_statistic_ranks(std::size_t count, double q, double confidence) {
  stats::check_confidence(confidence);
  const long long n = static_cast<long long>(count);
  const double half_alpha = 0.5 * (1.0 - confidence);
  OrderStatisticRanks r{0, n + 1, 1.0};
  if (n <= 1000000) {
    auto F = [&](long long k) { return stats::binomial_cdf(k, n, q); };
    long long lo = 0, hi = n;  // largest l in [0, n] with F(l - 1) <= a/2
    while (lo < hi) {
      const long long mid = lo + (hi - lo + 1) / 2;
      if (F(mid - 1) <= half_alpha)
        lo = mid;
      else
        hi = mid - 1;
    }
    r.lower = lo;
    lo = 1, hi = n + 1;  // smallest u in [1, n + 1] with F(u - 1) >= 1 - a/2
    while (lo < hi) {
      const long long mid = lo + (hi - lo) / 2;
      if (F(mid - 1) >= 1.0 - half_alpha)
        hi = mid;
      else
        lo = mid + 1;
    }
    r.upper = lo;
    r.coverage = F(r.upper - 1) - F(r.lower - 1);
  } else {
    const double z = normal_quantile(1.0 - half_alpha);
    const double mean = static_cast<double>(n) * q,
                 sd = std::sqrt(static_cast<double>(n) * q * (1 - q));
    r.lower = std::max<long long>(0, static_cast<long long>(std::floor(mean - z * sd)));
    r.upper = std::min<long long>(n + 1, static_cast<long long>(std::ceil(mean + z * sd)) + 1);
    auto Fn = [&](long long k) {
      return sd > 0 ? normal_cdf((static_cast<double>(k) + 0.5 - mean) / sd) : 1.0;
    };
    r.coverage = Fn(r.upper - 1) - Fn(r.lower - 1);
  }
  return r;
}

// Hyndman & Fan type 7 quantile of sorted values (may end with +inf).
// Where type 7 reads n sorted values: h = (n - 1) q, between ranks k = floor(h) and k + 1.
struct Type7Position {
  std::size_t k;
  double frac;
};
inline Type7Position type7_position(std::size_t n, double q) {
  const double h = (static_cast<double>(n) - 1.0) * q;
  const auto k = static_cast<std::size_t>(std::floor(h));
  return {k, h - static_cast<double>(k)};
}
// The quantile from the sorted values' accessor at(rank) (ranks k and k + 1 of type7_position, or
// only min(k, n - 1)).
template <class At>
double quantile_type7(std::size_t n, double q, const At& at) {
  const Type7Position p = type7_position(n, q);
  if (p.k + 1 >= n || p.frac == 0.0) return at(std::min(p.k, n - 1));
  const double a = at(p.k), b = at(p.k + 1);
  if (std::isinf(b)) return b;
  return a + p.frac * (b - a);
}
inline double quantile_type7(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) throw std::invalid_argument("quantile of no values");
  return quantile_type7(sorted.size(), q, [&](std::size_t r) { return sorted[r]; });
}

namespace stats {
inline void check_values(const std::vector<double>& values, const char* who) {
  if (values.empty())
    throw std::invalid_argument(std::string(who) + ": no values (every sample failed?)");
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::isnan(values[i]) || values[i] == -inf)
      throw std::invalid_argument(
          std::string(who) + ": values[" + std::to_string(i) +
          "] = " + detail::format_number(values[i]) +
          ": must be a number or +inf (exclude failed samples before the statistics)");
}

// Eight compensated (Kahan) sums: the i-th term added (counting from the first) goes into lane
// i % 8, each lane's compensation is taken back before the lanes are added pairwise. The error
// does not grow with the number of terms as a plain sum's does, and the result depends on the
// terms and their order only, not on how they were handed over (one at a time or in blocks).
// Beside them run eight plain sums: where a compensated lane overflows (its compensation then
// turns it into NaN), total() is theirs, infinite.
class LaneSum {
 public:
  void add(const double x) {
    add_to(static_cast<int>(count_ & 7), x);
    ++count_;
  }
  // add(term(i)) for i in [0, n). The blocks of eight run on local copies of the lanes (the
  // terms' reads cannot alias them: they stay in registers).
  template <class Term>
  void add_terms(const std::size_t n, const Term& term) {
    std::size_t i = 0;
    for (; i < n && (count_ & 7) != 0; ++i) add(term(i));
    double sum[8], lost[8], plain[8];
    for (int l = 0; l < 8; ++l) {
      sum[l] = sum_[l];
      lost[l] = lost_[l];
      plain[l] = plain_[l];
    }
    const std::size_t from = i;
    for (; i + 8 <= n; i += 8)
      for (int l = 0; l < 8; ++l) {
        const double x = term(i + std::size_t(l));
        const double y = x - lost[l], t = sum[l] + y;
        lost[l] = (t - sum[l]) - y;
        sum[l] = t;
        plain[l] += x;
      }
    for (int l = 0; l < 8; ++l) {
      sum_[l] = sum[l];
      lost_[l] = lost[l];
      plain_[l] = plain[l];
    }
    count_ += i - from;
    for (; i < n; ++i) add(term(i));
  }
  double total() const {
    double s[8];
    for (int l = 0; l < 8; ++l) s[l] = sum_[l] - lost_[l];
    const double t = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
    if (std::isfinite(t)) return t;
    return ((plain_[0] + plain_[1]) + (plain_[2] + plain_[3])) +
           ((plain_[4] + plain_[5]) + (plain_[6] + plain_[7]));
  }

 private:
  void add_to(const int l, const double x) {
    const double y = x - lost_[l], t = sum_[l] + y;
    lost_[l] = (t - sum_[l]) - y;
    sum_[l] = t;
    plain_[l] += x;
  }
  double sum_[8] = {}, lost_[8] = {}, plain_[8] = {};
  std::uint64_t count_ = 0;
};

// The mean and the standard deviation's sums: the sum of the values, and about a shift K the
// sums of (x - K)^2 and of (x - K), whence var = (ss - c^2 / n) / (n - 1) (the corrected
// two-pass formula, exact for any K in exact arithmetic; in floating point its error grows with
// (mean - K)^2 / var). K is the mean of the first `shift_values` values (of all, where there are
// no more: the two-pass algorithm itself), so the sums can run as the values arrive, once those
// first values are in.
constexpr std::size_t kShiftValues = std::size_t{1} << 18;

struct Moments {
  double mean, standard_deviation;
};

inline Moments moments_from_sums(const std::size_t n, const double sum, const double ss,
                                 const double c) {
  Moments m{sum / static_cast<double>(n), std::numeric_limits<double>::quiet_NaN()};
  if (n >= 2) {
    const double var = (ss - c * c / static_cast<double>(n)) / static_cast<double>(n - 1);
    m.standard_deviation = std::sqrt(std::max(0.0, var));
  }
  return m;
}

// The ranks describe() reads: the extremes, and per quantile the two of type 7 and its
// interval's bounds; ascending, without repeats.
struct DescribeRanks {
  std::size_t rank[14];
  std::size_t count;
  OrderStatisticRanks bounds[3];
  static constexpr double q[3] = {0.05, 0.50, 0.95};
};

}  // namespace stats

inline stats::DescribeRanks describe_ranks(const std::size_t n, const double confidence) {
  stats::DescribeRanks r;
  std::size_t* const ranks = r.rank;
  std::size_t count = 0;
  ranks[count++] = 0;
  ranks[count++] = n - 1;
  for (int j = 0; j < 3; ++j) {
    const std::size_t k = type7_position(n, r.q[j]).k;
    ranks[count++] = std::min(k, n - 1);
    ranks[count++] = std::min(k + 1, n - 1);
    r.bounds[j] = order_statistic_ranks(n, r.q[j], confidence);
    if (r.bounds[j].lower >= 1) ranks[count++] = static_cast<std::size_t>(r.bounds[j].lower - 1);
    if (r.bounds[j].upper <= static_cast<long long>(n))
      ranks[count++] = static_cast<std::size_t>(r.bounds[j].upper - 1);
  }
  for (std::size_t i = 1; i < count; ++i)  // ascending (an insertion sort of at most 14)
    for (std::size_t j = i; j > 0 && ranks[j - 1] > ranks[j]; --j)
      std::swap(ranks[j - 1], ranks[j]);
  r.count = static_cast<std::size_t>(std::unique(ranks, ranks + count) - ranks);
  return r;
}

// OutputStatistics of n values (infinite of them +inf) from their moments (ignored where some
// are infinite) and the values at the ranks of describe_ranks (at_rank[j] at rank r.rank[j]).
inline OutputStatistics describe_from(const std::size_t n, const std::size_t infinite,
                                      const stats::Moments& m, const stats::DescribeRanks& r,
                                      const double* const at_rank, const double confidence) {
  const auto at = [&](const std::size_t rank) {
    return at_rank[std::lower_bound(r.rank, r.rank + r.count, rank) - r.rank];
  };
  OutputStatistics s;
  s.count = n;
  s.min = at(0);
  s.max = at(n - 1);
  s.infinite_count = infinite;
  if (infinite > 0) {
    s.mean = s.standard_deviation = stats::inf;
    s.mean_ci = {stats::inf, stats::inf};
  } else {
    s.mean = m.mean;
    s.standard_deviation = m.standard_deviation;
    if (n >= 2) {
      const double t =
          stats::student_t_quantile(0.5 + 0.5 * confidence, static_cast<double>(n - 1));
      const double half = t * s.standard_deviation / std::sqrt(static_cast<double>(n));
      s.mean_ci = {s.mean - half, s.mean + half};
    } else {
      s.mean_ci = {-stats::inf, stats::inf};
    }
  }
  double quantile[3];
  Interval interval[3];
  for (int j = 0; j < 3; ++j) {
    quantile[j] = quantile_type7(n, r.q[j], at);
    interval[j].low =
        r.bounds[j].lower <= 0 ? -stats::inf : at(static_cast<std::size_t>(r.bounds[j].lower - 1));
    interval[j].high = r.bounds[j].upper > static_cast<long long>(n)
                           ? stats::inf
                           : at(static_cast<std::size_t>(r.bounds[j].upper - 1));
  }
  s.q05 = quantile[0];
  s.q50 = quantile[1];
  s.q95 = quantile[2];
  s.q05_ci = interval[0];
  s.q50_ci = interval[1];
  s.q95_ci = interval[2];
  return s;
}

// describe() of `values`, left as they are, with `scratch` as the buffers of the order
// statistics (order_statistics.hpp): a caller that describes many columns keeps them. The
// quantiles and their intervals read a dozen order statistics, selected rather than sorted for;
// the sums of the mean and the standard deviation run over the values in their order
// (stats::LaneSum, about the mean of the first `shift_values` values: stats::kShiftValues), so
// the results do not depend on the thread count, and a column fed a batch at a time
// (sweeps/column_accumulator.hpp) gets the same.
inline OutputStatistics describe(const std::vector<double>& values, OrderScratch& scratch,
                                 double confidence = 0.95,
                                 std::size_t shift_values = stats::kShiftValues) {
  stats::check_values(values, "describe");
  stats::check_confidence(confidence);
  const std::size_t n = values.size();
  const double* const v = values.data();
  const stats::DescribeRanks r = describe_ranks(n, confidence);
  double at_rank[14];
  order_statistics(v, n, r.rank, r.count, at_rank, scratch);
  std::size_t infinite = 0;
  for (std::size_t i = 0; i < n; ++i) infinite += v[i] == stats::inf;
  stats::Moments m{stats::inf, stats::inf};
  if (infinite == 0) {
    const std::size_t p = std::min(n, std::max<std::size_t>(shift_values, 1));
    stats::LaneSum sum, ss, c;
    sum.add_terms(n, [v](std::size_t i) { return v[i]; });
    double k = sum.total() / static_cast<double>(n);
    if (p < n) {
      stats::LaneSum first;
      first.add_terms(p, [v](std::size_t i) { return v[i]; });
      k = first.total() / static_cast<double>(p);
    }
    ss.add_terms(n, [v, k](std::size_t i) { return (v[i] - k) * (v[i] - k); });
    c.add_terms(n, [v, k](std::size_t i) { return v[i] - k; });
    m = stats::moments_from_sums(n, sum.total(), ss.total(), c.total());
  }
  return describe_from(n, infinite, m, r, at_rank, confidence);
}

// Throws std::invalid_argument on NaN or -inf or empty input (the caller excludes failed samples), and
// for a confidence outside (0,1).
inline OutputStatistics describe(const std::vector<double>& values, double confidence = 0.95) {
  OrderScratch scratch;
  return describe(values, scratch, confidence);
}

// P(value > threshold) from the count of values above it among `count`, with the Wilson score
// interval at `confidence` (count >= 1).
inline ExceedanceEstimate exceedance_from_counts(const double threshold,
                                                 const std::size_t exceed_count,
                                                 const std::size_t count, const double confidence) {
  ExceedanceEstimate e{threshold, exceed_count, count, 0.0, {0, 0}};
  const double n = static_cast<double>(e.count), k = static_cast<double>(e.exceed_count);
  e.probability = k / n;
  const double z = normal_quantile(0.5 + 0.5 * confidence), z2 = z * z;
  const double denom = 1.0 + z2 / n;
  const double center = (e.probability + z2 / (2 * n)) / denom;
  const double half =
      z * std::sqrt(e.probability * (1 - e.probability) / n + z2 / (4 * n * n)) / denom;
  e.ci.low = e.exceed_count == 0 ? 0.0 : std::max(0.0, center - half);
  e.ci.high = e.exceed_count == e.count ? 1.0 : std::min(1.0, center + half);
  return e;
}

// P(value > threshold), Wilson score interval at `confidence`. Same input rules as describe().
inline ExceedanceEstimate exceedance(const std::vector<double>& values, double threshold,
                                     double confidence = 0.95) {
  stats::check_values(values, "exceedance");
  stats::check_confidence(confidence);
  if (std::isnan(threshold))
    throw std::invalid_argument("exceedance: threshold = nan: must be a number");
  std::size_t above = 0;
  for (double v : values) above += v > threshold;
  return exceedance_from_counts(threshold, above, values.size(), confidence);
}

}  // namespace lsi::sweeps
