// Particle to grid: mass, APIC momentum m (v_p + C_p (x_i - x_p)), and force
// -V_p sigma_p grad(w_ip) + w_ip m_p g, scattered without data races by a Kokkos ScatterView:
// either one copy of the grid per thread summed afterwards (duplicated) or atomic additions into
// one grid, chosen by `Atomic` (bench/ measures which is faster). Serial needs neither.
#pragma once
#include <Kokkos_Core.hpp>
#include <Kokkos_ScatterView.hpp>
#include <type_traits>

#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/particles.hpp"
#include "kernels/mpm/shape_function.hpp"

namespace lsi::mpm {

// The scatter targets of P2G, allocated once per solver and reset every step (allocating the
// per-thread copies every step costs as much as the scatter itself on small grids).
template <class ExecSpace, bool Atomic>
struct GridScatter {
  using Exec = ExecSpace;
#ifdef KOKKOS_ENABLE_SERIAL
  static constexpr bool serial = std::is_same_v<ExecSpace, Kokkos::Serial>;
#else
  static constexpr bool serial = false;
#endif
  static constexpr bool duplicated = !Atomic && !serial;
  using Duplication = std::conditional_t<duplicated, Kokkos::Experimental::ScatterDuplicated,
                                         Kokkos::Experimental::ScatterNonDuplicated>;
  using Contribution = std::conditional_t<Atomic && !serial, Kokkos::Experimental::ScatterAtomic,
                                          Kokkos::Experimental::ScatterNonAtomic>;
  template <class Data>
  using SV = Kokkos::Experimental::ScatterView<Data, Kokkos::LayoutRight, ExecSpace,
                                               Kokkos::Experimental::ScatterSum, Duplication,
                                               Contribution>;
  SV<double*> mass;
  SV<double* [2]> momentum, force;

  GridScatter() = default;
  template <class MemorySpace>
  explicit GridScatter(const Grid<MemorySpace>& g)
      : mass(g.mass), momentum(g.momentum), force(g.force) {}
};

template <class ExecSpace, bool Atomic, class MemorySpace>
void p2g(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g,
         GridScatter<ExecSpace, Atomic>& scatter, const double gravity[2]) {
  namespace KE = Kokkos::Experimental;
  if constexpr (GridScatter<ExecSpace, Atomic>::duplicated) {
    Kokkos::deep_copy(g.mass, 0.0);   // the copies are summed into the grid
    Kokkos::deep_copy(g.momentum, 0.0);
    Kokkos::deep_copy(g.force, 0.0);
  }
  scatter.mass.reset();               // not duplicated: this zeroes the grid itself
  scatter.momentum.reset();
  scatter.force.reset();
  auto& mass = scatter.mass;
  auto& momentum = scatter.momentum;
  auto& force = scatter.force;
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, inv_dx = 1.0 / g.dx;
  const int nx = g.nx;
  const double gx = gravity[0], gy = gravity[1];
  Kokkos::parallel_for(
      "lsi::mpm::p2g", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q) {
        auto m_acc = mass.access();
        auto p_acc = momentum.access();
        auto f_acc = force.access();
        const double xp = p.position(q, 0) - ox, yp = p.position(q, 1) - oy;
        const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
        const double m = p.mass(q), V = p.volume(q);
        const double mv[2] = {m * p.velocity(q, 0), m * p.velocity(q, 1)};
        const double mC[2][2] = {{m * p.affine(q, 0, 0), m * p.affine(q, 0, 1)},
                                 {m * p.affine(q, 1, 0), m * p.affine(q, 1, 1)}};
        const double Vs[3] = {V * p.stress(q, 0), V * p.stress(q, 1), V * p.stress(q, 2)};
        // Separable weights w = wx(a) wy(b). Per node i:
        //   mass     w m
        //   momentum w (m v + m C (x_i - x_p))             = wx P[r] + wx dxa Q[r]
        //   force   -V sigma grad(w) + w m g               = dwx F1[r] + wx F0[r]
        // with the row factors P, Q, F0, F1 below.
        double wx[3], wxd[3], dwx[3];
        for (int a = 0; a < 3; ++a) {
          wx[a] = sx.w[a];
          wxd[a] = sx.w[a] * ((sx.base + a) * dx - xp);
          dwx[a] = sx.dw[a];
        }
        for (int b = 0; b < 3; ++b) {
          const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
          const double P[2] = {wy * (mv[0] + mC[0][1] * dyb), wy * (mv[1] + mC[1][1] * dyb)};
          const double Q[2] = {wy * mC[0][0], wy * mC[1][0]};
          const double F1[2] = {-Vs[0] * wy, -Vs[2] * wy};
          const double F0[2] = {-Vs[2] * dwy + wy * m * gx, -Vs[1] * dwy + wy * m * gy};
          const int row = sx.base + nx * (sy.base + b);
          for (int a = 0; a < 3; ++a) {
            const int node = row + a;
            m_acc(node) += wx[a] * wy * m;
            p_acc(node, 0) += wx[a] * P[0] + wxd[a] * Q[0];
            p_acc(node, 1) += wx[a] * P[1] + wxd[a] * Q[1];
            f_acc(node, 0) += dwx[a] * F1[0] + wx[a] * F0[0];
            f_acc(node, 1) += dwx[a] * F1[1] + wx[a] * F0[1];
          }
        }
      });
  auto gm = g.mass;
  auto gp = g.momentum;
  auto gf = g.force;
  KE::contribute(gm, mass);
  KE::contribute(gp, momentum);
  KE::contribute(gf, force);
}

}  // namespace lsi::mpm
