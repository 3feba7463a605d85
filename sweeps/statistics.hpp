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
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sweeps/distribution.hpp"
#include "sweeps/huge_pages.hpp"
#include "sweeps/normal_distribution.hpp"

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
inline double quantile_type7(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) throw std::invalid_argument("quantile of no values");
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q;
  const auto k = static_cast<std::size_t>(std::floor(h));
  const double frac = h - static_cast<double>(k);
  if (k + 1 >= sorted.size() || frac == 0.0) return sorted[std::min(k, sorted.size() - 1)];
  const double a = sorted[k], b = sorted[k + 1];
  if (std::isinf(b)) return b;
  return a + frac * (b - a);
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
// Sorts values (no NaN) ascending: the same sequence as std::sort with operator< (the only
// freedom std::sort has is the relative order of -0 and +0, which compare equal; here -0 comes
// first), so every statistic computed from it is bitwise the same. An LSD radix sort, one byte a
// pass, on the order-preserving bit pattern of the doubles (sign bit set for >= +0, all bits
// flipped for negatives), kept in the values' own storage and in `scratch` in turn; a pass whose
// byte is the same for all values (e.g. the sign and the top exponent bits of outputs of one
// magnitude) is skipped. ~5x faster than std::sort at 1e7 values (docs/notes/performance.md,
// "Sweeps"); small inputs go to std::sort. `scratch` is resized to the values' size at least:
// a caller that sorts many columns keeps it, so that its memory is not new each time.
inline void sort_values(std::vector<double>& values, std::vector<std::uint64_t>& scratch) {
  const std::size_t n = values.size();
  if (n < 4096) {
    std::sort(values.begin(), values.end());
    return;
  }
  if (scratch.size() < n) {
    scratch.clear();
    reserve_on_huge_pages(scratch, n);
    scratch.resize(n);
  }
  constexpr std::uint64_t sign = std::uint64_t{1} << 63;
  // The keys are 8-byte patterns in either buffer, read and written with memcpy.
  auto load = [](const unsigned char* p, std::size_t i) {
    std::uint64_t u;
    std::memcpy(&u, p + 8 * i, sizeof u);
    return u;
  };
  auto store = [](unsigned char* p, std::size_t i, std::uint64_t u) {
    std::memcpy(p + 8 * i, &u, sizeof u);
  };
  unsigned char* const own = reinterpret_cast<unsigned char*>(values.data());
  unsigned char* const other = reinterpret_cast<unsigned char*>(scratch.data());
  std::array<std::array<std::size_t, 256>, 8> count{};
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t u = load(own, i);
    u = (u & sign) ? ~u : (u | sign);
    store(own, i, u);
    for (int byte = 0; byte < 8; ++byte) ++count[byte][(u >> (8 * byte)) & 0xFF];
  }
  unsigned char* from = own;
  unsigned char* to = other;
  for (int byte = 0; byte < 8; ++byte) {
    auto& c = count[byte];
    if (c[(load(from, 0) >> (8 * byte)) & 0xFF] == n) continue;  // all values share this byte
    std::size_t offset[256], running = 0;
    for (int k = 0; k < 256; ++k) {
      offset[k] = running;
      running += c[k];
    }
    const int shift = 8 * byte;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t u = load(from, i);
      store(to, offset[(u >> shift) & 0xFF]++, u);
    }
    std::swap(from, to);
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t u = load(from, i);
    u = (u & sign) ? (u & ~sign) : ~u;
    store(own, i, u);
  }
}

inline void sort_values(std::vector<double>& values) {
  std::vector<std::uint64_t> scratch;
  sort_values(values, scratch);
}

inline Interval quantile_interval(const std::vector<double>& sorted, double q, double confidence) {
  const auto r = order_statistic_ranks(sorted.size(), q, confidence);
  const double low = r.lower <= 0 ? -inf : sorted[static_cast<std::size_t>(r.lower - 1)];
  const double high = r.upper > static_cast<long long>(sorted.size())
                          ? inf
                          : sorted[static_cast<std::size_t>(r.upper - 1)];
  return {low, high};
}
}  // namespace stats

// describe() of `values`, sorted in place (they are left sorted) with `scratch` as the sort's
// buffer (stats::sort_values): a caller that describes many columns keeps both.
inline OutputStatistics describe_in_place(std::vector<double>& values,
                                          std::vector<std::uint64_t>& scratch,
                                          double confidence = 0.95) {
  stats::check_values(values, "describe");
  stats::check_confidence(confidence);
  stats::sort_values(values, scratch);
  OutputStatistics s;
  const std::size_t n = values.size();
  s.count = n;
  s.infinite_count = static_cast<std::size_t>(std::count(values.begin(), values.end(), stats::inf));
  s.min = values.front();
  s.max = values.back();
  if (s.infinite_count > 0) {
    s.mean = s.standard_deviation = stats::inf;
    s.mean_ci = {stats::inf, stats::inf};
  } else {
    double sum = 0;
    for (double v : values) sum += v;
    s.mean = sum / static_cast<double>(n);
    double ss = 0,
           c = 0;  // two-pass, with the compensation term of the corrected two-pass algorithm
    for (double v : values) {
      ss += (v - s.mean) * (v - s.mean);
      c += v - s.mean;
    }
    if (n >= 2) {
      const double var = (ss - c * c / static_cast<double>(n)) / static_cast<double>(n - 1);
      s.standard_deviation = std::sqrt(std::max(0.0, var));
      const double t =
          stats::student_t_quantile(0.5 + 0.5 * confidence, static_cast<double>(n - 1));
      const double half = t * s.standard_deviation / std::sqrt(static_cast<double>(n));
      s.mean_ci = {s.mean - half, s.mean + half};
    } else {
      s.standard_deviation = std::numeric_limits<double>::quiet_NaN();
      s.mean_ci = {-stats::inf, stats::inf};
    }
  }
  s.q05 = quantile_type7(values, 0.05);
  s.q50 = quantile_type7(values, 0.50);
  s.q95 = quantile_type7(values, 0.95);
  s.q05_ci = stats::quantile_interval(values, 0.05, confidence);
  s.q50_ci = stats::quantile_interval(values, 0.50, confidence);
  s.q95_ci = stats::quantile_interval(values, 0.95, confidence);
  return s;
}

// Throws std::invalid_argument on NaN or -inf or empty input (the caller excludes failed samples), and
// for a confidence outside (0,1).
inline OutputStatistics describe(std::vector<double> values, double confidence = 0.95) {
  std::vector<std::uint64_t> scratch;
  return describe_in_place(values, scratch, confidence);
}

// P(value > threshold), Wilson score interval at `confidence`. Same input rules as describe().
inline ExceedanceEstimate exceedance(const std::vector<double>& values, double threshold,
                                     double confidence = 0.95) {
  stats::check_values(values, "exceedance");
  stats::check_confidence(confidence);
  if (std::isnan(threshold))
    throw std::invalid_argument("exceedance: threshold = nan: must be a number");
  ExceedanceEstimate e{threshold, 0, values.size(), 0.0, {0, 0}};
  for (double v : values)
    if (v > threshold) ++e.exceed_count;
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

}  // namespace lsi::sweeps
