// Two-phase particle to grid with the single-phase P2G's two passes (p2g.hpp: a scatter into
// node-interleaved buffers, 11 doubles per node, per thread or atomic, then a gather over the
// touched rectangle of nodes, and its row spans, that leaves the grids' active rectangles and
// spans for the grid update).
// Per node i and point p, w = w_ip, with APIC momenta:
//   solid   mass     w m_S                 momentum w m_S (v_S + C_S (x_i - x_p))
//   liquid  mass     w m_L                 momentum w m_L (v_L + C_L (x_i - x_p))
//   mixture force   -V (sigma' - p I) grad(w) + w (m_S + m_L) g + w t_p      (t_p: surface load)
//   liquid  force   +V n p grad(w) + w m_L g     (weak form of -n grad p; the free surface
//                                                 term drops out: natural drained p = 0)
//   drag    Q       w V n^2 rho_L g_D / k        (g_D: the g in the definition of k)
// where p stands for p + q, q >= 0 the artificial bulk viscosity of the point
// (pore_pressure_update.hpp; zero when it is off).
//
// Optional wall correction (TwoPhaseSettings::wall_correction). A wall acts on the nodes on or
// beyond it, but the quadratic B-spline of the first free node above a wall is still 1/8 on the
// wall, so that free node takes 1/8 of the wall's reaction in the weak form and misses it: the
// points of the lowest cell layers carry a decaying +15 %, -5 %, +2 % pattern of the stress and
// pore pressure (the boundary layer of docs/theory/mpm.md, test_mpm_geostatic.cpp). With the correction,
// each point within 1.5 cells of an active wall adds, to the free nodes only (those more than
// 1e-9 dx inside the wall) and to the force component NORMAL to the wall only, the force of its
// mirror image across the wall (a symmetry plane: same normal stresses and pore pressure, shear
// stress and normal gravity reversed). For a field symmetric about the wall this completes the
// partition of unity, i.e. it is the missing share N_j(wall) sigma_nn of the wall reaction. The
// mixture force is corrected for `walls`, the liquid force for `liquid_walls` (impermeable
// walls). Valid while the material rests against the wall (a column, a deposit, a flow on its
// base); a body approaching a wall through the air would feel its mirror within 1.5 cells.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstddef>
#include <type_traits>

#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/p2g.hpp"
#include "kernels/mpm/prefetch_points.hpp"
#include "kernels/mpm/shape_function.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

// The interleaved record of a node in the two-phase P2G's buffers.
namespace node_field {
enum : int {
  SolidMass,
  SolidMomentumX,
  SolidMomentumY,
  MixtureForceX,
  MixtureForceY,
  LiquidMass,
  LiquidMomentumX,
  LiquidMomentumY,
  LiquidForceX,
  LiquidForceY,
  Drag,
  Padding,  // unused: the record is 12 doubles, so that the host adds it in vectors of 8 and 4
  Count
};
}

template <class ExecSpace, bool Atomic>
using TwoPhaseScatter = P2GScatter<ExecSpace, Atomic, node_field::Count>;

// The walls of the mirror correction, relative to the grid origin (see the file comment).
struct MirrorWalls {
  bool any = false;
  bool solid[4] = {false, false, false, false};  // left, right, bottom, top
  bool liquid[4] = {false, false, false, false};
  double at[4] = {0.0, 0.0, 0.0, 0.0};
};

