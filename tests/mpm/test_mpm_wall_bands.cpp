// The walls' pressure bands (kernels/mpm/wall_bands.hpp, methods.mpm.wall_band_m) on a liquid at
// rest in a tank, through the driver: a strengthless, weakly compressible liquid (Mohr-Coulomb
// phi = c = 0, K = 1.6 MPa) h = 1 m deep between smooth walls 2 m apart, built with its
// hydrostatic stress (K0 = 1), and held for 0.5 s. The side walls then carry
// p(z) = rho g (h - z), the bottom rho g h everywhere.
//
// Asserted: the right wall's bands follow the hydrostatic law band by band, the left wall mirrors
// the right one, the bottom carries rho g h. And, on the grid update alone, a wall's bands add up
// to its normal reaction to round-off, whatever the nodes' heights against the band edges.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/mpm_scene.hpp"
#include "kernels/mpm/grid_update.hpp"
#include "model/mpm_runner.hpp"

namespace {

nlohmann::json tank() {
  return nlohmann::json::parse(R"({
    "name": "hydrostatic-tank",
    "mpm_case": {
      "domain_m": {"x": [0.0, 2.2], "y": [0.0, 1.5]},
      "gravity_m_s2": [0.0, -9.81],
      "walls": {"left": {"position_m": 0.1, "friction": 0.0},
                "right": {"position_m": 2.1, "friction": 0.0},
                "bottom": {"position_m": 0.1, "friction": 0.0}},
      "materials": {"liquid": {"model": "mohr-coulomb", "density_kg_m3": 1000,
                               "young_modulus_mpa": 0.48, "poisson_ratio": 0.45,
                               "friction_angle_deg": 0, "dilatancy_angle_deg": 0,
                               "cohesion_kpa": 0, "tension_cutoff_kpa": 0}},
      "bodies": [{"material": "liquid", "polygon_m": [[0.1, 0.1], [2.1, 0.1], [2.1, 1.1], [0.1, 1.1]],
                  "geostatic_k0": 1.0}]
    },
    "methods": {"mpm": {"cell_size_m": 0.05, "particles_per_cell": 4, "courant": 0.5,
                        "end_time_s": 0.5, "output_interval_s": 0.05, "wall_band_m": 0.2}}
  })");
}

std::string band(const char* wall, int k) {
  char name[48];
  std::snprintf(name, sizeof name, "wall_pressure_%s_band_%03d", wall, k);
  return name;
}

using Exec = Kokkos::DefaultExecutionSpace;
using Mem = Exec::memory_space;

// One grid update against a right wall only: nodes on the wall at every height move into it, so
// the wall stops each; its bands (0.13 m: edges that fall between nodes) get the x impulses.
TEST(MpmWallBands, BandsAddUpToTheWallsReaction) {
  const double lower[2] = {0.0, 0.0}, upper[2] = {1.0, 1.0}, dx = 0.1, dt = 1e-3;
  lsi::mpm::Grid<Mem> g(lower, upper, dx);
  auto mass = Kokkos::create_mirror_view(g.mass);
  auto momentum = Kokkos::create_mirror_view(g.momentum);
  for (int j = 0; j < g.ny; ++j)
    for (int i = g.nx - 3; i < g.nx; ++i) {
      const int n = i + g.nx * j;
      mass(n) = 1.0 + 0.1 * j;
      momentum(n, 0) = mass(n) * (2.0 + 0.3 * j);  // into the right wall
      momentum(n, 1) = -mass(n) * 0.5;
    }
  Kokkos::deep_copy(g.mass, mass);
  Kokkos::deep_copy(g.momentum, momentum);
  lsi::mpm::Boundaries walls;
  walls.right = {true, 0.9, 0.0, false, false};
  const auto bands = lsi::mpm::make_wall_bands<Mem>(walls, g, 0.13);
  ASSERT_EQ(bands.count[lsi::mpm::RightWall], 8);  // 0 .. 1 m in 0.13 m bands
  ASSERT_EQ(bands.count[lsi::mpm::LeftWall], 0);
  double wall_force[2] = {0.0, 0.0};
  lsi::mpm::grid_update<Exec>(g, walls, dt, wall_force, 0.0, nullptr, bands);
  const auto impulse = lsi::mpm::take_wall_band_impulse(bands);
  double sum = 0.0;
  for (double v : impulse[lsi::mpm::RightWall]) {
    EXPECT_GT(v, 0.0);  // every band has wall nodes pushing into it
    sum += v;
  }
  // The same nodes' impulses, shared and summed in another order: round-off of ~20 terms.
  constexpr double kSharedSumRel = 1e-13;
  EXPECT_NEAR(sum, wall_force[0] * dt, kSharedSumRel * std::fabs(wall_force[0] * dt));
  // Taking resets the account.
  const auto again = lsi::mpm::take_wall_band_impulse(bands);
  for (double v : again[lsi::mpm::RightWall]) EXPECT_EQ(v, 0.0);
}

