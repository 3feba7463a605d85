// Two-phase grid to particle, APIC or a FLIP/PIC blend for both phases (the single-phase
// Transfer and flip ratio of g2p.hpp): with
// APIC the solid and liquid velocities are interpolated and so are their affine matrices
// C = 4/dx^2 sum w v_i (x_i - x_p)^T; with FLIP/PIC each velocity is
// r (v_p + sum w (v_i - v_i,old)) + (1 - r) sum w v_i and the affine matrices stay zero (the
// single-phase g2p.hpp's blend, per phase). Then the solid velocity gradient
// L_S = sum v_S,i grad(w)^T (for the effective stress, the volume and the porosity), the liquid
// divergence div v_L = sum v_L,i . grad(w) (for the pore pressure), and the position, which moves
// with the SOLID: x += dt sum w (v_S,i_old + v_S,i) / 2 (trapezoidal, as the single-phase g2p).
// In the same pass: the largest speed of either phase (time step), the work of the points'
// surface loads dt t_p . v_S,mid, and the health check (non-finite velocities, positions or
// pore pressures; points within one cell of the grid edge).
// With the wall correction (two_phase_p2g.hpp), the nodes strictly beyond a corrected wall are
// read as ghosts: their velocity component normal to the wall is minus that of their mirror node
// (the odd extension of the normal velocity about a symmetry plane), so that the divergence and
// velocity gradient seen by the points is the transpose of the mirror forces of P2G (a consistent
// pair: without it the correction drives a growing checkerboard of the pore pressure in the
// lowest cells). Corrected walls must lie on grid lines.
// Separable sums (as the single-phase g2p.hpp): each row of 3 nodes is summed first, then the
// row factors.
// two_phase_g2p_update() runs, in the same pass over the points, the rest of the step's point
// work with L_S and div v_L still in registers: the effective-stress update (stress_update.hpp),
// the pore pressure and porosity (pore_pressure_update.hpp, when the free-surface drainage is
// off: it needs every point's new volume first) and the time-step limits of the next step
// (two_phase_time_step.hpp). One pass over the points instead of five.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>
#include <cmath>
#include <type_traits>

#include "kernels/common/execution_instance.hpp"
#include "kernels/common/math.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/g2p.hpp"
#include "kernels/mpm/host_transpose.hpp"
#include "kernels/mpm/prefetch_points.hpp"
#include "kernels/mpm/shape_function.hpp"
#include "kernels/mpm/stress_update.hpp"
#include "kernels/mpm/two_phase/pore_pressure_update.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "kernels/mpm/two_phase/two_phase_time_step.hpp"