namespace detail {

// The 3 x 3 x node_field::Count values point q adds to the nodes of its stencil (sx, sy, which it
// returns): add(b, a, field, value) for node (sx.base + a, sy.base + b). The point-by-point
// scatter's (two_phase_p2g_point); the host's blocked one (two_phase_p2g_block) gives the same
// sums up to round-off.
// `Points`: TwoPhaseParticles, or TwoPhasePointArrays on the host.
template <class Points, class Add>
KOKKOS_FORCEINLINE_FUNCTION void two_phase_point_contributions(const Points& p, const int q,
                                                               const double ox, const double oy,
                                                               const double dx, const double inv_dx,
                                                               const double gx, const double gy,
                                                               const double rhoLg, Stencil1D& sx,
                                                               Stencil1D& sy, const Add& add) {
  namespace nf = node_field;
  const auto& s = p.solid;
  const double xp = s.position(q, 0) - ox, yp = s.position(q, 1) - oy;
  sx = quadratic_bspline(xp, inv_dx);
  sy = quadratic_bspline(yp, inv_dx);
  const double mS = s.mass(q), mL = p.liquid_mass(q), V = s.volume(q);
  // p + q: the artificial bulk viscosity acts like a pore pressure (pore_pressure_update.hpp)
  const double n = p.porosity(q), pw = p.pore_pressure(q) + p.viscous_pressure(q);
  // total stress times volume (tension positive)
  const double Vs[3] = {V * (s.stress(q, 0) - pw), V * (s.stress(q, 1) - pw), V * s.stress(q, 2)};
  const double Vnp = V * n * pw;
  const double Q = V * n * n * rhoLg / p.conductivity(q);
  const double fext[2] = {(mS + mL) * gx + p.traction(q, 0), (mS + mL) * gy + p.traction(q, 1)};
  const double fLext[2] = {mL * gx, mL * gy};
  const double mvS[2] = {mS * s.velocity(q, 0), mS * s.velocity(q, 1)};
  const double mvL[2] = {mL * p.liquid_velocity(q, 0), mL * p.liquid_velocity(q, 1)};
  const double mCS[2][2] = {{mS * s.affine(q, 0, 0), mS * s.affine(q, 0, 1)},
                            {mS * s.affine(q, 1, 0), mS * s.affine(q, 1, 1)}};
  const double mCL[2][2] = {{mL * p.liquid_affine(q, 0, 0), mL * p.liquid_affine(q, 0, 1)},
                            {mL * p.liquid_affine(q, 1, 0), mL * p.liquid_affine(q, 1, 1)}};
  // Separable weights w = wx(a) wy(b), as the single-phase p2g_point: per node
  //   momentum  w (m v + m C (x_i - x_p))   = wx P[r] + wx dxa Q[r]
  //   forces    a.grad(w) + w f              = dwx F1[r] + wx F0[r]
  // with the row factors below.
  const double* wx = sx.w;
  const double* dwx = sx.dw;
  double wxd[3];
  offset_weights(sx, xp, dx, wxd);
#pragma GCC unroll 3
  for (int b = 0; b < 3; ++b) {
    const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
    double PS[2], QS[2], PL[2], QL[2];
    lsi::mpm::detail::apic_row_factors(wy, dyb, mvS, mCS, PS, QS);
    lsi::mpm::detail::apic_row_factors(wy, dyb, mvL, mCL, PL, QL);
    // mixture: -(Vs . grad w) + w fext;  liquid: Vnp grad w + w fLext
    const double FS1[2] = {-Vs[0] * wy, -Vs[2] * wy};
    const double FS0[2] = {-Vs[2] * dwy + wy * fext[0], -Vs[1] * dwy + wy * fext[1]};
    const double FL1 = Vnp * wy;
    const double FL0[2] = {wy * fLext[0], Vnp * dwy + wy * fLext[1]};
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      const double w = wx[a] * wy;
      add(b, a, nf::SolidMass, w * mS);
      add(b, a, nf::SolidMomentumX, wx[a] * PS[0] + wxd[a] * QS[0]);
      add(b, a, nf::SolidMomentumY, wx[a] * PS[1] + wxd[a] * QS[1]);
      add(b, a, nf::MixtureForceX, dwx[a] * FS1[0] + wx[a] * FS0[0]);
      add(b, a, nf::MixtureForceY, dwx[a] * FS1[1] + wx[a] * FS0[1]);
      add(b, a, nf::LiquidMass, w * mL);
      add(b, a, nf::LiquidMomentumX, wx[a] * PL[0] + wxd[a] * QL[0]);
      add(b, a, nf::LiquidMomentumY, wx[a] * PL[1] + wxd[a] * QL[1]);
      add(b, a, nf::LiquidForceX, dwx[a] * FL1 + wx[a] * FL0[0]);
      add(b, a, nf::LiquidForceY, wx[a] * FL0[1]);
      add(b, a, nf::Drag, w * Q);
    }
  }
}

