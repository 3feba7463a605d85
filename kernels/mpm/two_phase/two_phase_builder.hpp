// Host-side construction of saturated material points: polygons filled with n x n points per cell
// (the same positions as particle_builder.hpp), with
//   solid mass  m_S = (1 - n) rho_S V      (rho_S = Material::density, the GRAIN density)
//   liquid mass m_L = n rho_L V,           porosity n, hydraulic conductivity k,
// and optionally the initial state of a column at rest under gravity g (water table at the
// surface, the body fully saturated):
//   hydrostatic pore pressure  p = rho_L g (surface_y - y)
//   geostatic effective stress sigma'_yy = -(rho_m - rho_L) g (surface_y - y) (buoyant weight),
//                              sigma'_xx = sigma'_zz = K0 sigma'_yy,  rho_m = (1-n) rho_S + n rho_L
// plus a uniform excess pore pressure (e.g. Terzaghi's undrained response to a load), and a
// surface load: a pressure q on the top surface y = surface_y carried by the topmost row of points
// (those within one point spacing h = dx / n_ppc of the surface), each with the force q h
// downwards (N/m) applied to the mixture (a drained load: the liquid gets no traction).
#pragma once
#include <Kokkos_Core.hpp>
#include <array>
#include <cmath>
#include <vector>

#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "kernels/common/constants.hpp"

namespace lsi::mpm::two_phase {

// A saturated body: the dry body's shape, material (the skeleton's; its density is the grain
// density), velocity (of both phases), points and geostatic state (the surface is also the water
// table), and the pore liquid's.
struct TwoPhaseBodySpec : BodySpec {
  double porosity = 0.4;                 // n0
  double hydraulic_conductivity = 1e-4;  // k, m/s
  double excess_pore_pressure = 0.0;     // Pa, uniform, added to p
  double surface_load = 0.0;             // Pa, on the top row of points (surface_y)
};

template <class MemorySpace>
TwoPhaseParticles<MemorySpace> build_two_phase_particles(
    const std::vector<TwoPhaseBodySpec>& bodies, const std::vector<Material>& materials,
    const Liquid& liquid, const double grid_origin[2], double cell_size) {
  struct Point {
    double x[2], v[2], mS, mL, V, n, k, p, s[4], t[2];
    int mat;
  };
  std::vector<Point> pts;
  for (const auto& body : bodies) {
    const int np = body.points_per_cell_direction;
    const double h = cell_size / np;
    const Material& mat = materials.at(body.material);
    const double n = body.porosity, rho_L = liquid.density;
    const double rho_m = (1.0 - n) * mat.density + n * rho_L;
    for_each_fill_point(
        body.polygon, np, grid_origin, cell_size, [&](double x, double y, double V) {
          Point P{{x, y},
                  {body.velocity[0], body.velocity[1]},
                  (1.0 - n) * mat.density * V,
                  n * rho_L * V,
                  V,
                  n,
                  body.hydraulic_conductivity,
                  body.excess_pore_pressure,
                  {0, 0, 0, 0},
                  {0, 0},
                  body.material};
          const double depth =
              (body.surface_from_polygon ? polygon_top(body.polygon, x) : body.surface_y) - y;
          if (body.geostatic_k0 >= 0.0 && depth > 0.0) {
            P.p += rho_L * body.gravity * depth;
            const double syy = -(rho_m - rho_L) * body.gravity * depth;
            P.s[1] = syy;
            P.s[0] = P.s[3] = body.geostatic_k0 * syy;
          }
          if (body.surface_load != 0.0 && depth > 0.0 && depth < h) P.t[1] = -body.surface_load * h;
          pts.push_back(P);
        });
  }
  const int count = static_cast<int>(pts.size());
  TwoPhaseParticles<MemorySpace> p(count);
  auto x = Kokkos::create_mirror_view(p.solid.position);
  auto v = Kokkos::create_mirror_view(p.solid.velocity);
  auto vl = Kokkos::create_mirror_view(p.liquid_velocity);
  auto s = Kokkos::create_mirror_view(p.solid.stress);
  auto ms = Kokkos::create_mirror_view(p.solid.mass);
  auto ml = Kokkos::create_mirror_view(p.liquid_mass);
  auto vol = Kokkos::create_mirror_view(p.solid.volume);
  auto mat = Kokkos::create_mirror_view(p.solid.material);
  auto por = Kokkos::create_mirror_view(p.porosity);
  auto k = Kokkos::create_mirror_view(p.conductivity);
  auto pw = Kokkos::create_mirror_view(p.pore_pressure);
  auto t = Kokkos::create_mirror_view(p.traction);
  for (int q = 0; q < count; ++q) {
    const Point& P = pts[q];
    for (int d = 0; d < 2; ++d) {
      x(q, d) = P.x[d];
      v(q, d) = vl(q, d) = P.v[d];
      t(q, d) = P.t[d];
    }
    for (int c = 0; c < 4; ++c) s(q, c) = P.s[c];
    ms(q) = P.mS;
    ml(q) = P.mL;
    vol(q) = P.V;
    mat(q) = P.mat;
    por(q) = P.n;
    k(q) = P.k;
    pw(q) = P.p;
  }
  Kokkos::deep_copy(p.solid.position, x);
  Kokkos::deep_copy(p.solid.velocity, v);
  Kokkos::deep_copy(p.liquid_velocity, vl);
  Kokkos::deep_copy(p.solid.stress, s);
  Kokkos::deep_copy(p.solid.mass, ms);
  Kokkos::deep_copy(p.liquid_mass, ml);
  Kokkos::deep_copy(p.solid.volume, vol);
  Kokkos::deep_copy(p.solid.volume0, vol);
  Kokkos::deep_copy(p.solid.material, mat);
  Kokkos::deep_copy(p.porosity, por);
  Kokkos::deep_copy(p.conductivity, k);
  Kokkos::deep_copy(p.pore_pressure, pw);
  Kokkos::deep_copy(p.traction, t);
  return p;
}

}  // namespace lsi::mpm::two_phase
