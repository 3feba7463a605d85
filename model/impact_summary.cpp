#include "model/impact_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace lsi {

double impulse_until(const std::vector<double>& time, const std::vector<double>& force, double t) {
  double j = 0.0;
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (t <= time[i - 1]) break;
    j += force[i] * (std::min(t, time[i]) - time[i - 1]);
  }
  return j;
}

WindowedPeak windowed_peak(const std::vector<double>& time, const std::vector<double>& force,
                           double window) {
  WindowedPeak best;
  const std::size_t n = time.size();
  if (n < 2) return best;
  // The cumulative impulse J(t) is piecewise linear with breakpoints at the output times, so
  // (J(t + w) - J(t)) / w is piecewise linear in t too and its maximum lies where t or t + w is
  // an output time.
  std::vector<double> J(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) J[i] = J[i - 1] + force[i] * (time[i] - time[i - 1]);
  const double t0 = time.front(), t1 = time.back();
  const double w = std::min(window, t1 - t0);
  if (!(w > 0.0)) return best;
  auto J_at = [&](double t) {
    const std::size_t k = std::upper_bound(time.begin(), time.end(), t) - time.begin();
    if (k == 0) return 0.0;
    if (k >= n) return J[n - 1];
    return J[k - 1] + force[k] * (t - time[k - 1]);
  };
  best.force = -1e300;
  auto consider = [&](double start) {
    start = std::max(t0, std::min(start, t1 - w));  // t1 - w may round below t0
    const double mean = (J_at(start + w) - J_at(start)) / w;
    if (mean > best.force) {
      best.force = mean;
      best.time = start + 0.5 * w;
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    consider(time[i]);
    consider(time[i] - w);
  }
  return best;
}

ImpactDuration impact_duration(const std::vector<double>& time, const std::vector<double>& force) {
  ImpactDuration d;
  const std::size_t n = force.size();
  if (n == 0) return d;
  const std::size_t peak = std::max_element(force.begin(), force.end()) - force.begin();
  const std::size_t tail = std::max<std::size_t>(1, n / 20);
  for (std::size_t i = n - tail; i < n; ++i) d.final_force += force[i] / tail;
  d.duration = time[peak];
  for (std::size_t i = peak; i < n; ++i)
    if (std::abs(force[i] - d.final_force) > 0.1 * force[peak]) d.duration = time[i];
  return d;
}

}  // namespace lsi