namespace lsi::mpm::two_phase {

struct TwoPhaseG2PReport {
  G2PReport health;        // max_speed over both phases, non_finite, outside
  double load_work = 0.0;  // J/m, work of the surface loads this step
  // two_phase_g2p_update() only:
  double viscous_work = 0.0;  // J/m, the bulk viscosity's work (pore pressure fused)
  TimeStepLimits limits;      // of the points at the end of the step (pore pressure fused)
};

// What two_phase_g2p_impl does after the transfer of a point.
struct TwoPhasePointWork {
  bool plastic = false;         // the stress update with Mohr-Coulomb (a kernel of its own)
  bool pore_pressure = false;   // pore pressure, porosity and the next step's limits
  TwoPhaseConstants constants;  // of the pore pressure and the limits
};

// The corrected walls of the ghost reads (see the file comment).
struct GhostWalls {
  bool solid[4] = {false, false, false, false};  // left, right, bottom, top
  bool liquid[4] = {false, false, false, false};
  int index[4] = {0, 0, 0, 0};  // node index of the wall line
};

namespace detail {

// Points per work item of the host's two-phase G2P (two_phase_g2p_block).
constexpr int kTwoPhaseG2PBlock = 32;

// The grids' velocities at the stencil of a point, read from the grids (with the ghost reads of
// the corrected walls when Ghosts): node(bi, bj, b, a, vs, vso, vl, vlo) gives the solid velocity
// after and before the update and the liquid's of node (bi + a, bj + b); the liquid's before
// only where LiquidOld (FLIP/PIC). The host's blocked G2P copies them into a block's arrays first
// (TwoPhaseBlockStencil).
template <bool Ghosts, bool LiquidOld, class GridVelocity>
struct TwoPhaseGridStencil {
  GridVelocity vs, vso, vl, vlo;
  int nx;
  GhostWalls ghost;
  KOKKOS_FORCEINLINE_FUNCTION void node(const int bi, const int bj, const int b, const int a,
                                        double vs_[2], double vso_[2], double vl_[2],
                                        double vlo_[2]) const {
    const int node = bi + a + nx * (bj + b);
    if constexpr (Ghosts) {
      // Ghost nodes: for each phase, the mirror node across every corrected wall the node lies
      // beyond, and which components are reflected.
      int is[2] = {bi + a, bj + b}, il[2] = {bi + a, bj + b};
      bool flip_s[2] = {false, false}, flip_l[2] = {false, false};
      for (int k = 0; k < 4; ++k) {
        const int ax = k < 2 ? 0 : 1;
        const int sg = (k == 0 || k == 2) ? 1 : -1;
        const int own = ax == 0 ? bi + a : bj + b;
        if (sg * (own - ghost.index[k]) >= 0) continue;  // not beyond this wall
        if (ghost.solid[k]) {
          is[ax] = 2 * ghost.index[k] - own;
          flip_s[ax] = true;
        }
        if (ghost.liquid[k]) {
          il[ax] = 2 * ghost.index[k] - own;
          flip_l[ax] = true;
        }
      }
      const int ms_node = is[0] + nx * is[1], ml_node = il[0] + nx * il[1];
      for (int r = 0; r < 2; ++r) {
        vs_[r] = flip_s[r] ? -vs(ms_node, r) : vs(node, r);
        vso_[r] = flip_s[r] ? -vso(ms_node, r) : vso(node, r);
        vl_[r] = flip_l[r] ? -vl(ml_node, r) : vl(node, r);
        vlo_[r] = 0.0;
        if constexpr (LiquidOld) vlo_[r] = flip_l[r] ? -vlo(ml_node, r) : vlo(node, r);
      }
    } else {
      for (int r = 0; r < 2; ++r) {
        vs_[r] = vs(node, r);
        vso_[r] = vso(node, r);
        vl_[r] = vl(node, r);
        vlo_[r] = 0.0;
        if constexpr (LiquidOld) vlo_[r] = vlo(node, r);
      }
    }
  }
};

// The stencil of point k of a block (TwoPhaseGridStencil), from the block's copies
// [row][2 node + component][point].
template <int B, bool LiquidOld>
struct TwoPhaseBlockStencil {
  const double (*vs)[6][B];
  const double (*vso)[6][B];
  const double (*vl)[6][B];
  const double (*vlo)[6][B];
  int k;
  KOKKOS_FORCEINLINE_FUNCTION void node(int, int, const int b, const int a, double vs_[2],
                                        double vso_[2], double vl_[2], double vlo_[2]) const {
    for (int r = 0; r < 2; ++r) {
      vs_[r] = vs[b][2 * a + r][k];
      vso_[r] = vso[b][2 * a + r][k];
      vl_[r] = vl[b][2 * a + r][k];
      vlo_[r] = LiquidOld ? vlo[b][2 * a + r][k] : 0.0;
    }
  }
};

// The grid-to-point transfer of point q (see the file comment): its velocities, position, affine
// matrices, solid velocity gradient and liquid divergence. Returns the solid velocity gradient
// in LS, the liquid divergence in divL, the solid's mid-step velocity in vSm and the grids'
// velocities interpolated to the point in vS and vL (the health check's speeds). LS and divL go
// into the points' fields only where store_rates: when a later pass over the points reads them
// there (the separate stress and pore pressure updates); the fused passes take them from here.
// `Points`: TwoPhaseParticles, or TwoPhasePointArrays on the host.
template <bool Apic, class Points, class Stencil>
KOKKOS_FORCEINLINE_FUNCTION void two_phase_g2p_point(
    const Points& points, const int q, const bool store_rates, const Stencil& nodes,
    const double ox, const double oy, const double dx, const double inv_dx, const double apic_scale,
    const double r_flip, const double r_pic, const double dt, double LS[2][2], double& divL,
    double vSm[2], double vS[2], double vL[2]) {
  const auto& s = points.solid;
  const double xp = s.position(q, 0) - ox, yp = s.position(q, 1) - oy;
  const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
  const double* wx = sx.w;
  const double* dwx = sx.dw;
  double wxd[3];
  offset_weights(sx, xp, dx, wxd);
  double CS[2][2] = {{0, 0}, {0, 0}}, CL[2][2] = {{0, 0}, {0, 0}};
  double vSo[2] = {0, 0}, vLo[2] = {0, 0};  // FLIP: old grid velocities
  vS[0] = vS[1] = vSm[0] = vSm[1] = vL[0] = vL[1] = 0.0;
  LS[0][0] = LS[0][1] = LS[1][0] = LS[1][1] = 0.0;
  divL = 0.0;
  // Unrolled completely, so that the host's loop over points, not these, is the one that
  // vectorises.
#pragma GCC unroll 3
  for (int b = 0; b < 3; ++b) {  // rows outside: the inner loop walks contiguous nodes
    const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
    double A0s[2] = {0, 0}, A1s[2] = {0, 0}, A2s[2] = {0, 0}, O0s[2] = {0, 0};
    double A0l[2] = {0, 0}, A1l[2] = {0, 0}, A2l = 0.0, O0l[2] = {0, 0};
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      double vs[2], vso[2], vl[2], vlo[2];
      nodes.node(sx.base, sy.base, b, a, vs, vso, vl, vlo);
#pragma GCC unroll 2
      for (int r = 0; r < 2; ++r) {
        A0s[r] += wx[a] * vs[r];
        A1s[r] += wxd[a] * vs[r];
        A2s[r] += dwx[a] * vs[r];
        O0s[r] += wx[a] * vso[r];
        A0l[r] += wx[a] * vl[r];
        A1l[r] += wxd[a] * vl[r];
        if constexpr (!Apic) O0l[r] += wx[a] * vlo[r];
      }
      A2l += dwx[a] * vl[0];
    }
#pragma GCC unroll 2
    for (int r = 0; r < 2; ++r) {
      vS[r] += wy * A0s[r];
      vSm[r] += 0.5 * wy * (A0s[r] + O0s[r]);
      CS[r][0] += wy * A1s[r];
      CS[r][1] += wy * dyb * A0s[r];
      LS[r][0] += wy * A2s[r];
      LS[r][1] += dwy * A0s[r];
      vL[r] += wy * A0l[r];
      if constexpr (!Apic) {
        vSo[r] += wy * O0s[r];
        vLo[r] += wy * O0l[r];
      }
      CL[r][0] += wy * A1l[r];
      CL[r][1] += wy * dyb * A0l[r];
    }
    divL += wy * A2l + dwy * A0l[1];
  }
#pragma GCC unroll 2
  for (int r = 0; r < 2; ++r) {
    if constexpr (Apic) {
      s.velocity(q, r) = vS[r];
      points.liquid_velocity(q, r) = vL[r];
    } else {
      s.velocity(q, r) = r_flip * (s.velocity(q, r) + vS[r] - vSo[r]) + r_pic * vS[r];
      points.liquid_velocity(q, r) =
          r_flip * (points.liquid_velocity(q, r) + vL[r] - vLo[r]) + r_pic * vL[r];
    }
    s.position(q, r) += dt * vSm[r];
#pragma GCC unroll 2
    for (int c = 0; c < 2; ++c) {
      if constexpr (Apic) {  // FLIP/PIC: the affine matrices stay zero (as built)
        s.affine(q, r, c) = apic_scale * CS[r][c];
        points.liquid_affine(q, r, c) = apic_scale * CL[r][c];
      }
      if (store_rates) s.velocity_gradient(q, r, c) = LS[r][c];
    }
  }
  if (store_rates) points.liquid_divergence(q) = divL;
}

// The health of point q after its update (see the file comment), from the speeds of the grids'
// interpolated velocities s2 = |v_S|^2 and l2 = |v_L|^2: speed = sqrt(max(s2, l2)), 0 where a
// value is not finite (counted in nonfinite); outside counts a point too close to the grid's
// edge. Without branches, so that the host's loop over a block vectorises.
template <class Points>
KOKKOS_FORCEINLINE_FUNCTION void two_phase_g2p_health(const Points& p, const int q, const double s2,
                                                      const double l2, const double ox,
                                                      const double oy, const double dx,
                                                      const double xmax, const double ymax,
                                                      double& speed, int& nonfinite, int& outside) {
  const auto& s = p.solid;
  const double x = s.position(q, 0), y = s.position(q, 1);
  const bool bad = !(s2 < 1e300) | !(l2 < 1e300) | !(x == x) | !(y == y) |
                   !(math::fabs(p.pore_pressure(q)) < 1e300);
  nonfinite += bad ? 1 : 0;
  speed = bad ? 0.0 : math::sqrt(math::max(s2, l2));
  const double px = x - ox, py = y - oy;
  outside += (px > dx) & (px < xmax) & (py > dx) & (py < ymax) ? 0 : 1;
}

// Asks the caches for the point data that two_phase_g2p_block reads or writes for the points
// [q0, q1) (prefetch_points.hpp): up to 34 streams, more than the hardware follows. The block
// calls it for the next block before its first loop. StoreRates: the block stores the velocity
// gradient and the liquid divergence (two_phase_g2p_point).
template <bool WithStress, bool Plastic, bool Pore, bool StoreRates>
KOKKOS_FORCEINLINE_FUNCTION void prefetch_block_points(const TwoPhasePointArrays& a, const int q0,
                                                       const int q1) {
  using lsi::mpm::detail::point_stream;
  using lsi::mpm::detail::prefetch_streams;
  const PointArrays& s = a.solid;
  const lsi::mpm::detail::PointStream transfer[] = {
      point_stream(s.position.c[0]),         point_stream(s.position.c[1]),
      point_stream(s.velocity.c[0]),         point_stream(s.velocity.c[1]),
      point_stream(s.affine.c[0][0]),        point_stream(s.affine.c[0][1]),
      point_stream(s.affine.c[1][0]),        point_stream(s.affine.c[1][1]),
      point_stream(a.liquid_velocity.c[0]),  point_stream(a.liquid_velocity.c[1]),
      point_stream(a.liquid_affine.c[0][0]), point_stream(a.liquid_affine.c[0][1]),
      point_stream(a.liquid_affine.c[1][0]), point_stream(a.liquid_affine.c[1][1]),
      point_stream(a.traction.c[0]),         point_stream(a.traction.c[1]),
      point_stream(a.pore_pressure.c)};
  prefetch_streams<2>(transfer, q0, q1);
  if constexpr (StoreRates) {
    const lsi::mpm::detail::PointStream rates[] = {
        point_stream(s.velocity_gradient.c[0][0]), point_stream(s.velocity_gradient.c[0][1]),
        point_stream(s.velocity_gradient.c[1][0]), point_stream(s.velocity_gradient.c[1][1]),
        point_stream(a.liquid_divergence.c)};
    prefetch_streams<2>(rates, q0, q1);
  }
  if constexpr (WithStress) {
    const lsi::mpm::detail::PointStream stress[] = {
        point_stream(s.stress.c[0]), point_stream(s.stress.c[1]),
        point_stream(s.stress.c[2]), point_stream(s.stress.c[3]),
        point_stream(s.volume.c),    point_stream(s.deviatoric_strain.c),
        point_stream(s.material.c)};
    prefetch_streams<2>(stress, q0, q1);
  }
  if constexpr (Plastic) {
    const lsi::mpm::detail::PointStream plastic[] = {point_stream(s.volume0.c),
                                                     point_stream(s.plastic_work.c)};
    prefetch_streams<2>(plastic, q0, q1);
  }
  if constexpr (Pore) {
    const lsi::mpm::detail::PointStream pore[] = {point_stream(a.volumetric_rate.c),
                                                  point_stream(a.porosity.c),
                                                  point_stream(a.conductivity.c)};
    prefetch_streams<2>(pore, q0, q1);
  }
}

// What a two-phase G2P reduces over its points (TwoPhaseG2PReport before the square root of the
// wave speed).
struct TwoPhaseG2PSums {
  double max_speed, load_work, viscous_work, max_wave_speed2, min_permeability_dt;
  int nonfinite, outside;
};

// A block of points [q0, q1) of the host's two-phase G2P, in loops over the block's points (as
// the single-phase g2p_block, g2p.hpp), after asking the caches for the next block's point data
// (prefetch_block_points):
//  1. the grids' velocities at each point's 3 x 3 stencil into the block's arrays (without
//     ghosts, in registers 8 points at a time where host_transpose.hpp is compiled in);
//  2. the transfer (two_phase_g2p_point, reading those arrays; the velocity gradient and the
//     liquid divergence stored only for a later pass: without the stress update, or without
//     the pore pressure's, Pore);
//  3. the mixture's volumetric rate (Pore) and the trial effective stress, and whether the point
//     needs the return mapping;
//  4. the return mappings where needed (block_return_mappings, stress_update.hpp);
//  5. the rest of the stress update, the pore pressure and porosity and the next step's limits
//     (Pore);
//  6. with the bulk viscosity on, its pressure and share of the limits, point by point;
//  7. the health check.
// Loops 2 to 5 and 7 (4 but for rate-dependent materials) have no branches and no dependence
// between points: the compiler vectorises them over the points. The sums and extrema go through
// arrays and are reduced after the loops in the order of the points (GCC vectorises no
// floating-point max or sum reduction).
template <bool Apic, G2PStress Stress, bool Pore, class Grid, class MaterialOf>
KOKKOS_FORCEINLINE_FUNCTION void two_phase_g2p_block(
    const TwoPhasePointArrays a, const Grid& grid, const bool ghosts, const double* const vs,
    const double* const vso, const double* const vl, const double* const vlo,
    const MaterialOf material_of, const int nx, const double ox, const double oy, const double dx,
    const double inv_dx, const double apic_scale, const double r_flip, const double r_pic,
    const double dt, const double xmax, const double ymax, const TwoPhaseConstants& constants,
    const int q0, const int q1, TwoPhaseG2PSums& sums) {
  constexpr bool with_stress = Stress != G2PStress::None;
  constexpr bool plastic = Stress == G2PStress::Plastic;
  constexpr bool store_rates = !(with_stress && Pore);
  constexpr int B = kTwoPhaseG2PBlock;
  const int count = q1 - q0;
  alignas(64) double gs[3][6][B], gso[3][6][B], gl[3][6][B], glo[Apic ? 1 : 3][6][B];
  prefetch_block_points<with_stress, plastic, Pore, store_rates>(a, q1, q1 + count);
  int k0 = 0;
#if LSI_MPM_HOST_TRANSPOSE
  // Without ghosts, 8 points at a time: each stencil row's 6 doubles of the 8 points transposed
  // in registers, per grid array (as g2p_block).
  static_assert(B % 8 == 0);
  namespace host_simd = lsi::mpm::detail::host_simd;
  if (!ghosts) {
    for (; k0 + 8 <= count; k0 += 8) {
      int first[8];
      for (int p = 0; p < 8; ++p) {
        const int q = q0 + k0 + p;
        const int bi = quadratic_bspline(a.solid.position(q, 0) - ox, inv_dx).base;
        const int bj = quadratic_bspline(a.solid.position(q, 1) - oy, inv_dx).base;
        first[p] = 2 * (bi + nx * bj);
      }
      const auto gather = [&](const double* const v, const int b, double(*out)[6][B]) {
        const double* rows[8];
        for (int p = 0; p < 8; ++p) rows[p] = v + first[p] + 2 * nx * b;
        host_simd::V8 t[6];
        host_simd::gather_rows6(rows, t);
        for (int c = 0; c < 6; ++c) host_simd::store8(&out[b][c][k0], t[c]);
      };
      for (int b = 0; b < 3; ++b) {
        gather(vs, b, gs);
        gather(vso, b, gso);
        gather(vl, b, gl);
        if constexpr (!Apic) gather(vlo, b, glo);
      }
    }
  }
#endif
  for (int q = q0 + k0; q < q1; ++q) {
    const int k = q - q0;
    const int bi = quadratic_bspline(a.solid.position(q, 0) - ox, inv_dx).base;
    const int bj = quadratic_bspline(a.solid.position(q, 1) - oy, inv_dx).base;
    if (ghosts) {
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c) {
          double v[2], vo[2], w[2], wo[2];
          grid.node(bi, bj, b, c, v, vo, w, wo);
          for (int r = 0; r < 2; ++r) {
            gs[b][2 * c + r][k] = v[r];
            gso[b][2 * c + r][k] = vo[r];
            gl[b][2 * c + r][k] = w[r];
            if constexpr (!Apic) glo[b][2 * c + r][k] = wo[r];
          }
        }
    } else {
      for (int b = 0; b < 3; ++b) {
        const int row = 2 * (bi + nx * (bj + b));
        for (int c = 0; c < 6; ++c) {
          gs[b][c][k] = vs[row + c];
          gso[b][c][k] = vso[row + c];
          gl[b][c][k] = vl[row + c];
          if constexpr (!Apic) glo[b][c][k] = vlo[row + c];
        }
      }
    }
  }
  double Lb[4][B], div[B], load[B], s2[B], l2[B];
#pragma GCC ivdep
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    double LS[2][2], divL, vSm[2], vS[2], vL[2];
    two_phase_g2p_point<Apic>(a, q, store_rates,
                              TwoPhaseBlockStencil<B, !Apic>{gs, gso, gl, glo, k}, ox, oy, dx,
                              inv_dx, apic_scale, r_flip, r_pic, dt, LS, divL, vSm, vS, vL);
    Lb[0][k] = LS[0][0];
    Lb[1][k] = LS[0][1];
    Lb[2][k] = LS[1][0];
    Lb[3][k] = LS[1][1];
    div[k] = divL;
    load[k] = dt * (a.traction(q, 0) * vSm[0] + a.traction(q, 1) * vSm[1]);
    s2[k] = vS[0] * vS[0] + vS[1] * vS[1];
    l2[k] = vL[0] * vL[0] + vL[1] * vL[1];
  }
  for (int k = 0; k < count; ++k) sums.load_work += load[k];
  if constexpr (with_stress) {
    double sb[4][B];
    std::int64_t needs_return[B];  // block_return_mappings (stress_update.hpp)
#pragma GCC ivdep
    for (int q = q0; q < q1; ++q) {
      const int k = q - q0;
      // The pore pressure update needs the porosity of the start of the step (n in D) and
      // the volume of the end (stress update first, as in the unfused sequence).
      if constexpr (Pore)
        a.volumetric_rate(q) = mixture_volumetric_rate(a.porosity(q), Lb[0][k] + Lb[3][k], div[k]);
      double s[4];
      needs_return[k] = trial_point_stress<plastic>(a.solid, q, material_of(q), Lb[0][k], Lb[1][k],
                                                    Lb[2][k], Lb[3][k], dt, s);
      for (int c = 0; c < 4; ++c) sb[c][k] = s[c];
    }
    if constexpr (plastic)
      block_return_mappings<B>(a.solid, q0, q1, material_of, Lb, sb, needs_return);
    double wave2[B], perm_dt[B];
#pragma GCC ivdep
    for (int q = q0; q < q1; ++q) {
      const int k = q - q0;
      const double s[4] = {sb[0][k], sb[1][k], sb[2][k], sb[3][k]};
      finish_point_stress<plastic>(a.solid, q, material_of(q), Lb[0][k], Lb[1][k], Lb[2][k],
                                   Lb[3][k], dt, s);
      if constexpr (Pore) {
        update_point_pore_pressure_porosity(a, q, constants, Lb[0][k], Lb[1][k], Lb[2][k], Lb[3][k],
                                            dt);
        point_wave_speed_and_permeability_step(a, q, material_of(q), constants, wave2[k],
                                               perm_dt[k]);
      }
    }
    if constexpr (Pore) {
      if (constants.viscous()) {
        for (int q = q0; q < q1; ++q) {
          const int k = q - q0;
          sums.viscous_work += update_point_viscous_pressure(a, q, material_of(q), constants, dt);
          wave2[k] = with_viscous_speed(wave2[k], a.volumetric_rate(q), constants);
        }
      }
      for (int k = 0; k < count; ++k) {
        if (wave2[k] > sums.max_wave_speed2) sums.max_wave_speed2 = wave2[k];
        if (perm_dt[k] < sums.min_permeability_dt) sums.min_permeability_dt = perm_dt[k];
      }
    }
  }
  double speed[B];
  int nonfinite = 0, outside = 0;
