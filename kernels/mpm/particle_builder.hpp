// Host-side construction of material points: polygons filled with n x n points per cell at the
// Gauss-like regular positions ((k + 1/2) / n of the cell), optional geostatic initial stress.
// No I/O; used by the drivers and the tests.
#pragma once
#include <Kokkos_Core.hpp>
#include <array>
#include <cmath>
#include <vector>

#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/particles.hpp"
#include "kernels/common/constants.hpp"

namespace lsi::mpm {

struct BodySpec {
  std::vector<std::array<double, 2>> polygon;   // vertices, either orientation
  int material = 0;                             // index into the material table
  std::array<double, 2> velocity = {0.0, 0.0};  // initial velocity, m/s
  int points_per_cell_direction = 2;            // n: n^2 points per cell
  // Geostatic initial stress under gravity magnitude g: sigma_yy = -rho g (surface_y - y),
  // sigma_xx = sigma_zz = K0 sigma_yy. Off when geostatic_k0 < 0. With surface_from_polygon the
  // surface is the polygon's top above each point (sloping fronts and tails), not surface_y.
  double geostatic_k0 = -1.0;
  double surface_y = 0.0;
  bool surface_from_polygon = false;
  double gravity = lsi::gravity;
};

inline bool inside_polygon(const std::vector<std::array<double, 2>>& poly, double x, double y) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
  }
  return in;
}

// The highest point of the polygon's boundary on the vertical line through x (-1e300 if none).
inline double polygon_top(const std::vector<std::array<double, 2>>& poly, double x) {
  double top = -1e300;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a[0] <= x) == (b[0] <= x)) continue;  // the edge does not cross the line
    top = std::max(top, a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]));
  }
  return top;
}

// Calls f(x, y, V) for every fill point of the polygon: n x n points per cell of the grid
// (origin, cell_size) at (k + 1/2) / n of the cell, V = (cell_size / n)^2 each.
template <class F>
void for_each_fill_point(const std::vector<std::array<double, 2>>& polygon, int n,
                         const double grid_origin[2], double cell_size, F&& f) {
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const auto& v : polygon)
    for (int d = 0; d < 2; ++d) {
      lo[d] = std::min(lo[d], v[d]);
      hi[d] = std::max(hi[d], v[d]);
    }
  const double h = cell_size / n, V = h * h;
  const int i0 = static_cast<int>(std::floor((lo[0] - grid_origin[0]) / cell_size));
  const int i1 = static_cast<int>(std::ceil((hi[0] - grid_origin[0]) / cell_size));
  const int j0 = static_cast<int>(std::floor((lo[1] - grid_origin[1]) / cell_size));
  const int j1 = static_cast<int>(std::ceil((hi[1] - grid_origin[1]) / cell_size));
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i)
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const double x = grid_origin[0] + i * cell_size + (a + 0.5) * h;
          const double y = grid_origin[1] + j * cell_size + (b + 0.5) * h;
          if (inside_polygon(polygon, x, y)) f(x, y, V);
        }
}

template <class MemorySpace>
Particles<MemorySpace> build_particles(const std::vector<BodySpec>& bodies,
                                       const std::vector<Material>& materials,
                                       const double grid_origin[2], double cell_size) {
  struct Point {
    double x, y, vx, vy, m, V, s[4];
    int mat;
  };
  std::vector<Point> pts;
  for (const auto& body : bodies) {
    const Material& mat = materials.at(body.material);
    for_each_fill_point(body.polygon, body.points_per_cell_direction, grid_origin, cell_size,
                        [&](double x, double y, double V) {
                          Point p{x,
                                  y,
                                  body.velocity[0],
                                  body.velocity[1],
                                  mat.density * V,
                                  V,
                                  {0, 0, 0, 0},
                                  body.material};
                          if (body.geostatic_k0 >= 0.0) {
                            const double top = body.surface_from_polygon
                                                   ? polygon_top(body.polygon, x)
                                                   : body.surface_y;
                            const double syy = -mat.density * body.gravity * (top - y);
                            p.s[1] = syy;
                            p.s[0] = p.s[3] = body.geostatic_k0 * syy;
                          }
                          pts.push_back(p);
                        });
  }
  Particles<MemorySpace> p(static_cast<int>(pts.size()));
  auto x = Kokkos::create_mirror_view(p.position);
  auto v = Kokkos::create_mirror_view(p.velocity);
  auto s = Kokkos::create_mirror_view(p.stress);
  auto m = Kokkos::create_mirror_view(p.mass);
  auto vol = Kokkos::create_mirror_view(p.volume);
  auto mat = Kokkos::create_mirror_view(p.material);
  for (size_t q = 0; q < pts.size(); ++q) {
    x(q, 0) = pts[q].x;
    x(q, 1) = pts[q].y;
    v(q, 0) = pts[q].vx;
    v(q, 1) = pts[q].vy;
    for (int k = 0; k < 4; ++k) s(q, k) = pts[q].s[k];
    m(q) = pts[q].m;
    vol(q) = pts[q].V;
    mat(q) = pts[q].mat;
  }
  Kokkos::deep_copy(p.position, x);
  Kokkos::deep_copy(p.velocity, v);
  Kokkos::deep_copy(p.stress, s);
  Kokkos::deep_copy(p.mass, m);
  Kokkos::deep_copy(p.volume, vol);
  Kokkos::deep_copy(p.volume0, vol);
  Kokkos::deep_copy(p.material, mat);
  return p;
}

}  // namespace lsi::mpm
