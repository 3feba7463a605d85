// Grid convergence of one output over three resolutions: observed order of accuracy, Richardson
// extrapolation, Roache's grid convergence index (GCI) and the asymptotic-range check, following
// the procedure of Celik et al. (2008), "Procedure for estimation and reporting of uncertainty due
// to discretization in CFD applications", J. Fluids Eng. 130(7), 078001 (docs/vv/accuracy.md).
//
// h is the representative spacing of a run (cell size, point spacing, time-step factor): any
// quantity proportional to the discretisation's step, so that the error behaves as C h^p. The
// refinement ratios need not be equal: the observed order then solves
//   p = | ln|e32/e21| + ln((r21^p - s) / (r32^p - s)) | / ln r21,   s = sign(e32/e21),
// by fixed-point iteration (e21 = phi2 - phi1, e32 = phi3 - phi2, r21 = h2/h1, r32 = h3/h2,
// 1 the finest run). Safety factor 1.25 (three grids).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace lsi::sweeps {

enum class Convergence {
  Monotonic,    // e32/e21 > 0 and |e32| > |e21|: converging without oscillation
  Oscillatory,  // e32/e21 < 0: the order and the extrapolation are not trustworthy
  Diverging,    // e32/e21 > 0 but the differences grow with refinement
  Converged,    // e21 = 0 (or both differences below round-off): nothing to extrapolate
};

inline const char* describe(Convergence c) {
  switch (c) {
    case Convergence::Monotonic:
      return "monotonic";
    case Convergence::Oscillatory:
      return "oscillatory";
    case Convergence::Diverging:
      return "diverging";
    case Convergence::Converged:
      return "converged";
  }
  return "?";
}

struct GridConvergence {
  Convergence kind = Convergence::Converged;
  double order = std::numeric_limits<double>::quiet_NaN();         // observed p
  double extrapolated = std::numeric_limits<double>::quiet_NaN();  // phi_ext^21
  double relative_change = 0.0;  // e_a^21 = |(phi1 - phi2) / phi1|
  double extrapolated_error =
      std::numeric_limits<double>::quiet_NaN();                  // |(phi_ext - phi1)/phi_ext|
  double gci_fine = std::numeric_limits<double>::quiet_NaN();    // GCI^21, relative to phi1
  double gci_coarse = std::numeric_limits<double>::quiet_NaN();  // GCI^32, relative to phi2
  // Roache's asymptotic-range check GCI^32 / (r21^p GCI^21), with the GCIs relative to phi2 and
  // phi1. With the order observed from these same three runs the absolute GCIs satisfy
  // GCI^32 = r21^p GCI^21 exactly, so the ratio reduces to |phi1 / phi2|: ~1 by construction, and
  // no evidence of the asymptotic range on its own. The accuracy study (app/accuracy_study.cpp)
  // therefore also compares the order of the three finest runs with that of the next three.
  double asymptotic_ratio = std::numeric_limits<double>::quiet_NaN();
  int iterations = 0;
};

// phi[0..2] at spacings h[0..2], finest first (h[0] < h[1] < h[2]). Throws nothing: a degenerate
// triple is reported through `kind` with NaN order.
inline GridConvergence grid_convergence(const std::array<double, 3>& h,
                                        const std::array<double, 3>& phi) {
  GridConvergence g;
  const double r21 = h[1] / h[0], r32 = h[2] / h[1];
  const double e21 = phi[1] - phi[0], e32 = phi[2] - phi[1];
  g.relative_change = phi[0] != 0.0 ? std::abs(e21 / phi[0]) : std::abs(e21);
  const double scale = std::max({std::abs(phi[0]), std::abs(phi[1]), std::abs(phi[2]), 1e-300});
  const double roundoff = 64 * std::numeric_limits<double>::epsilon() * scale;
  if (std::abs(e21) <= roundoff && std::abs(e32) <= roundoff) {
    g.kind = Convergence::Converged;
    g.order = std::numeric_limits<double>::quiet_NaN();
    g.extrapolated = phi[0];
    g.extrapolated_error = 0.0;
    g.gci_fine = g.gci_coarse = 0.0;
    return g;
  }
  if (std::abs(e21) <= roundoff) {  // the two finest agree, the coarse one does not
    g.kind = Convergence::Converged;
    g.extrapolated = phi[0];
    g.extrapolated_error = 0.0;
    g.gci_fine = 0.0;
    return g;
  }
  const double ratio = e32 / e21;
  const double s = ratio >= 0 ? 1.0 : -1.0;
  if (s < 0)
    g.kind = Convergence::Oscillatory;
  else
    g.kind = std::abs(e32) > std::abs(e21) ? Convergence::Monotonic : Convergence::Diverging;
  // Fixed-point iteration of Celik's eq. (3a)-(3c) from the equal-ratio value.
  const double lr = std::log(std::abs(ratio));
  double p = std::abs(lr) / std::log(r21);
  for (g.iterations = 0; g.iterations < 200; ++g.iterations) {
    const double num = std::pow(r21, p) - s, den = std::pow(r32, p) - s;
    if (!(num > 0 && den > 0)) break;  // the log's argument left its domain: keep p
    const double next = std::abs(lr + std::log(num / den)) / std::log(r21);
    if (!std::isfinite(next)) break;
    const bool done = std::abs(next - p) <= 1e-12 * std::max(1.0, p);
    p = next;
    if (done) break;
  }
  g.order = p;
  const double r21p = std::pow(r21, p), r32p = std::pow(r32, p);
  if (g.kind == Convergence::Diverging || !(r21p > 1.0)) return g;
  g.extrapolated = (r21p * phi[0] - phi[1]) / (r21p - 1.0);
  g.extrapolated_error =
      g.extrapolated != 0.0 ? std::abs((g.extrapolated - phi[0]) / g.extrapolated) : 0.0;
  g.gci_fine = 1.25 * g.relative_change / (r21p - 1.0);
  const double ea32 = phi[1] != 0.0 ? std::abs(e32 / phi[1]) : std::abs(e32);
  g.gci_coarse = 1.25 * ea32 / (r32p - 1.0);
  g.asymptotic_ratio = g.gci_coarse / (r21p * g.gci_fine);
  return g;
}

}  // namespace lsi::sweeps