// The forces of point q's mirror images (see the file comment) into the interleaved buffer
// `buf` (node (i, j) at node_field::Count tile.offset(i, j)). Wall k: axis a (0: x, 1: y),
// position c, inward sign s (+1: the material is on the side of larger coordinates). The free
// nodes of an image's stencil lie in the point's own stencil (the point is within 1.5 cells of
// the wall), so the touched rectangle and its row spans cover them.
template <bool Atomic, class Points>
KOKKOS_INLINE_FUNCTION void two_phase_p2g_mirrors(const Points& p, const int q, double* buf,
                                                  const lsi::mpm::detail::NodeTile& tile,
                                                  const double ox, const double oy, const double dx,
                                                  const double inv_dx, const double gx,
                                                  const double gy, const MirrorWalls& mw) {
  using lsi::mpm::detail::scatter_add;
  namespace nf = node_field;
  constexpr int F = nf::Count;
  const auto& s = p.solid;
  const double xp = s.position(q, 0) - ox, yp = s.position(q, 1) - oy;
  const double mS = s.mass(q), mL = p.liquid_mass(q), V = s.volume(q);
  const double n = p.porosity(q), pw = p.pore_pressure(q) + p.viscous_pressure(q);
  const double Vs[3] = {V * (s.stress(q, 0) - pw), V * (s.stress(q, 1) - pw), V * s.stress(q, 2)};
  const double Vnp = V * n * pw;
  const double tol = 1e-9 * dx;
  for (int k = 0; k < 4; ++k) {
    const bool solid_wall = mw.solid[k], liquid_wall = mw.liquid[k];
    if (!solid_wall && !liquid_wall) continue;
    const int ax = k < 2 ? 0 : 1;
    const double c = mw.at[k], sgn = (k == 0 || k == 2) ? 1.0 : -1.0;
    const double pos[2] = {xp, yp};
    const double dist = sgn * (pos[ax] - c);  // > 0 inside
    if (!(dist > 0.0 && dist < 1.5 * dx)) continue;
    double mpos[2] = {xp, yp};
    mpos[ax] = 2.0 * c - pos[ax];
    const Stencil1D mx = quadratic_bspline(mpos[0], inv_dx);
    const Stencil1D my = quadratic_bspline(mpos[1], inv_dx);
    // Normal force of the image: -V (sigma_nn d_n w - sigma_nt d_t w) - w m g_n (mixture),
    // V n p d_n w - w m_L g_n (liquid).
    const double snn = Vs[ax == 0 ? 0 : 1], snt = Vs[2];
    const double gn = ax == 0 ? gx : gy;
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a) {
        const int ni[2] = {mx.base + a, my.base + b};
        if (!(sgn * (ni[ax] * dx - c) > tol)) continue;  // free nodes only
        double* node = buf + F * tile.offset(ni[0], ni[1]);
        const double w = mx.w[a] * my.w[b];
        const double gw[2] = {mx.dw[a] * my.w[b], mx.w[a] * my.dw[b]};
        if (solid_wall)
          scatter_add<Atomic>(node + nf::MixtureForceX + ax,
                              -(snn * gw[ax] - snt * gw[1 - ax]) - w * (mS + mL) * gn);
        if (liquid_wall)
          scatter_add<Atomic>(node + nf::LiquidForceX + ax, Vnp * gw[ax] - w * mL * gn);
      }
  }
}

