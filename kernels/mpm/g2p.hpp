// Grid to particle: velocity (APIC: the grid velocity interpolated, with the affine matrix
// C = 4/dx^2 sum w v_i (x_i - x_p)^T; or a FLIP/PIC blend, plain PIC at flip_ratio 0), velocity
// gradient L = sum v_i grad(w)^T, and position x += dt sum w (v_i_old + v_i) / 2 (trapezoidal:
// exact for constant acceleration). In the same pass it reduces the largest particle speed and
// the largest expansion V / V0 (both for the next time step, time_step.hpp) and flags
// non-finite values or particles leaving the grid (health check).
// g2p_stress_update() also runs the stress update (stress_update.hpp) of each point in the same
// pass, with the velocity gradient at hand: one pass over the points instead of two.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>
#include <type_traits>

#include "kernels/common/execution_instance.hpp"
#include "kernels/common/math.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/host_transpose.hpp"
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

namespace detail {

// Points per work item of the host G2P (g2p_impl): its loops over a block vectorise.
constexpr int kG2PBlock = 32;

// The grid's velocities (after and before the update) at the stencil of a point:
// value(bi, bj, b, a, r, vi, vo) gives component r of node (bi + a, bj + b). GridStencil reads
// them from the grid; the host's blocked G2P first copies them into a block's arrays
// (BlockStencil), whose reads then vectorise.
template <class GridVelocity>
struct GridStencil {
  GridVelocity velocity, velocity_old;
  int nx;
  KOKKOS_FORCEINLINE_FUNCTION void value(const int bi, const int bj, const int b, const int a,
                                         const int r, double& vi, double& vo) const {
    const int n = bi + a + nx * (bj + b);
    vi = velocity(n, r);
    vo = velocity_old(n, r);
  }
};

// The grid-to-point transfer of point q: its velocity, position and affine matrix, and its
// velocity gradient, returned in L and stored in the point's field where StoreGradient (a later
// pass over the points reads it there: the separate stress update; the fused pass uses L).
template <bool Flip, bool StoreGradient, class Points, class Stencil>
KOKKOS_FORCEINLINE_FUNCTION void g2p_point(const Points& p, const int q, const Stencil& nodes,
                                           const double ox, const double oy, const double dx,
                                           const double inv_dx, const double apic, const double fr,
                                           const double dt, double L[2][2]) {
  const double xp = p.position(q, 0) - ox, yp = p.position(q, 1) - oy;
  const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
  // Separable weights w = wx(a) wy(b): sums along each row first, then the row factors.
  const double* wx = sx.w;
  const double* dwx = sx.dw;
  double wxd[3];
  offset_weights(sx, xp, dx, wxd);
  double v[2] = {0, 0}, dv[2] = {0, 0}, vmid[2] = {0, 0}, C[2][2] = {{0, 0}, {0, 0}};
  L[0][0] = L[0][1] = L[1][0] = L[1][1] = 0.0;
  // Unrolled completely (here and in the calls it makes), so that the host's loop over points,
  // not these, is the one that vectorises.
#pragma GCC unroll 3
  for (int b = 0; b < 3; ++b) {  // rows outside: the inner loop walks contiguous nodes
    const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
    double A0[2] = {0, 0}, A1[2] = {0, 0}, A2[2] = {0, 0}, O0[2] = {0, 0};
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
#pragma GCC unroll 2
      for (int r = 0; r < 2; ++r) {
        double vi, vo;
        nodes.value(sx.base, sy.base, b, a, r, vi, vo);
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
      if constexpr (StoreGradient) p.velocity_gradient(q, r, c) = L[r][c];
    }
  }
}

// The health of point q after its update: its speed and V / V0 (both 0 where it is not finite),
// counted in nonfinite where its velocity or position is not finite, in outside where it is
// too close to the grid's edge. Without branches (`&`, `|`, selections), so that the host's loop
// over a block vectorises.
template <class Points>
KOKKOS_FORCEINLINE_FUNCTION void g2p_health(const Points& p, const int q, const double ox,
                                            const double oy, const double dx, const double xmax,
                                            const double ymax, double& speed, double& expansion,
                                            int& nonfinite, int& outside) {
  const double vx = p.velocity(q, 0), vy = p.velocity(q, 1);
  const double x = p.position(q, 0), y = p.position(q, 1);
  const double s2 = vx * vx + vy * vy;
  const bool bad = !(s2 < 1e300) | !(x == x) | !(y == y);
  nonfinite += bad ? 1 : 0;
  speed = math::sqrt(bad ? 0.0 : s2);
  expansion = bad ? 0.0 : p.volume(q) / p.volume0(q);
  const double px = x - ox, py = y - oy;
  outside += (px > dx) & (px < xmax) & (py > dx) & (py < ymax) ? 0 : 1;
}

// The stencil of point k of a block (GridStencil), from the block's copies.
template <int B>
struct BlockStencil {
  const double (*v)[6][B];
  const double (*v_old)[6][B];
  int k;
  KOKKOS_FORCEINLINE_FUNCTION void value(int, int, const int b, const int a, const int r,
                                         double& vi, double& vo) const {
    vi = v[b][2 * a + r][k];
    vo = v_old[b][2 * a + r][k];
  }
};

// A block of points [q0, q1) of the host G2P (g2p_impl), in loops over the block's points:
//  1. the grid velocities of each point's 3 x 3 stencil into the block's arrays (a transpose:
//     the nodes of neighbouring points are near, not adjacent, in the grid; in registers, 8
//     points at a time, where host_transpose.hpp is compiled in);
//  2. the transfer (g2p_point, reading those arrays), its velocity gradient into Lb (and into
//     the points' field only without the stress update, whose pass reads the field);
//  3. the trial stress, and whether the point needs the return mapping;
//  4. the return mappings where needed: Mohr-Coulomb's vectorised
//     (mohr_coulomb_return_selected), the rate-dependent ones point by point;
//  5. the rest of the stress update and the health check.
// Loops 2, 3 and 5 have no branches and no dependence between points: the compiler vectorises
// them over the points (component arrays, particles.hpp). Everything the loops read is a
// parameter (a value once inlined): a constant read through a kernel's closure in a loop
// stopped GCC from vectorising it. v, v_old: the grid's velocities after and before the update
// (n x 2, node-interleaved); material_of(q): point q's material.
template <bool Flip, G2PStress Stress, class MaterialOf>
KOKKOS_FORCEINLINE_FUNCTION void g2p_block(const PointArrays a, const double* const v,
                                           const double* const v_old, const MaterialOf material_of,
                                           const int nx, const double ox, const double oy,
                                           const double dx, const double inv_dx, const double apic,
                                           const double fr, const double dt, const double xmax,
                                           const double ymax, const int q0, const int q1,
                                           double& vm, double& jm, int& nonfinite, int& outside) {
  constexpr bool with_stress = Stress != G2PStress::None;
  constexpr bool plastic = Stress == G2PStress::Plastic;
  constexpr int B = kG2PBlock;
  double Lb[4][B], sb[4][B];
  // Whether a point needs the return mapping, as a 64-bit integer: a vector mask in the loops
  // over doubles (GCC vectorises no selection on a bool loaded from memory there).
  std::int64_t needs_return[B];
  alignas(64) double gv[3][6][B], gvo[3][6][B];
  int k0 = 0;
#if LSI_MPM_HOST_TRANSPOSE
  // 8 points at a time: each stencil row's 6 doubles of the 8 points transposed in registers.
  static_assert(B % 8 == 0);
  for (; k0 + 8 <= q1 - q0; k0 += 8) {
    int first[8];
    for (int p = 0; p < 8; ++p) {
      const int q = q0 + k0 + p;
      const int bi = quadratic_bspline(a.position(q, 0) - ox, inv_dx).base;
      const int bj = quadratic_bspline(a.position(q, 1) - oy, inv_dx).base;
      first[p] = 2 * (bi + nx * bj);
    }
    for (int b = 0; b < 3; ++b) {
      const double* rows[8];
      const double* rows_old[8];
      for (int p = 0; p < 8; ++p) {
        rows[p] = v + first[p] + 2 * nx * b;
        rows_old[p] = v_old + first[p] + 2 * nx * b;
      }
      host_simd::V8 t[6], t_old[6];
      host_simd::gather_rows6(rows, t);
      host_simd::gather_rows6(rows_old, t_old);
      for (int c = 0; c < 6; ++c) {
        host_simd::store8(&gv[b][c][k0], t[c]);
        host_simd::store8(&gvo[b][c][k0], t_old[c]);
      }
    }
  }
#endif
  for (int q = q0 + k0; q < q1; ++q) {
    const int k = q - q0;
    const int bi = quadratic_bspline(a.position(q, 0) - ox, inv_dx).base;
    const int bj = quadratic_bspline(a.position(q, 1) - oy, inv_dx).base;
    for (int b = 0; b < 3; ++b) {
      const double* row = v + 2 * (bi + nx * (bj + b));
      const double* row_old = v_old + 2 * (bi + nx * (bj + b));
      for (int c = 0; c < 6; ++c) {
        gv[b][c][k] = row[c];
        gvo[b][c][k] = row_old[c];
      }
    }
  }
#pragma GCC ivdep
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    double L[2][2];
    g2p_point<Flip, !with_stress>(a, q, BlockStencil<B>{gv, gvo, k}, ox, oy, dx, inv_dx, apic, fr,
                                  dt, L);
    Lb[0][k] = L[0][0];
    Lb[1][k] = L[0][1];
    Lb[2][k] = L[1][0];
    Lb[3][k] = L[1][1];
  }
  if constexpr (with_stress) {
#pragma GCC ivdep
    for (int q = q0; q < q1; ++q) {
      const int k = q - q0;
      double s[4];
      needs_return[k] = trial_point_stress<plastic>(a, q, material_of(q), Lb[0][k], Lb[1][k],
                                                    Lb[2][k], Lb[3][k], dt, s);
      for (int c = 0; c < 4; ++c) sb[c][k] = s[c];
    }
  }
  if constexpr (plastic) block_return_mappings<B>(a, q0, q1, material_of, Lb, sb, needs_return);
  // The health of each point into arrays, reduced after the loop: GCC vectorises no maximum of
  // doubles (its NaN rules) inside a loop.
  double speed[B], expansion[B];
  int nonfinite_b = 0, outside_b = 0;
#pragma GCC ivdep
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    if constexpr (with_stress) {
      const double s[4] = {sb[0][k], sb[1][k], sb[2][k], sb[3][k]};
      finish_point_stress<plastic>(a, q, material_of(q), Lb[0][k], Lb[1][k], Lb[2][k], Lb[3][k], dt,
                                   s);
    }
    g2p_health(a, q, ox, oy, dx, xmax, ymax, speed[k], expansion[k], nonfinite_b, outside_b);
  }
  for (int k = 0; k < q1 - q0; ++k) {
    vm = speed[k] > vm ? speed[k] : vm;
    jm = expansion[k] > jm ? expansion[k] : jm;
  }
  nonfinite += nonfinite_b;
  outside += outside_b;
}

}  // namespace detail

