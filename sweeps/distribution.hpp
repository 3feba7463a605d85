// Marginal distributions of the uncertain inputs of a sweep: the host-side description built by the
// study parser (DistributionSpec), its validation, and the device-side form (Marginal) whose
// quantile function turns a uniform u in (0,1) into the input's value inside a Kokkos kernel.
//
// Quantiles (inverse CDFs, so that every design and the Gaussian copula act on uniforms):
//   Constant         value.
//   Uniform          min + u (max - min).
//   Normal           mean + sd z, with z = Phi^-1(u) (the copula's normal score is used directly).
//   Lognormal        exp(mu + sigma z) with sigma^2 = ln(1 + (sd/mean)^2), mu = ln(mean) - sigma^2/2:
//                    `mean` and `sd` are those of the variable itself, not of its logarithm.
//   TruncatedNormal  the parent Normal(mean, sd) restricted to [min, max] (either may be infinite):
//                    x = mean + sd Phi^-1(Phi(a) + u (Phi(b) - Phi(a))) with a, b the standardised
//                    bounds. When a > 0 the whole interval lies in the upper tail, where Phi(a) is
//                    1 - tiny and loses its digits; the complement is used there instead:
//                    x = mean - sd Phi^-1(Q(a) - u (Q(a) - Q(b))), Q = 1 - Phi computed by erfc. (When
//                    b < 0, Phi itself is accurate.) The result is clamped to [min, max] against rounding.
//   Discrete         values with weights (empty = equal): the cumulative weights, normalised so that
//                    the last is exactly 1, and the first k with u <= cdf[k] (binary search, on device).
//                    A zero weight is allowed and never drawn.
// All of these are monotone in u, so the Gaussian copula of the sampler (sampler.hpp) works for
// every marginal, discrete included.
#pragma once
#include <Kokkos_Core.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sweeps/normal_distribution.hpp"

