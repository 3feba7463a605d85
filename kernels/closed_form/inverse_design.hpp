// Inverse use of a model (the paper's section 4.3): the minimum barrier mass per metre for which
// the final displacement stays within a tolerable value. `displacement_of_mass(m)` is any model's
// final displacement (m) as a function of the barrier mass (kg/m). The mass range is scanned on a
// logarithmic grid, from the heaviest mass down to the first that fails, and that crossing is
// refined by bisection, so the answer is the smallest mass above which every scanned mass is
// acceptable, even if the model is not monotone.
#pragma once
#include <cmath>

namespace lsi {

struct MassForDisplacement {
  enum class Status { Found, AnyMassWorks, NoMassInRange };
  Status status = Status::NoMassInRange;
  double mass = 0.0;          // kg/m (Found: the minimum; AnyMassWorks: the lower scan bound)
  double displacement = 0.0;  // m, at `mass`
  int evaluations = 0;
};

template <class DisplacementOfMass>
MassForDisplacement minimum_barrier_mass(DisplacementOfMass&& displacement_of_mass,
                                         double max_displacement, double mass_low = 1.0,
                                         double mass_high = 1e9, int scan_points = 121,
                                         double relative_tolerance = 1e-10) {
  MassForDisplacement out;
  auto ok = [&](double m) {
    ++out.evaluations;
    return displacement_of_mass(m) <= max_displacement;
  };
  const double l0 = std::log(mass_low), l1 = std::log(mass_high);
  // Last scanned mass that fails: the scan from the heaviest down to the first failure, which
  // never evaluates the lighter masses (the lightest barriers slide longest, their models cost
  // most).
  int last_fail = -1;
  for (int k = scan_points - 1; k >= 0; --k) {
    const double m = std::exp(l0 + (l1 - l0) * k / (scan_points - 1));
    if (!ok(m)) {
      last_fail = k;
      break;
    }
  }
  if (last_fail == scan_points - 1) {
    out.mass = mass_high;
    out.displacement = displacement_of_mass(mass_high);
    return out;
  }
  if (last_fail < 0) {
    out.status = MassForDisplacement::Status::AnyMassWorks;
    out.mass = mass_low;
    out.displacement = displacement_of_mass(mass_low);
    return out;
  }
  double lo = l0 + (l1 - l0) * last_fail / (scan_points - 1);        // fails
  double hi = l0 + (l1 - l0) * (last_fail + 1) / (scan_points - 1);  // passes
  while (hi - lo > relative_tolerance) {
    const double mid = 0.5 * (lo + hi);
    (ok(std::exp(mid)) ? hi : lo) = mid;
  }
  out.status = MassForDisplacement::Status::Found;
  out.mass = std::exp(hi);
  out.displacement = displacement_of_mass(out.mass);
  return out;
}

}  // namespace lsi