#pragma GCC ivdep
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    two_phase_g2p_health(a, q, s2[k], l2[k], ox, oy, dx, xmax, ymax, speed[k], nonfinite, outside);
  }
  for (int k = 0; k < count; ++k)
    sums.max_speed = speed[k] > sums.max_speed ? speed[k] : sums.max_speed;
  sums.nonfinite += nonfinite;
  sums.outside += outside;
}

}  // namespace detail

// Host spaces: each work item takes detail::kTwoPhaseG2PBlock consecutive points
// (detail::two_phase_g2p_block, whose loops vectorise over the points; the rate-dependent
// return and the bulk viscosity stay scalar). A device runs one point per thread. Both give the
// same results up to round-off.
template <class ExecSpace, bool Ghosts, G2PStress Stress, bool Apic, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p_impl(
    const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g, double dt,
    const GhostWalls& gw, const TwoPhasePointWork& work, double flip_ratio,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials = {}) {
  constexpr bool host =
      Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename ExecSpace::memory_space>::accessible;
  const auto s = p.solid;
  const auto S = g.solid;
  const auto L = g.liquid;
  const double ox = S.origin[0], oy = S.origin[1], dx = S.dx, inv_dx = 1.0 / S.dx;
  const double apic = 4.0 * inv_dx * inv_dx;
  const double xmax = (S.nx - 2) * dx, ymax = (S.ny - 2) * dx;
  const int nx = S.nx, count = p.count;
  const bool pore = work.pore_pressure;
  const TwoPhaseConstants kc = work.constants;
  const double flip = flip_ratio, pic = 1.0 - flip_ratio;
  using Velocity = decltype(S.velocity);
  const detail::TwoPhaseGridStencil<Ghosts, !Apic, Velocity> grid{
      S.velocity, S.velocity_old, L.velocity, L.velocity_old, nx, gw};
  double vmax = 0.0, load = 0.0, viscous = 0.0, cmax = 0.0, dtk = 1e300;
  int bad = 0, out = 0;
  const char* name =
      Stress == G2PStress::None ? "lsi::mpm::two_phase::g2p" : "lsi::mpm::two_phase::g2p_update";
  if constexpr (host) {
    constexpr int B = detail::kTwoPhaseG2PBlock;
    Kokkos::parallel_reduce(
        name, range_policy<ExecSpace>(0, (count + B - 1) / B),
        KOKKOS_LAMBDA(const int block, double& vm, double& wk, double& visc, double& cm, double& tk,
                      int& nonfinite, int& outside) {
          const int q0 = block * B, q1 = q0 + B < count ? q0 + B : count;
          const TwoPhasePointArrays a(p);
          const PreparedMaterial* const mats =
              Stress != G2PStress::None ? materials.data() : nullptr;
          // One material in the block (the usual case): its constants are loop invariants;
          // otherwise each point looks its material up.
          bool uniform = true;
          if constexpr (Stress != G2PStress::None) {
            for (int q = q0; q < q1; ++q) uniform &= a.solid.material(q) == a.solid.material(q0);
          }
          static_assert(std::is_same_v<typename Velocity::array_layout, Kokkos::LayoutRight>);
          const double* const vs = grid.vs.data();
          const double* const vso = grid.vso.data();
          const double* const vl = grid.vl.data();
          const double* const vlo = grid.vlo.data();
          detail::TwoPhaseG2PSums sums{vm, wk, visc, cm, tk, nonfinite, outside};
          const auto run = [&](const auto& material_of) {
            if (pore)
              detail::two_phase_g2p_block<Apic, Stress, true>(
                  a, grid, Ghosts, vs, vso, vl, vlo, material_of, nx, ox, oy, dx, inv_dx, apic,
                  flip, pic, dt, xmax, ymax, kc, q0, q1, sums);
            else
              detail::two_phase_g2p_block<Apic, Stress, false>(
                  a, grid, Ghosts, vs, vso, vl, vlo, material_of, nx, ox, oy, dx, inv_dx, apic,
                  flip, pic, dt, xmax, ymax, kc, q0, q1, sums);
          };
          if (uniform) {
            const PreparedMaterial m =
                Stress != G2PStress::None ? mats[a.solid.material(q0)] : PreparedMaterial();
            run([&m](int) -> const PreparedMaterial& { return m; });
          } else {
            run([mats, a](int q) -> const PreparedMaterial& { return mats[a.solid.material(q)]; });
          }
          vm = sums.max_speed;
          wk = sums.load_work;
          visc = sums.viscous_work;
          cm = sums.max_wave_speed2;
          tk = sums.min_permeability_dt;
          nonfinite = sums.nonfinite;
          outside = sums.outside;
        },
        Kokkos::Max<double>(vmax), load, viscous, Kokkos::Max<double>(cmax),
        Kokkos::Min<double>(dtk), bad, out);
  } else {
    Kokkos::parallel_reduce(
        name, range_policy<ExecSpace>(0, count),
        KOKKOS_LAMBDA(const int q, double& vm, double& wk, double& visc, double& cm, double& tk,
                      int& nonfinite, int& outside) {
          // Named here, outside the `if constexpr`s: nvcc rejects a lambda whose first use (and
          // so capture) of a variable is inside one.
          [[maybe_unused]] const auto& mats = materials;
          [[maybe_unused]] const bool fuse_pore = pore;
          [[maybe_unused]] const TwoPhaseConstants& constants = kc;
          [[maybe_unused]] const auto& solid = s;
          const auto& points = p;
          double LS[2][2], divL, vSm[2], vS[2], vL[2];
          const bool store_rates = Stress == G2PStress::None || !fuse_pore;
          detail::two_phase_g2p_point<Apic>(points, q, store_rates, grid, ox, oy, dx, inv_dx, apic,
                                            flip, pic, dt, LS, divL, vSm, vS, vL);
          wk += dt * (points.traction(q, 0) * vSm[0] + points.traction(q, 1) * vSm[1]);
          if constexpr (Stress != G2PStress::None) {
            const PreparedMaterial& m = mats(solid.material(q));
            // The pore pressure update needs the porosity of the start of the step (n in D) and
            // the volume of the end (stress update first, as in the unfused sequence).
            if (fuse_pore)
              points.volumetric_rate(q) =
                  mixture_volumetric_rate(points.porosity(q), LS[0][0] + LS[1][1], divL);
            update_point_stress<Stress == G2PStress::Plastic>(solid, q, m, LS[0][0], LS[0][1],
                                                              LS[1][0], LS[1][1], dt);
            if (fuse_pore) {
              visc += update_point_pore_pressure(points, q, m, constants, LS[0][0], LS[0][1],
                                                 LS[1][0], LS[1][1], dt);
              point_time_step_limits(points, q, m, constants, cm, tk);
            }
          }
          double speed;
          detail::two_phase_g2p_health(points, q, vS[0] * vS[0] + vS[1] * vS[1],
                                       vL[0] * vL[0] + vL[1] * vL[1], ox, oy, dx, xmax, ymax, speed,
                                       nonfinite, outside);
          if (speed > vm) vm = speed;
        },
        Kokkos::Max<double>(vmax), load, viscous, Kokkos::Max<double>(cmax),
        Kokkos::Min<double>(dtk), bad, out);
  }
  TwoPhaseG2PReport r;
  r.health.max_speed = vmax;
  r.health.non_finite = bad;
  r.health.outside = out;
  r.load_work = load;
  r.viscous_work = viscous;
  r.limits.wave_speed = cmax > 0.0 ? std::sqrt(cmax) : 0.0;  // the reduction took c^2
  r.limits.permeability_dt = dtk;
  return r;
}