// One grid update against a bottom wall at y = 0.3 m: the nodes of rows 0 to 3 (on and below
// the wall) move down into it, so four rows add into each column of the wall, each row into a
// slot of its own (wall_bands.hpp); the bottom's bands (0.17 m) add up to its reaction, and each
// band gets the impulse of the columns its length overlaps (computed here by hand for the first
// band: columns x = 0, 0.1 whole, x = 0.2 for 0.17 - 0.15 = 0.02 of its 0.1 m).
TEST(MpmWallBands, ABottomWallsBandsTakeEveryRowOnAndBelowIt) {
  const double lower[2] = {0.0, 0.0}, upper[2] = {1.0, 1.0}, dx = 0.1, dt = 1e-3;
  lsi::mpm::Grid<Mem> g(lower, upper, dx);
  auto mass = Kokkos::create_mirror_view(g.mass);
  auto momentum = Kokkos::create_mirror_view(g.momentum);
  std::vector<double> column(g.nx, 0.0);  // each column's impulse on the wall, N s/m
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const int n = i + g.nx * j;
      mass(n) = 1.0 + 0.1 * i + 0.01 * j;
      momentum(n, 1) = -mass(n) * (1.0 + 0.2 * j);  // down, into the bottom wall
      column[i] += mass(n) * (1.0 + 0.2 * j);       // the wall stops it: m |v| on the wall
    }
  Kokkos::deep_copy(g.mass, mass);
  Kokkos::deep_copy(g.momentum, momentum);
  lsi::mpm::Boundaries walls;
  walls.bottom = {true, 0.3, 0.0, false, false};
  const auto bands = lsi::mpm::make_wall_bands<Mem>(walls, g, 0.17);
  ASSERT_EQ(bands.count[lsi::mpm::BottomWall], 6);  // 0 .. 1 m in 0.17 m bands
  double wall_force[2] = {0.0, 0.0};
  lsi::mpm::grid_update<Exec>(g, walls, dt, wall_force, 0.0, nullptr, bands);
  const auto impulse = lsi::mpm::take_wall_band_impulse(bands);
  ASSERT_EQ(impulse[lsi::mpm::BottomWall].size(), 6u);
  double sum = 0.0;
  for (double v : impulse[lsi::mpm::BottomWall]) sum += v;
  // Sums of ~40 terms in two orders: round-off.
  constexpr double kRel = 1e-13;
  EXPECT_NEAR(sum, -wall_force[1] * dt, kRel * std::fabs(wall_force[1] * dt));
  // Band 0 ([0, 0.17] m; x = 0 carries [-0.05, 0.05], the band takes what lies below 0).
  const double first = column[0] + column[1] + 0.2 * column[2];
  EXPECT_NEAR(impulse[lsi::mpm::BottomWall][0], first, kRel * first);
}

TEST(MpmWallBands, HydrostaticTankLoadsItsWallsAsTheLawSays) {
  const lsi::MpmCase c = lsi::parse_mpm_case(tank());
  const lsi::MpmOutcome out = lsi::run_mpm_case(c);
  ASSERT_TRUE(out.finished()) << out.status();
  const lsi::MethodResult& r = out.result;
  const double rho_g = 1000 * 9.81, h = 1.0, width = 0.2;
  // Side walls: 0.1 .. 1.5 m (7 bands of 0.2 m); bottom: 0.1 .. 2.1 m (10 bands).
  ASSERT_TRUE(r.series.count(band("right", 6)));
  ASSERT_FALSE(r.series.count(band("right", 7)));
  ASSERT_TRUE(r.series.count(band("bottom", 9)));
  ASSERT_FALSE(r.series.count(band("top", 0)));
  const std::size_t last = r.time.size() - 1;
  // A band of 0.2 m over 0.05 m cells: the nodes' stress is a mean over their B-spline stencil,
  // which samples the linear law exactly in the interior; the band at the bottom also takes the
  // corner node's share below the bottom wall (its tributary half-cell), the band at the surface
  // the liquid's thinning top row. 3 % in the interior, 6 % at the bottom band, 50 Pa (0.5 % of
  // rho g h) above the surface.
  constexpr double kInteriorRel = 0.03, kBottomBandRel = 0.06, kAboveSurfacePa = 50.0;
  // The tank is symmetric: the left wall's bands equal the right one's but for the order of the
  // parallel sums.
  constexpr double kMirrorRel = 1e-9;
  double right = 0.0;
  for (int k = 0; k < 7; ++k) {
    const double z0 = k * width, z1 = std::min(z0 + width, h);
    const double law = z0 < h ? rho_g * (h - 0.5 * (z0 + z1)) * (z1 - z0) / width : 0.0;
    const double p = r.series.at(band("right", k)).values[last];
    const double mirror = r.series.at(band("left", k)).values[last];
    std::cout << "[ wall bands ] right band " << k << ": " << p << " Pa (law " << law << "), left "
              << mirror << "\n";
    right += p * width;
    EXPECT_NEAR(mirror, p, kMirrorRel * rho_g * h);
    if (k == 0)
      EXPECT_NEAR(p / law, 1.0, kBottomBandRel);
    else if (law > 0.0)
      EXPECT_NEAR(p / law, 1.0, kInteriorRel);
    else
      EXPECT_LT(std::fabs(p), kAboveSurfacePa);
  }
  // The whole wall: rho g h^2 / 2 within 2 % (the bottom band's excess).
  constexpr double kWallForceRel = 0.02;
  std::cout << "[ wall bands ] right wall " << right << " N/m (law " << 0.5 * rho_g * h * h
            << ")\n";
  EXPECT_NEAR(right / (0.5 * rho_g * h * h), 1.0, kWallForceRel);
  // The bottom carries rho g h under the whole tank (its end bands meet the side walls, whose
  // corner nodes push on both): 6 % as the side walls' bottom band.
  for (int k = 0; k < 10; ++k) {
    const double p = r.series.at(band("bottom", k)).values[last];
    std::cout << "[ wall bands ] bottom band " << k << ": " << p << " Pa (law " << rho_g * h
              << ")\n";
    EXPECT_NEAR(p / (rho_g * h), 1.0, kBottomBandRel);
  }
}

}  // namespace