// Point q's contributions (3 x 3 nodes, and its mirror images' within the same stencil) into the
// interleaved buffer `buf` (node (i, j) at node_field::Count tile.offset(i, j)); (bi, bj): the
// first node of its stencil.
template <bool Atomic, class MemorySpace>
KOKKOS_FORCEINLINE_FUNCTION void two_phase_p2g_point(
    const TwoPhaseParticles<MemorySpace>& p, const int q, double* buf,
    const lsi::mpm::detail::NodeTile& tile, const double ox, const double oy, const double dx,
    const double inv_dx, const double gx, const double gy, const double rhoLg,
    const MirrorWalls& mw, int& bi, int& bj) {
  using lsi::mpm::detail::scatter_add;
  constexpr int F = node_field::Count;
  Stencil1D sx, sy;
  two_phase_point_contributions(p, q, ox, oy, dx, inv_dx, gx, gy, rhoLg, sx, sy,
                                [&](const int b, const int a, const int field, const double v) {
                                  scatter_add<Atomic>(
                                      buf + F * tile.offset(sx.base + a, sy.base + b) + field, v);
                                });
  bi = sx.base;
  bj = sy.base;
  if (mw.any) two_phase_p2g_mirrors<Atomic>(p, q, buf, tile, ox, oy, dx, inv_dx, gx, gy, mw);
}