// Host spaces: each work item takes kG2PBlock consecutive points (detail::g2p_block, whose
// loops vectorise over the points; the Mohr-Coulomb returns to an edge or the apex stay scalar). A device runs one
// point per thread: the transfer, the stress update (trial, return, finish) and the health check
// in turn. Both give the same results up to round-off.
template <class ExecSpace, bool Flip, G2PStress Stress, class MemorySpace>
G2PReport g2p_impl(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g, double dt,
                   double flip_ratio,
                   const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials = {}) {
  constexpr bool host =
      Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename ExecSpace::memory_space>::accessible;
  constexpr bool with_stress = Stress != G2PStress::None;
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, inv_dx = 1.0 / g.dx;
  const double apic = Flip ? 0.0 : 4.0 * inv_dx * inv_dx;
  const double xmax = (g.nx - 2) * dx, ymax = (g.ny - 2) * dx;  // keep 1 cell of padding
  const int nx = g.nx, count = p.count;
  const auto velocity = g.velocity;
  const auto velocity_old = g.velocity_old;
  double vmax = 0.0, jmax = 1.0;
  int bad = 0, out = 0;
  const char* name = with_stress ? "lsi::mpm::g2p_stress_update" : "lsi::mpm::g2p";
  if constexpr (host) {
    constexpr int B = detail::kG2PBlock;
    Kokkos::parallel_reduce(
        name, range_policy<ExecSpace>(0, (count + B - 1) / B),
        KOKKOS_LAMBDA(const int block, double& vm, double& jm, int& nonfinite, int& outside) {
          const int q0 = block * B, q1 = q0 + B < count ? q0 + B : count;
          const PointArrays a(p);
          const PreparedMaterial* const mats = with_stress ? materials.data() : nullptr;
          // One material in the block (the usual case: bodies are built one after the other):
          // its constants are loop invariants; otherwise each point looks its material up.
          bool uniform = true;
          if constexpr (with_stress) {
            for (int q = q0; q < q1; ++q) uniform &= a.material(q) == a.material(q0);
          }
          static_assert(std::is_same_v<typename decltype(velocity)::array_layout,
                                       Kokkos::LayoutRight>);  // node-interleaved on the host
          const double* const v = velocity.data();
          const double* const v_old = velocity_old.data();
          if (uniform) {
            const PreparedMaterial m = with_stress ? mats[a.material(q0)] : PreparedMaterial();
            detail::g2p_block<Flip, Stress>(
                a, v, v_old, [&m](int) -> const PreparedMaterial& { return m; }, nx, ox, oy, dx,
                inv_dx, apic, flip_ratio, dt, xmax, ymax, q0, q1, vm, jm, nonfinite, outside);
          } else {
            detail::g2p_block<Flip, Stress>(
                a, v, v_old,
                [mats, a](int q) -> const PreparedMaterial& { return mats[a.material(q)]; }, nx, ox,
                oy, dx, inv_dx, apic, flip_ratio, dt, xmax, ymax, q0, q1, vm, jm, nonfinite,
                outside);
          }
        },
        Kokkos::Max<double>(vmax), Kokkos::Max<double>(jmax), bad, out);
  } else {
    Kokkos::parallel_reduce(
        name, range_policy<ExecSpace>(0, count),
        KOKKOS_LAMBDA(const int q, double& vm, double& jm, int& nonfinite, int& outside) {
          [[maybe_unused]] const auto& mats = materials;
          double L[2][2];
          detail::g2p_point<Flip, Stress == G2PStress::None>(
              p, q, detail::GridStencil<decltype(velocity)>{velocity, velocity_old, nx}, ox, oy, dx,
              inv_dx, apic, flip_ratio, dt, L);
          // The template parameter, not the constexpr locals: nvcc counts a local named in an
          // `if constexpr` of a device lambda as a capture there, and rejects it.
          if constexpr (Stress != G2PStress::None)
            update_point_stress<Stress == G2PStress::Plastic>(p, q, mats(p.material(q)), L[0][0],
                                                              L[0][1], L[1][0], L[1][1], dt);
          double speed, expansion;
          detail::g2p_health(p, q, ox, oy, dx, xmax, ymax, speed, expansion, nonfinite, outside);
          if (speed > vm) vm = speed;
          if (expansion > jm) jm = expansion;
        },
        Kokkos::Max<double>(vmax), Kokkos::Max<double>(jmax), bad, out);
  }
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
// stress_update<ExecSpace, WithPlasticity>(), but for the points' velocity gradient field, which
// this pass leaves as it was (the gradient goes from the transfer to the stress update in
// registers; nothing after the step reads the field).
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
