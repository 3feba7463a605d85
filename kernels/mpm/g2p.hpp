// Grid to particle: velocity (APIC: the grid velocity interpolated, with the affine matrix
// C = 4/dx^2 sum w v_i (x_i - x_p)^T; or a FLIP/PIC blend, plain PIC at flip_ratio 0), velocity
// gradient L = sum v_i grad(w)^T, and position x += dt sum w (v_i_old + v_i) / 2 (trapezoidal:
// exact for constant acceleration). In the same pass it reduces the largest particle speed and
// the largest expansion V / V0 (both for the next time step, time_step.hpp) and flags
// non-finite values or particles leaving the grid (health check).
// g2p_stress_update() also runs the stress update (stress_update.hpp) of each point in the same
// pass, with the velocity gradient still in registers: one pass over the points instead of two.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/math.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/particles.hpp"
#include "kernels/mpm/shape_function.hpp"
#include "kernels/mpm/stress_update.hpp"

namespace lsi::mpm {

enum class Transfer { Apic, FlipPic };

struct G2PReport {
  double max_speed = 0.0;      // m/s
  double max_expansion = 1.0;  // largest V / V0 of a point, at least 1 (time_step.hpp)
  int non_finite = 0;          // number of particles with a non-finite velocity or position
  int outside = 0;             // number of particles too close to the grid edge (or beyond)
};

// What G2P does after the transfer: nothing, or the stress update (elastic, or with plasticity).
enum class G2PStress { None, Elastic, Plastic };

template <class ExecSpace, bool Flip, G2PStress Stress, class MemorySpace>
G2PReport g2p_impl(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g, double dt,
                   double flip_ratio,
                   const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials = {}) {
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, inv_dx = 1.0 / g.dx;
  const double apic = Flip ? 0.0 : 4.0 * inv_dx * inv_dx;
  const double xmax = (g.nx - 2) * dx, ymax = (g.ny - 2) * dx;  // keep 1 cell of padding
  const int nx = g.nx;
  double vmax = 0.0, jmax = 1.0;
  int bad = 0, out = 0;
  Kokkos::parallel_reduce(
      Stress == G2PStress::None ? "lsi::mpm::g2p" : "lsi::mpm::g2p_stress_update",
      Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& vm, double& jm, int& nonfinite, int& outside) {
        // Named here, outside the `if constexpr`s: nvcc rejects a lambda whose first use (and
        // so capture) of a variable is inside one.
        [[maybe_unused]] const double fr = flip_ratio;
        [[maybe_unused]] const auto& mats = materials;
        const double xp = p.position(q, 0) - ox, yp = p.position(q, 1) - oy;
        const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
        // Separable weights w = wx(a) wy(b): sums along each row first, then the row factors.
        const double* wx = sx.w;
        const double* dwx = sx.dw;
        double wxd[3];
        offset_weights(sx, xp, dx, wxd);
        double v[2] = {0, 0}, dv[2] = {0, 0}, vmid[2] = {0, 0}, C[2][2] = {{0, 0}, {0, 0}},
               L[2][2] = {{0, 0}, {0, 0}};
        for (int b = 0; b < 3; ++b) {  // rows outside: the inner loop walks contiguous nodes
          const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
          const int row = sx.base + nx * (sy.base + b);
          double A0[2] = {0, 0}, A1[2] = {0, 0}, A2[2] = {0, 0}, O0[2] = {0, 0};
          for (int a = 0; a < 3; ++a) {
            for (int r = 0; r < 2; ++r) {
              const double vi = g.velocity(row + a, r), vo = g.velocity_old(row + a, r);
              A0[r] += wx[a] * vi;
              A1[r] += wxd[a] * vi;
              A2[r] += dwx[a] * vi;
              O0[r] += wx[a] * vo;
            }
          }
          for (int r = 0; r < 2; ++r) {
            v[r] += wy * A0[r];
            vmid[r] += 0.5 * wy * (A0[r] + O0[r]);
            if constexpr (Flip) dv[r] += wy * (A0[r] - O0[r]);
            C[r][0] += wy * A1[r];
            C[r][1] += wy * dyb * A0[r];
            L[r][0] += wy * A2[r];
            L[r][1] += dwy * A0[r];
          }
        }
        for (int r = 0; r < 2; ++r) {
          double vnew = v[r];
          if constexpr (Flip) vnew = fr * (p.velocity(q, r) + dv[r]) + (1.0 - fr) * v[r];
          p.velocity(q, r) = vnew;
          p.position(q, r) += dt * vmid[r];
          for (int c = 0; c < 2; ++c) {
            p.affine(q, r, c) = apic * C[r][c];
            p.velocity_gradient(q, r, c) = L[r][c];
          }
        }
        if constexpr (Stress != G2PStress::None)
          update_point_stress<Stress == G2PStress::Plastic>(p, q, mats(p.material(q)), L[0][0],
                                                            L[0][1], L[1][0], L[1][1], dt);
        const double s2 = p.velocity(q, 0) * p.velocity(q, 0) + p.velocity(q, 1) * p.velocity(q, 1);
        if (!(s2 < 1e300) || !(p.position(q, 0) == p.position(q, 0)) ||
            !(p.position(q, 1) == p.position(q, 1))) {
          ++nonfinite;
        } else {
          const double s = math::sqrt(s2);
          if (s > vm) vm = s;
          const double J = p.volume(q) / p.volume0(q);
          if (J > jm) jm = J;
        }
        const double px = p.position(q, 0) - ox, py = p.position(q, 1) - oy;
        if (!(px > dx && px < xmax && py > dx && py < ymax)) ++outside;
      },
      Kokkos::Max<double>(vmax), Kokkos::Max<double>(jmax), bad, out);
  return {vmax, jmax > 1.0 ? jmax : 1.0, bad, out};
}

template <class ExecSpace, class MemorySpace>
G2PReport g2p(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g, double dt,
              Transfer transfer, double flip_ratio) {
  return transfer == Transfer::FlipPic
             ? g2p_impl<ExecSpace, true, G2PStress::None>(p, g, dt, flip_ratio)
             : g2p_impl<ExecSpace, false, G2PStress::None>(p, g, dt, 0.0);
}

// G2P and the stress update of each point in one pass: the same results as g2p() followed by
// stress_update<ExecSpace, WithPlasticity>().
template <class ExecSpace, bool WithPlasticity, class MemorySpace>
G2PReport g2p_stress_update(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g,
                            const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials,
                            double dt, Transfer transfer, double flip_ratio) {
  constexpr G2PStress S = WithPlasticity ? G2PStress::Plastic : G2PStress::Elastic;
  return transfer == Transfer::FlipPic
             ? g2p_impl<ExecSpace, true, S>(p, g, dt, flip_ratio, materials)
             : g2p_impl<ExecSpace, false, S>(p, g, dt, 0.0, materials);
}

}  // namespace lsi::mpm