// The host's scatter of points [q0, q1) (plain additions into one buffer), in two loops:
//  1. per point, the stencil's weights and the factors of its contributions, in a loop with no
//     branches and no dependence between the points, which the compiler vectorises over the
//     points (component arrays, particles.hpp);
//  2. point after point (neighbouring points add into the same nodes), the factors as vectors
//     over the node's record (node_field::Count is padded to 12 doubles, a vector of 8 and one
//     of 4), so that each node takes two vector additions. Node (bi + a, bj + b) adds
//       lo += wx_a R_b + T_a (wy_b DE),   hi += wx_a H_b + dwx_a wy_b (Vnp, 0, 0, 0)
//     with R_b = wy_b A + wy_b dy_b Bv + dwy_b Cv and H_b = wy_b Ah + dwy_b (0, Vnp, 0, 0)
//     (the per-point vectors below). T_a is wxd_a on the momentum lanes and dwx_a on the
//     mixture force lanes, where DE holds the affine factors m C_.x and the stress terms of
//     d/dx respectively: their lanes do not overlap, so one product serves both.
//     Then the point's mirror images (the order of two_phase_p2g_point).
// Between the two, the next block's point data is prefetched (prefetch_points.hpp): loop 1 reads
// 26 streams with little arithmetic between the loads and, on its own, waits for memory;
// prefetched, the loads overlap loop 2's arithmetic (the dry P2G's first loop, 13 streams,
// measured no gain from it). The sums of two_phase_point_contributions up to round-off. Widens `touched` by the stencils.
inline void two_phase_p2g_block(const TwoPhasePointArrays p, const int q0, const int q1,
                                double* const buf, const int nx, const double ox, const double oy,
                                const double dx, const double inv_dx, const double gx,
                                const double gy, const double rhoLg, const MirrorWalls& mw,
                                lsi::mpm::detail::TouchedNodes& touched) {
  namespace nf = node_field;
  constexpr int F = nf::Count, B = lsi::mpm::detail::kP2GBlock;
  // The record as a vector of 8 fields and one of 4: (SolidMass, SolidMomentumX,
  // SolidMomentumY, MixtureForceX, MixtureForceY, LiquidMass, LiquidMomentumX,
  // LiquidMomentumY), (LiquidForceX, LiquidForceY, Drag, Padding).
  static_assert(nf::MixtureForceX == 3 && nf::LiquidMomentumY == 7 && nf::Drag == 10 && F == 12);
  typedef double Oct __attribute__((vector_size(64), aligned(8)));
  typedef double Quad __attribute__((vector_size(32), aligned(8)));
  // Loop 1's results, B points per row: the factors of A (mass, m v, external mixture force),
  // Bv (m C_.y), Cv (-V sigma_xy, -V sigma_yy total), D (m C_.x), E (-V sigma_xx total, and
  // -V sigma_xy again from Cv's row), the liquid's gravity force, the drag coefficient and V n p.
  // clang-format off
  enum : int {
    kMassS, kMomSx, kMomSy, kForceX, kForceY, kMassL, kMomLx, kMomLy,  // A
    kAffSxy, kAffSyy, kAffLxy, kAffLyy,                                 // Bv
    kStressXy, kStressYy,                                               // Cv
    kAffSxx, kAffSyx, kAffLxx, kAffLyx,                                 // D
    kStressXx,                                                          // E
    kGravityLx, kGravityLy, kDrag, kVnp,
    kFactors
  };
  // clang-format on
  alignas(64) double f[kFactors][B];
  alignas(64) double wx[3][B], wxd[3][B], dwx[3][B], wy[3][B], wyd[3][B], dwy[3][B];
  int first_i[B], first_j[B];
  const auto& s = p.solid;
#pragma GCC ivdep
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    const double xp = s.position(q, 0) - ox, yp = s.position(q, 1) - oy;
    const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
    const double mS = s.mass(q), mL = p.liquid_mass(q), V = s.volume(q);
    const double n = p.porosity(q), pw = p.pore_pressure(q) + p.viscous_pressure(q);
    const double Vs[3] = {V * (s.stress(q, 0) - pw), V * (s.stress(q, 1) - pw), V * s.stress(q, 2)};
    double offset[3];
    offset_weights(sx, xp, dx, offset);
    for (int a = 0; a < 3; ++a) {
      wx[a][k] = sx.w[a];
      wxd[a][k] = offset[a];
      dwx[a][k] = sx.dw[a];
      wy[a][k] = sy.w[a];
      wyd[a][k] = sy.w[a] * ((sy.base + a) * dx - yp);
      dwy[a][k] = sy.dw[a];
    }
    first_i[k] = sx.base;
    first_j[k] = sy.base;
    f[kMassS][k] = mS;
    f[kMomSx][k] = mS * s.velocity(q, 0);
    f[kMomSy][k] = mS * s.velocity(q, 1);
    f[kForceX][k] = (mS + mL) * gx + p.traction(q, 0);
    f[kForceY][k] = (mS + mL) * gy + p.traction(q, 1);
    f[kMassL][k] = mL;
    f[kMomLx][k] = mL * p.liquid_velocity(q, 0);
    f[kMomLy][k] = mL * p.liquid_velocity(q, 1);
    f[kAffSxy][k] = mS * s.affine(q, 0, 1);
    f[kAffSyy][k] = mS * s.affine(q, 1, 1);
    f[kAffLxy][k] = mL * p.liquid_affine(q, 0, 1);
    f[kAffLyy][k] = mL * p.liquid_affine(q, 1, 1);
    f[kStressXy][k] = -Vs[2];
    f[kStressYy][k] = -Vs[1];
    f[kAffSxx][k] = mS * s.affine(q, 0, 0);
    f[kAffSyx][k] = mS * s.affine(q, 1, 0);
    f[kAffLxx][k] = mL * p.liquid_affine(q, 0, 0);
    f[kAffLyx][k] = mL * p.liquid_affine(q, 1, 0);
    f[kStressXx][k] = -Vs[0];
    f[kGravityLx][k] = mL * gx;
    f[kGravityLy][k] = mL * gy;
    f[kDrag][k] = V * n * n * rhoLg / p.conductivity(q);
    f[kVnp][k] = V * n * pw;
  }
  // The lanes of T_a: wxd_a on the momentum lanes, dwx_a on the mixture force lanes.
  const Oct momentum_lanes = {0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0};
  const Oct force_lanes = {0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0};
  const lsi::mpm::detail::NodeTile grid{0, 0, nx};
  using lsi::mpm::detail::point_stream;
  const lsi::mpm::detail::PointStream streams[] = {point_stream(s.position.c[0]),
                                                   point_stream(s.position.c[1]),
                                                   point_stream(s.velocity.c[0]),
                                                   point_stream(s.velocity.c[1]),
                                                   point_stream(s.affine.c[0][0]),
                                                   point_stream(s.affine.c[0][1]),
                                                   point_stream(s.affine.c[1][0]),
                                                   point_stream(s.affine.c[1][1]),
                                                   point_stream(s.stress.c[0]),
                                                   point_stream(s.stress.c[1]),
                                                   point_stream(s.stress.c[2]),
                                                   point_stream(s.mass.c),
                                                   point_stream(s.volume.c),
                                                   point_stream(p.liquid_mass.c),
                                                   point_stream(p.porosity.c),
                                                   point_stream(p.pore_pressure.c),
                                                   point_stream(p.viscous_pressure.c),
                                                   point_stream(p.conductivity.c),
                                                   point_stream(p.liquid_velocity.c[0]),
                                                   point_stream(p.liquid_velocity.c[1]),
                                                   point_stream(p.traction.c[0]),
                                                   point_stream(p.traction.c[1]),
                                                   point_stream(p.liquid_affine.c[0][0]),
                                                   point_stream(p.liquid_affine.c[0][1]),
                                                   point_stream(p.liquid_affine.c[1][0]),
                                                   point_stream(p.liquid_affine.c[1][1])};
  lsi::mpm::detail::prefetch_streams(streams, q1, q1 + (q1 - q0));
  touched.widen_block(first_i, first_j, q1 - q0);
  for (int k = 0; k < q1 - q0; ++k) {
    const Oct A = {f[kMassS][k],  f[kMomSx][k], f[kMomSy][k], f[kForceX][k],
                   f[kForceY][k], f[kMassL][k], f[kMomLx][k], f[kMomLy][k]};
    const Oct Bv = {0.0, f[kAffSxy][k], f[kAffSyy][k], 0.0, 0.0, 0.0, f[kAffLxy][k], f[kAffLyy][k]};
    const Oct Cv = {0.0, 0.0, 0.0, f[kStressXy][k], f[kStressYy][k], 0.0, 0.0, 0.0};
    const Oct DE = {0.0, f[kAffSxx][k], f[kAffSyx][k], f[kStressXx][k], f[kStressXy][k],
                    0.0, f[kAffLxx][k], f[kAffLyx][k]};
    const Quad Ah = {f[kGravityLx][k], f[kGravityLy][k], f[kDrag][k], 0.0};
    const double Vnp = f[kVnp][k];
    const Quad Ch = {0.0, Vnp, 0.0, 0.0}, Eh = {Vnp, 0.0, 0.0, 0.0};
    Oct T[3];
    for (int a = 0; a < 3; ++a) T[a] = wxd[a][k] * momentum_lanes + dwx[a][k] * force_lanes;
    const int bi = first_i[k], bj = first_j[k];
    for (int b = 0; b < 3; ++b) {
      const double y = wy[b][k], yd = wyd[b][k], dy = dwy[b][k];
      const Oct R = y * A + yd * Bv + dy * Cv, RDE = y * DE;
      const Quad H = y * Ah + dy * Ch, H2 = y * Eh;
      double* row = buf + F * (bi + nx * (bj + b));
      for (int a = 0; a < 3; ++a) {
        Oct* lo = reinterpret_cast<Oct*>(row + F * a);
        Quad* hi = reinterpret_cast<Quad*>(row + F * a + 8);
        *lo += wx[a][k] * R + T[a] * RDE;
        *hi += wx[a][k] * H + dwx[a][k] * H2;
      }
    }
    if (mw.any) two_phase_p2g_mirrors<false>(p, q0 + k, buf, grid, ox, oy, dx, inv_dx, gx, gy, mw);
  }
}

