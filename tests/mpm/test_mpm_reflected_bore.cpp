// Verification of the energy the MPM loses in its transfers (kernels/mpm/transfer_dissipation.hpp)
// against the one flow whose loss is known in closed form: a bore. A 1 m deep stream of a
// strengthless, weakly compressible liquid (Mohr-Coulomb with phi = c = 0, bulk modulus 1.6 MPa:
// wave speed 40 m/s, 13 times the flow) runs at v = 3 m/s into still liquid held by a smooth
// vertical wall (scenes/verification/reflected-bore.json). The still region is given the depth
// h2 of the bore that brings the stream to rest, so a single bore runs upstream (the Riemann
// problem of shallow water). Its jump conditions, mass h1 (v + c) = h2 c and momentum
// g (h2^2 - h1^2) / 2 = h1 (v + c) v, give its speed c = 2.688 m/s and depth h2 = 2.116 m; the
// wall carries the hydrostatic load rho g h2^2 / 2 = 21.97 kN/m; and the bore dissipates
//   D = rho g Q (h2 - h1)^3 / (4 h1 h2),  Q = h1 (v + c)  (9.17 kW/m)
// whatever the fluid's viscosity: the loss is set by mass and momentum conservation alone.
// No term of the model dissipates in this liquid (no friction, no strength), so the MPM's loss is
// its transfer dissipation (plus the smooth walls' projection): this is what the saturated
// impacts lose in the grid transfers (docs/theory/mpm.md, "Energy lost in the transfers").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "model/mpm_runner.hpp"
#include "io/mpm_scene.hpp"

namespace {

struct Bore {
  double c, h2, D, wall_force;
};

// The bore's jump conditions (above), solved for its speed by bisection.
Bore bore(double h1, double v, double rho, double g) {
  auto momentum_gap = [&](double c) {
    const double h2 = h1 * (v + c) / c;
    return 0.5 * g * (h2 * h2 - h1 * h1) - h1 * (v + c) * v;
  };
  double lo = 0.1, hi = 20.0;  // the gap is positive at lo, negative at hi
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (momentum_gap(mid) > 0.0 ? lo : hi) = mid;
  }
  Bore b;
  b.c = 0.5 * (lo + hi);
  b.h2 = h1 * (v + b.c) / b.c;
  const double Q = h1 * (v + b.c);
  b.D = rho * g * Q * std::pow(b.h2 - h1, 3) / (4.0 * h1 * b.h2);
  b.wall_force = 0.5 * rho * g * b.h2 * b.h2;
  return b;
}

// The first output at or after t.
size_t output_at(const lsi::MethodResult& r, double t) {
  const size_t i = std::lower_bound(r.time.begin(), r.time.end(), t - 1e-9) - r.time.begin();
  return std::min(i, r.time.size() - 1);
}

TEST(MpmReflectedBore, DissipatesWhatTheJumpConditionsSay) {
  std::ifstream in(LSI_SOURCE_DIR "/scenes/verification/reflected-bore.json");
  const lsi::MpmCase c = lsi::parse_mpm_case(nlohmann::json::parse(in));
  const lsi::MpmOutcome out = lsi::run_mpm_case(c);
  ASSERT_TRUE(out.finished()) << out.status();
  const lsi::MethodResult& r = out.result;
  const Bore b = bore(1.0, 3.0, 1000.0, 9.81);
  EXPECT_NEAR(b.h2, 2.116, 1e-3);  // the depth the scene gives the still region
  auto lost = [&](size_t i) {
    return r.series.at("transfer_dissipation").values.at(i) +
           r.series.at("plastic_dissipation").values.at(i) +
           r.series.at("boundary_dissipation").values.at(i);
  };
  // The bore's roller takes about a second to form (the loss rate over 0.4-1.2 s is 0.79 D);
  // over 1.1-1.9 s, before the rarefaction from the stream's free tail reaches the bore (at
  // 1.9 s), it is steady. Measured 1.02 D at this cell (h1 / 10) and 0.95 D at h1 / 20; at h1 / 5
  // the walls' projection adds a third (1.74 D over 0.4-1.9 s). 20 %: the scatter of the two
  // finer cells and a margin, not more.
  const size_t i0 = output_at(r, 1.1), i1 = output_at(r, 1.9);
  const double rate = (lost(i1) - lost(i0)) / (r.time[i1] - r.time[i0]);
  // The wall's load, averaged over the outputs from 0.4 s: rho g h2^2 / 2 within 3 % (measured
  // -0.5 %; the pressure rings with the liquid's compressibility, hence the average).
  double force = 0.0;
  int n = 0;
  const auto& fx = r.series.at("wall_force_x").values;
  for (size_t i = 0; i < r.time.size(); ++i)
    if (r.time[i] >= 0.4) force += std::fabs(fx[i]), ++n;
  force /= n;
  const auto& unexplained = r.series.at("energy_residual_unexplained").values;
  const double un_min = *std::min_element(unexplained.begin(), unexplained.end());
  const double un_max = *std::max_element(unexplained.begin(), unexplained.end());
  std::cout << "[ reflected bore ] loss rate " << rate << " W/m = " << rate / b.D
            << " D; wall force " << force << " N/m = " << force / b.wall_force
            << " of rho g h2^2 / 2; unexplained residual " << un_min << " .. " << un_max << "\n";
  EXPECT_NEAR(rate / b.D, 1.0, 0.2);
  EXPECT_NEAR(force / b.wall_force, 1.0, 0.03);
  // The balance closes once the transfer loss is booked (measured -0.78 .. +0.03 %; the
  // residual itself reaches -11 %).
  EXPECT_GT(un_min, -0.02);
  EXPECT_LT(un_max, 0.02);
}

}  // namespace
