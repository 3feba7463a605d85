// sweeps/grid_convergence.hpp: observed order, Richardson extrapolation and GCI against the worked
// example of Celik et al. (2008, Table 1, first column: reattachment length over grids of 18 000,
// 8 000 and 4 500 cells in 2D) and against synthetic data phi = phi0 + C h^p whose answer is exact.
#include <gtest/gtest.h>

#include <cmath>

#include "sweeps/grid_convergence.hpp"

namespace {
using lsi::sweeps::Convergence;
using lsi::sweeps::grid_convergence;

// Celik's example: h = (area / N)^(1/2), so r21 = sqrt(18000/8000) = 1.5, r32 = sqrt(8000/4500).
// The paper prints p = 1.53, phi_ext = 6.1685, e_a = 1.5 %, e_ext = 1.7 %, GCI_fine = 2.2 %:
// tolerances are half a unit of the last printed digit.
TEST(GridConvergence, ReproducesCelikExample) {
  const auto g =
      grid_convergence({1.0 / std::sqrt(18000.0), 1.0 / std::sqrt(8000.0), 1.0 / std::sqrt(4500.0)},
                       {6.063, 5.972, 5.863});
  EXPECT_EQ(g.kind, Convergence::Monotonic);
  EXPECT_NEAR(g.order, 1.53, 0.005);
  EXPECT_NEAR(g.extrapolated, 6.1685, 0.00005);
  EXPECT_NEAR(g.relative_change, 0.015, 0.0005);
  EXPECT_NEAR(g.extrapolated_error, 0.017, 0.0005);
  EXPECT_NEAR(g.gci_fine, 0.022, 0.0005);
  // With the order observed from the same three runs the ratio reduces to |phi1 / phi2|.
  EXPECT_NEAR(g.asymptotic_ratio, 6.063 / 5.972, 1e-12);
}

// phi = 2 - 0.7 h^p with unequal ratios (the iteration on q(p) matters): order and limit exact to
// the iteration's tolerance (1e-12 relative; 1e-9 leaves room for the cancellation in phi_ext).
TEST(GridConvergence, ExactForPowerLawWithUnequalRatios) {
  for (const double p : {0.8, 1.0, 2.0, 3.1}) {
    const double h[3] = {0.1, 0.17, 0.4};
    std::array<double, 3> phi{};
    for (int i = 0; i < 3; ++i) phi[i] = 2.0 - 0.7 * std::pow(h[i], p);
    const auto g = grid_convergence({h[0], h[1], h[2]}, phi);
    EXPECT_EQ(g.kind, Convergence::Monotonic) << p;
    EXPECT_NEAR(g.order, p, 1e-9) << p;
    EXPECT_NEAR(g.extrapolated, 2.0, 1e-9) << p;
    // The extrapolated error is then the true error of the finest run.
    EXPECT_NEAR(g.extrapolated_error, 0.7 * std::pow(h[0], p) / 2.0, 1e-9) << p;
    // GCI_fine = 1.25 times the true relative error measured against phi1.
    EXPECT_NEAR(g.gci_fine, 1.25 * 0.7 * std::pow(h[0], p) / phi[0], 1e-9) << p;
  }
}

// Differences that change sign: oscillatory, and no extrapolation is claimed when the iteration
// cannot define the order (the argument of the logarithm may leave its domain).
TEST(GridConvergence, FlagsOscillationAndDivergence) {
  const auto osc = grid_convergence({1, 2, 4}, {1.0, 1.1, 0.9});
  EXPECT_EQ(osc.kind, Convergence::Oscillatory);
  const auto div = grid_convergence({1, 2, 4}, {1.0, 1.2, 1.3});  // |e32| < |e21|
  EXPECT_EQ(div.kind, Convergence::Diverging);
  EXPECT_TRUE(std::isnan(div.extrapolated));
  EXPECT_TRUE(std::isnan(div.gci_fine));
}

// Identical results: converged, zero error, no order.
TEST(GridConvergence, IdenticalRunsAreConverged) {
  const auto g = grid_convergence({1, 2, 4}, {3.5, 3.5, 3.5});
  EXPECT_EQ(g.kind, Convergence::Converged);
  EXPECT_TRUE(std::isnan(g.order));
  EXPECT_EQ(g.extrapolated, 3.5);
  EXPECT_EQ(g.gci_fine, 0.0);
}
}  // namespace