// two_phase_p2g_block as the block function of scatter_points.
template <class MemorySpace>
struct TwoPhaseP2GBlock {
  TwoPhaseParticles<MemorySpace> p;
  int nx;
  double ox, oy, dx, inv_dx, gx, gy, rhoLg;
  MirrorWalls mw;
  KOKKOS_INLINE_FUNCTION void operator()(const int q0, const int q1, double* buf,
                                         lsi::mpm::detail::TouchedNodes& touched) const {
#if !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)  // host buffers only
    two_phase_p2g_block(TwoPhasePointArrays(p), q0, q1, buf, nx, ox, oy, dx, inv_dx, gx, gy, rhoLg,
                        mw, touched);
#endif
  }
};

}  // namespace detail

namespace detail {

// Pass 1 of two_phase_p2g (the points' contributions into the scatter's buffers); returns the
// rectangle of touched nodes.
template <class ExecSpace, bool Atomic, class MemorySpace>
NodeBox two_phase_scatter(const TwoPhaseParticles<MemorySpace>& p,
                          const TwoPhaseGrid<MemorySpace>& g,
                          TwoPhaseScatter<ExecSpace, Atomic>& scatter, const double gravity[2],
                          double liquid_density, double darcy_gravity, const Boundaries* walls,
                          const Boundaries* liquid_walls) {
  using S = TwoPhaseScatter<ExecSpace, Atomic>;
  const double ox = g.solid.origin[0], oy = g.solid.origin[1], dx = g.solid.dx;
  const double inv_dx = 1.0 / dx;
  const int nx = g.solid.nx;
  const double gx = gravity[0], gy = gravity[1], rhoLg = liquid_density * darcy_gravity;
  // Walls for the correction, relative to the grid origin: left, right, bottom, top.
  MirrorWalls mw;
  mw.any = walls != nullptr || liquid_walls != nullptr;
  const Boundaries none;
  const Boundaries& sw = walls ? *walls : none;
  const Boundaries& lw = liquid_walls ? *liquid_walls : none;
  const Wall* ws[4] = {&sw.left, &sw.right, &sw.bottom, &sw.top};
  const Wall* wl[4] = {&lw.left, &lw.right, &lw.bottom, &lw.top};
  for (int k = 0; k < 4; ++k) {
    mw.solid[k] = ws[k]->active;
    mw.liquid[k] = wl[k]->active;
    mw.at[k] = (ws[k]->active ? ws[k]->position : wl[k]->position) - (k < 2 ? ox : oy);
  }
  // Host buffers with plain additions: the blocked scatter (two_phase_p2g_block).
  using Block = std::conditional_t<S::atomic, std::nullptr_t, TwoPhaseP2GBlock<MemorySpace>>;
  Block block{};
  if constexpr (!S::atomic) block = {p, nx, ox, oy, dx, inv_dx, gx, gy, rhoLg, mw};
  return lsi::mpm::detail::scatter_points(
      scatter, p.solid.position, p.count, ox, oy, inv_dx, nx,
      KOKKOS_LAMBDA(const int q, double* buf, const lsi::mpm::detail::NodeTile& tile, int& bi,
                    int& bj) {
        two_phase_p2g_point<S::atomic>(p, q, buf, tile, ox, oy, dx, inv_dx, gx, gy, rhoLg, mw, bi,
                                       bj);
      },
      block);
}

}  // namespace detail

