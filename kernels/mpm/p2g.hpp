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
        const double vx = p.velocity(q, 0), vy = p.velocity(q, 1);
        const double c00 = p.affine(q, 0, 0), c01 = p.affine(q, 0, 1), c10 = p.affine(q, 1, 0),
                     c11 = p.affine(q, 1, 1);
        const double sxx = p.stress(q, 0), syy = p.stress(q, 1), sxy = p.stress(q, 2);
        for (int a = 0; a < 3; ++a) {
          const double dxa = (sx.base + a) * dx - xp;
          for (int b = 0; b < 3; ++b) {
            const double dyb = (sy.base + b) * dx - yp;
            const int node = (sx.base + a) + nx * (sy.base + b);
            const double w = sx.w[a] * sy.w[b];
            const double gwx = sx.dw[a] * sy.w[b], gwy = sx.w[a] * sy.dw[b];
            m_acc(node) += w * m;
            p_acc(node, 0) += w * m * (vx + c00 * dxa + c01 * dyb);
            p_acc(node, 1) += w * m * (vy + c10 * dxa + c11 * dyb);
            f_acc(node, 0) += -V * (sxx * gwx + sxy * gwy) + w * m * gx;
            f_acc(node, 1) += -V * (sxy * gwx + syy * gwy) + w * m * gy;
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