// The ghost walls from the corrected walls (nullptr: none).
inline GhostWalls ghost_walls(const Boundaries* walls, const Boundaries* liquid_walls,
                              const double origin[2], double inv_dx) {
  const Boundaries none;
  const Boundaries& sw = walls ? *walls : none;
  const Boundaries& lw = liquid_walls ? *liquid_walls : none;
  const Wall* ws[4] = {&sw.left, &sw.right, &sw.bottom, &sw.top};
  const Wall* wl[4] = {&lw.left, &lw.right, &lw.bottom, &lw.top};
  GhostWalls gw;
  for (int k = 0; k < 4; ++k) {
    gw.solid[k] = ws[k]->active;
    gw.liquid[k] = wl[k]->active;
    const Wall& w = ws[k]->active ? *ws[k] : *wl[k];
    gw.index[k] = static_cast<int>((w.position - origin[k < 2 ? 0 : 1]) * inv_dx + 0.5);
  }
  return gw;
}

// The instantiation for the transfer: APIC, or the FLIP/PIC blend with flip_ratio r in [0, 1]
// (1: FLIP, 0: PIC; unused with APIC).
template <class ExecSpace, bool Ghosts, G2PStress Stress, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p_transfer(
    const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g, double dt,
    const GhostWalls& gw, const TwoPhasePointWork& work, Transfer transfer, double flip_ratio,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials = {}) {
  if (transfer == Transfer::Apic)
    return two_phase_g2p_impl<ExecSpace, Ghosts, Stress, true>(p, g, dt, gw, work, 0.0, materials);
  return two_phase_g2p_impl<ExecSpace, Ghosts, Stress, false>(p, g, dt, gw, work, flip_ratio,
                                                              materials);
}