template <class ExecSpace, bool Atomic, class MemorySpace>
void two_phase_p2g(const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g,
                   TwoPhaseScatter<ExecSpace, Atomic>& scatter, const double gravity[2],
                   double liquid_density, double darcy_gravity, const Boundaries* walls = nullptr,
                   const Boundaries* liquid_walls = nullptr) {
  namespace nf = node_field;
  const NodeBox touched = detail::two_phase_scatter(p, g, scatter, gravity, liquid_density,
                                                    darcy_gravity, walls, liquid_walls);
  const auto S_ = g.solid;
  const auto L_ = g.liquid;
  const auto drag = g.drag;
  const P2GBoxes boxes = lsi::mpm::detail::gather_nodes(
      scatter, touched, g.solid.whole(), g.solid.dirty_box(), g.solid.dirty_rows(), g.solid.nx,
      KOKKOS_LAMBDA(const int n, const double* acc) {
        S_.mass(n) = acc[nf::SolidMass];
        S_.momentum(n, 0) = acc[nf::SolidMomentumX];
        S_.momentum(n, 1) = acc[nf::SolidMomentumY];
        S_.force(n, 0) = acc[nf::MixtureForceX];
        S_.force(n, 1) = acc[nf::MixtureForceY];
        L_.mass(n) = acc[nf::LiquidMass];
        L_.momentum(n, 0) = acc[nf::LiquidMomentumX];
        L_.momentum(n, 1) = acc[nf::LiquidMomentumY];
        L_.force(n, 0) = acc[nf::LiquidForceX];
        L_.force(n, 1) = acc[nf::LiquidForceY];
        drag(n) = acc[nf::Drag];
      });
  for (const auto* grid : {&g.solid, &g.liquid}) {
    grid->set_mass_box(boxes.mass, boxes.mass_rows);
    grid->set_dirty_box(boxes.dirty, boxes.dirty_rows);
  }
}

}  // namespace lsi::mpm::two_phase