namespace lsi::sweeps {

enum class DistributionKind : int {
  Constant,
  Uniform,
  Normal,
  Lognormal,
  TruncatedNormal,
  Discrete
};

// Host-side description, built by the study parser.
struct DistributionSpec {
  DistributionKind kind = DistributionKind::Constant;
  // Constant: value. Uniform: min,max. Normal: mean,sd. Lognormal: mean,sd of the variable itself
  // (not of its log; converted inside). TruncatedNormal: mean,sd of the parent normal and min,max.
  double value = 0, min = 0, max = 0, mean = 0, sd = 0;
  std::vector<double> values,
      weights;  // Discrete (weights empty = equal); also the grid points of the Grid design
};

inline const char* to_string(DistributionKind k) {
  switch (k) {
    case DistributionKind::Constant:
      return "constant";
    case DistributionKind::Uniform:
      return "uniform";
    case DistributionKind::Normal:
      return "normal";
    case DistributionKind::Lognormal:
      return "lognormal";
    case DistributionKind::TruncatedNormal:
      return "truncated_normal";
    case DistributionKind::Discrete:
      return "discrete";
  }
  return "unknown";
}

namespace detail {
// The shortest decimal form that reads back as the same double ("0.1", "-1", "3e+20", "inf", "nan").
inline std::string format_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  for (int precision = 1; precision <= 17; ++precision) {
    std::ostringstream s;
    s.precision(precision);
    s << x;
    // strtod, not stod: stod throws out_of_range on a subnormal (ERANGE), and the message of
    // an error about a subnormal input must still be written (found by fuzzing).
    if (std::strtod(s.str().c_str(), nullptr) == x) return s.str();
  }
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

[[noreturn]] inline void invalid(const std::string& what) { throw std::invalid_argument(what); }

inline void require_finite(const char* name, double x) {
  if (!std::isfinite(x)) invalid(std::string(name) + " = " + format_number(x) + ": must be finite");
}
inline void require_positive(const char* name, double x) {
  require_finite(name, x);
  if (!(x > 0)) invalid(std::string(name) + " = " + format_number(x) + ": must be > 0");
}
inline void require_ordered(double lo, double hi) {
  if (!(lo < hi))
    invalid("min = " + format_number(lo) + " >= max = " + format_number(hi) +
            ": must be min < max");
}

// The probabilities that bound a truncated normal's quantile: (p_lo, p_hi) of the lower tail, or of
// the upper tail (complements) when the whole interval lies above the mean.
struct TruncationBounds {
  double p_lo, p_hi;
  bool upper_tail;
};
inline TruncationBounds truncation_bounds(double mean, double sd, double min, double max) {
  const double a = (min - mean) / sd, b = (max - mean) / sd;
  if (a > 0) return {normal_ccdf(a), normal_ccdf(b), true};
  return {normal_cdf(a), normal_cdf(b), false};
}
}  // namespace detail

// Throws std::invalid_argument naming the offending parameter and its allowed range
// ("sd = -1: must be > 0", "min = 3 >= max = 2: must be min < max", "weights: 2 given for 3 values");
// the caller prefixes the input's JSON path.
inline void validate(const DistributionSpec& s) {
  using detail::format_number;
  using detail::invalid;
  for (std::size_t i = 0; i < s.values.size(); ++i)
    if (!std::isfinite(s.values[i]))
      invalid("values[" + std::to_string(i) + "] = " + format_number(s.values[i]) +
              ": must be finite");
  switch (s.kind) {
    case DistributionKind::Constant:
      detail::require_finite("value", s.value);
      break;
    case DistributionKind::Uniform:
      detail::require_finite("min", s.min);
      detail::require_finite("max", s.max);
      detail::require_ordered(s.min, s.max);
      break;
    case DistributionKind::Normal:
      detail::require_finite("mean", s.mean);
      detail::require_positive("sd", s.sd);
      break;
    case DistributionKind::Lognormal:
      detail::require_finite("mean", s.mean);
      if (!(s.mean > 0))
        invalid("mean = " + format_number(s.mean) +
                ": must be > 0 (a lognormal variable is positive)");
      detail::require_positive("sd", s.sd);
      break;
    case DistributionKind::TruncatedNormal: {
      detail::require_finite("mean", s.mean);
      detail::require_positive("sd", s.sd);
      if (std::isnan(s.min)) invalid("min = nan: must be a number (-inf allowed)");
      if (std::isnan(s.max)) invalid("max = nan: must be a number (inf allowed)");
      detail::require_ordered(s.min, s.max);
      const auto t = detail::truncation_bounds(s.mean, s.sd, s.min, s.max);
      const double mass = t.upper_tail ? t.p_lo - t.p_hi : t.p_hi - t.p_lo;
      if (!(mass > 1e-290))
        invalid("min = " + format_number(s.min) + ", max = " + format_number(s.max) +
                ": the interval holds no probability of Normal(mean = " + format_number(s.mean) +
                ", sd = " + format_number(s.sd) + ") (it lies more than 36 sd from the mean)");
      break;
    }
    case DistributionKind::Discrete: {
      if (s.values.empty())
        invalid("values: none given: a discrete distribution needs at least one value");
      if (!s.weights.empty()) {
        if (s.weights.size() != s.values.size())
          invalid("weights: " + std::to_string(s.weights.size()) + " given for " +
                  std::to_string(s.values.size()) + " values");
        double sum = 0;
        for (std::size_t i = 0; i < s.weights.size(); ++i) {
          if (!(std::isfinite(s.weights[i]) && s.weights[i] >= 0))
            invalid("weights[" + std::to_string(i) + "] = " + format_number(s.weights[i]) +
                    ": must be finite and >= 0");
          sum += s.weights[i];
        }
        if (!(sum > 0)) invalid("weights: all zero: at least one must be > 0");
      }
      break;
    }
    default:
      invalid("kind = " + std::to_string(static_cast<int>(s.kind)) + ": not a distribution kind");
  }
}

// Device-side form of one marginal: plain data, parameters prepared on the host. The discrete table
// (values and cumulative probabilities) lives in the sampler's Views, at [offset, offset + count).
struct Marginal {
  DistributionKind kind = DistributionKind::Constant;
  double a = 0,
         b = 0;  // Constant: value. Uniform: min, width. Normal: mean, sd. Lognormal: mu, sigma.
                 // TruncatedNormal: mean, sd.
  double p_lo = 0,
         p_hi = 0;        // TruncatedNormal: the bounding probabilities (complements if upper_tail)
  double lo = 0, hi = 0;  // TruncatedNormal: min, max (the clamp)
  int upper_tail = 0;
  std::uint32_t offset = 0, count = 0;  // Discrete
};

// Prepares the device form of a validated spec; a Discrete spec appends its table to `values` and
// `cdf` (host vectors that the sampler copies to its memory space).
inline Marginal prepare_marginal(const DistributionSpec& s, std::vector<double>& values,
                                 std::vector<double>& cdf) {
  validate(s);
  Marginal m;
  m.kind = s.kind;
  switch (s.kind) {
    case DistributionKind::Constant:
      m.a = s.value;
      break;
    case DistributionKind::Uniform:
      m.a = s.min;
      m.b = s.max - s.min;
      m.lo = s.min;
      m.hi = s.max;
      break;
    case DistributionKind::Normal:
      m.a = s.mean;
      m.b = s.sd;
      break;
    case DistributionKind::Lognormal: {
      const double cv = s.sd / s.mean;
      const double sigma2 = std::log1p(cv * cv);
      m.a = std::log(s.mean) - 0.5 * sigma2;
      m.b = std::sqrt(sigma2);
      break;
    }
    case DistributionKind::TruncatedNormal: {
      const auto t = detail::truncation_bounds(s.mean, s.sd, s.min, s.max);
      m.a = s.mean;
      m.b = s.sd;
      m.p_lo = t.p_lo;
      m.p_hi = t.p_hi;
      m.upper_tail = t.upper_tail ? 1 : 0;
      m.lo = s.min;
      m.hi = s.max;
      break;
    }
    case DistributionKind::Discrete: {
      m.offset = static_cast<std::uint32_t>(values.size());
      m.count = static_cast<std::uint32_t>(s.values.size());
      double total = 0;
      for (std::size_t i = 0; i < s.values.size(); ++i)
        total += s.weights.empty() ? 1.0 : s.weights[i];
      double running = 0;
      for (std::size_t i = 0; i < s.values.size(); ++i) {
        running += s.weights.empty() ? 1.0 : s.weights[i];
        values.push_back(s.values[i]);
        cdf.push_back(running / total);
      }
      // The last value of non-zero weight ends the table at exactly 1 (not 1 - rounding), so that
      // every u in (0,1) finds a value; zero-weight values after it are never reached.
      std::size_t last = s.values.size() - 1;
      while (last > 0 && !s.weights.empty() && s.weights[last] == 0) --last;
      for (std::size_t k = last; k < s.values.size(); ++k) cdf[m.offset + k] = 1.0;
      break;
    }
  }
  return m;
}

// The steps of the marginals' quantiles that marginal_quantile and marginal_quantile_each share.
namespace detail {
KOKKOS_INLINE_FUNCTION double clamp_to(double x, double lo, double hi) {
  return x < lo ? lo : (x > hi ? hi : x);
}
// Uniform: min + u (max - min), clamped against rounding.
KOKKOS_INLINE_FUNCTION double uniform_value(const Marginal& m, double u) {
  return clamp_to(m.a + u * m.b, m.lo, m.hi);
}
// TruncatedNormal: the parent's probability (its complement in the upper tail) that u maps to,
// and the value at that probability's normal quantile z.
KOKKOS_INLINE_FUNCTION double truncated_probability(const Marginal& m, double u) {
  return m.upper_tail ? m.p_lo - u * (m.p_lo - m.p_hi) : m.p_lo + u * (m.p_hi - m.p_lo);
}
KOKKOS_INLINE_FUNCTION double truncated_value(const Marginal& m, double z) {
  return clamp_to(m.upper_tail ? m.a - m.b * z : m.a + m.b * z, m.lo, m.hi);
}
// Discrete: the first k in [0, count) with u <= cdf[offset + k] (binary search).
KOKKOS_INLINE_FUNCTION double discrete_value(const Marginal& m, double u, const double* values,
                                             const double* cdf) {
  std::uint32_t first = 0, n = m.count;
  while (n > 0) {
    const std::uint32_t half = n / 2;
    if (cdf[m.offset + first + half] < u) {
      first += half + 1;
      n -= half + 1;
    } else {
      n = half;
    }
  }
  if (first >= m.count) first = m.count - 1;
  return values[m.offset + first];
}
}  // namespace detail

// The marginal's value at the uniform u in (0,1). `z` is the normal score Phi^-1(u) when the caller
// has it (the copula computes it; pass has_z = false otherwise): Normal and Lognormal then use it
// directly instead of recomputing Phi^-1(u). `values`/`cdf` are the discrete table.
KOKKOS_INLINE_FUNCTION double marginal_quantile(const Marginal& m, double u, double z, bool has_z,
                                                const double* values, const double* cdf) {
  switch (m.kind) {
    case DistributionKind::Constant:
      return m.a;
    case DistributionKind::Uniform:
      return detail::uniform_value(m, u);
    case DistributionKind::Normal:
      return m.a + m.b * (has_z ? z : normal_quantile(u));
    case DistributionKind::Lognormal:
      return detail::exp(m.a + m.b * (has_z ? z : normal_quantile(u)));
    case DistributionKind::TruncatedNormal:
      return detail::truncated_value(m, normal_quantile(detail::truncated_probability(m, u)));
    case DistributionKind::Discrete:
      return detail::discrete_value(m, u, values, cdf);
  }
  return detail::quiet_nan();
}

// marginal_quantile for n uniforms u[0..n) (scores z[0..n) when has_z) into out[0..n) (host code),
// the same bits for each: the kind chosen once, and each step a loop over the n values, which
// GCC vectorises where it calls no library function (the Uniform, Normal and truncated normal
// arithmetic, Phi^-1 but its tails' logarithms: normal_quantile_each). out may be u or z.
inline void marginal_quantile_each(const Marginal& m, const double* u, const double* z, bool has_z,
                                   const double* values, const double* cdf, double* out, int n) {
  switch (m.kind) {
    case DistributionKind::Constant:
      for (int k = 0; k < n; ++k) out[k] = m.a;
      return;
    case DistributionKind::Uniform:
#pragma GCC ivdep
      for (int k = 0; k < n; ++k) out[k] = detail::uniform_value(m, u[k]);
      return;
    case DistributionKind::Normal:
    case DistributionKind::Lognormal: {
      if (!has_z) {
        normal_quantile_each(u, out, n);
        z = out;
      }
      if (m.kind == DistributionKind::Normal) {
#pragma GCC ivdep
        for (int k = 0; k < n; ++k) out[k] = m.a + m.b * z[k];
      } else {
        for (int k = 0; k < n; ++k) out[k] = detail::exp(m.a + m.b * z[k]);
      }
      return;
    }
    case DistributionKind::TruncatedNormal:
#pragma GCC ivdep
      for (int k = 0; k < n; ++k) out[k] = detail::truncated_probability(m, u[k]);
      normal_quantile_each(out, out, n);
#pragma GCC ivdep
      for (int k = 0; k < n; ++k) out[k] = detail::truncated_value(m, out[k]);
      return;
    case DistributionKind::Discrete:
      if (m.count > 32) {
        for (int k = 0; k < n; ++k) out[k] = detail::discrete_value(m, u[k], values, cdf);
        return;
      }
      // A short table: the index counted (how many cumulative weights lie below u), which is
      // the binary search's answer since the table is sorted, and a loop without branches.
      for (int begin = 0; begin < n; begin += 64) {
        const int count = n - begin < 64 ? n - begin : 64;
        int below[64];
        for (int k = 0; k < count; ++k) below[k] = 0;
        for (std::uint32_t j = 0; j < m.count; ++j) {
          const double c = cdf[m.offset + j];
#pragma GCC ivdep
          for (int k = 0; k < count; ++k) below[k] += c < u[begin + k] ? 1 : 0;
        }
        const int last = static_cast<int>(m.count) - 1;
#pragma GCC ivdep
        for (int k = 0; k < count; ++k)
          out[begin + k] =
              values[m.offset + static_cast<std::uint32_t>(below[k] < last ? below[k] : last)];
      }
      return;
  }
  for (int k = 0; k < n; ++k) out[k] = detail::quiet_nan();
}

}  // namespace lsi::sweeps