// G2P of both phases alone (the points' stress, pore pressure and porosity untouched).
template <class ExecSpace, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p(const TwoPhaseParticles<MemorySpace>& p,
                                const TwoPhaseGrid<MemorySpace>& g, double dt,
                                const Boundaries* walls = nullptr,
                                const Boundaries* liquid_walls = nullptr,
                                Transfer transfer = Transfer::Apic, double flip_ratio = 0.0) {
  const GhostWalls gw = ghost_walls(walls, liquid_walls, g.solid.origin, 1.0 / g.dx());
  const TwoPhasePointWork none;
  constexpr G2PStress N = G2PStress::None;
  if (walls != nullptr || liquid_walls != nullptr)
    return two_phase_g2p_transfer<ExecSpace, true, N>(p, g, dt, gw, none, transfer, flip_ratio);
  return two_phase_g2p_transfer<ExecSpace, false, N>(p, g, dt, gw, none, transfer, flip_ratio);
}

// G2P of both phases and the point updates that follow it (see the file comment): the effective
// stress always, the pore pressure, porosity and next step's limits when work.pore_pressure
// (then r.viscous_work and r.limits are set, and the points' velocity gradient and liquid
// divergence fields are left as they were: nothing after the pass reads them).
template <class ExecSpace, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p_update(
    const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g, double dt,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials,
    const TwoPhasePointWork& work, const Boundaries* walls = nullptr,
    const Boundaries* liquid_walls = nullptr, Transfer transfer = Transfer::Apic,
    double flip_ratio = 0.0) {
  const GhostWalls gw = ghost_walls(walls, liquid_walls, g.solid.origin, 1.0 / g.dx());
  const bool ghosts = walls != nullptr || liquid_walls != nullptr;
  constexpr G2PStress E = G2PStress::Elastic, P = G2PStress::Plastic;
  const Transfer t = transfer;
  const double r = flip_ratio;
  if (ghosts)
    return work.plastic
               ? two_phase_g2p_transfer<ExecSpace, true, P>(p, g, dt, gw, work, t, r, materials)
               : two_phase_g2p_transfer<ExecSpace, true, E>(p, g, dt, gw, work, t, r, materials);
  return work.plastic
             ? two_phase_g2p_transfer<ExecSpace, false, P>(p, g, dt, gw, work, t, r, materials)
             : two_phase_g2p_transfer<ExecSpace, false, E>(p, g, dt, gw, work, t, r, materials);
}

}  // namespace lsi::mpm::two_phase
