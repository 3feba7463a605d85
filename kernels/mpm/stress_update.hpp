// Stress update (after G2P, "update stress last"): with L the velocity gradient of the step,
// d eps = sym(L) dt and spin w = (L_xy - L_yx)/2; the stress is rotated (Jaumann), incremented
// elastically and, for Mohr-Coulomb materials, returned to the yield surface. The volume follows
// det(I + L dt). Instantiated with or without plasticity so that an elastic scene pays nothing
// for it. The per-point update (update_point_stress) is also called by the fused G2P
// (g2p.hpp, g2p_stress_update), which has L at hand: Solver::step() uses that one.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/constitutive/inertial_friction.hpp"
#include "kernels/mpm/constitutive/jaumann.hpp"
#include "kernels/mpm/constitutive/linear_elastic.hpp"
#include "kernels/mpm/constitutive/mohr_coulomb.hpp"
#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

// A cheap test that a Mohr-Coulomb trial stress is clearly elastic: strictly inside the yield
// surface and below the tension cut-off by a margin (1e-9 of the stress scale) far above the
// round-off of either computation. mohr_coulomb_return() leaves such a stress unchanged and
// returns 0, so skipping it changes nothing; it saves the return mapping's divisions and sort
// for the points that stay elastic (all but the yielding zones of a mostly elastic body; in
// the collapsing benchmark column only 19 % of the point-steps, docs/notes/performance.md).
KOKKOS_FORCEINLINE_FUNCTION bool clearly_elastic(const PreparedMaterial& pm, const double s[4]) {
  const double centre = 0.5 * (s[0] + s[1]), h = 0.5 * (s[0] - s[1]);
  const double radius = math::sqrt(h * h + s[2] * s[2]);
  const double a = centre + radius, b = centre - radius;
  const double s1 = a > s[3] ? a : s[3], s3 = b < s[3] ? b : s[3];
  const double c = pm.material.cohesion, sphi = pm.sin_phi, cphi = pm.cos_phi;
  const double margin = 1e-9 * (math::fabs(s1) + math::fabs(s3) + c + 1e-300);
  const double f = (s1 - s3) + (s1 + s3) * sphi - 2.0 * c * cphi;
  // Below the apex c cot(phi) too (without the division; the margin covers its round-off).
  // `&` and `|`, not `&&` and `||`: no branches, so that a loop over points vectorises (g2p.hpp).
  return (f < -margin) & (s1 < pm.material.tension_cutoff - margin) &
         (!(sphi > 0.0) | (s1 * sphi < c * cphi - 2.0 * margin * sphi));
}

// The stress update of point q in three parts, so that a loop over many points can run the
// first and the last vectorised and only the return mapping point by point (g2p.hpp):
//  trial_point_stress:  the trial stress s (Jaumann rotation and elastic increment of the step,
//                       from the velocity gradient L); returns whether the point needs the
//                       return mapping (a Mohr-Coulomb material and not clearly elastic, or a
//                       rate-dependent one);
//  return_point_stress: the return mapping of s and the plastic work it dissipates
//                       (return_mapping_work);
//  finish_point_stress: stores s, the volume and the equivalent shear strain.
// update_point_stress runs the three in turn.
template <bool WithPlasticity, class Points>
KOKKOS_FORCEINLINE_FUNCTION bool trial_point_stress(const Points& p, const int q,
                                                    const PreparedMaterial& m, const double Lxx,
                                                    const double Lxy, const double Lyx,
                                                    const double Lyy, const double dt,
                                                    double s[4]) {
  const double de[3] = {Lxx * dt, Lyy * dt, 0.5 * (Lxy + Lyx) * dt};
  for (int k = 0; k < 4; ++k) s[k] = p.stress(q, k);
  jaumann_rotate(s, 0.5 * (Lxy - Lyx), dt);
  elastic_increment(m, de, s);
  if constexpr (WithPlasticity)
    return m.rate_dependent |
           ((m.material.model == Material::Model::MohrCoulomb) & !clearly_elastic(m, s));
  return false;
}

// The return mapping of the trial stress s; returns the plastic work density (J/m^3).
KOKKOS_INLINE_FUNCTION double return_mapping_work(const PreparedMaterial& m, const double Lxx,
                                                  const double Lxy, const double Lyx,
                                                  const double Lyy, double s[4]) {
  if (m.rate_dependent) {
    // mu(I): the friction angle of this point and step (constitutive/inertial_friction.hpp).
    const PreparedMaterial mi =
        at_inertial_state(m, shear_rate(Lxx, Lyy, 0.5 * (Lxy + Lyx)), -0.5 * (s[0] + s[1]));
    return clearly_elastic(mi, s) ? 0.0 : mohr_coulomb_return(mi, s);
  }
  return mohr_coulomb_return(m, s);
}

template <class Points>
KOKKOS_INLINE_FUNCTION void return_point_stress(const Points& p, const int q,
                                                const PreparedMaterial& m, const double Lxx,
                                                const double Lxy, const double Lyx,
                                                const double Lyy, double s[4]) {
  p.plastic_work(q) += p.volume(q) * return_mapping_work(m, Lxx, Lxy, Lyx, Lyy, s);
}

// The return mappings of the points [q0, q1) of a block of the host's blocked G2P (g2p.hpp,
// two_phase/two_phase_g2p.hpp), between its trial and finish loops: Lb and sb hold each point's
// velocity gradient and trial stress (component c of the block's point k at [c][k]),
// needs_return whether it needs the return. The Mohr-Coulomb returns in one loop over the
// block's points, without branches (mohr_coulomb_return_selected: it vectorises where the block
// has one material); the rate-dependent ones (mu(I)) point by point. needs_return is a 64-bit
// integer: GCC vectorises no selection on a bool loaded from memory in a loop of doubles.
template <int B, class Points, class MaterialOf>
KOKKOS_FORCEINLINE_FUNCTION void block_return_mappings(const Points& p, const int q0, const int q1,
                                                       const MaterialOf material_of,
                                                       const double (&Lb)[4][B], double (&sb)[4][B],
                                                       std::int64_t (&needs_return)[B]) {
  int returns = 0;
  for (int k = 0; k < q1 - q0; ++k) returns += needs_return[k] != 0 ? 1 : 0;
  if (returns == 0) return;
#pragma GCC ivdep
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    const PreparedMaterial& m = material_of(q);
    double s[4] = {sb[0][k], sb[1][k], sb[2][k], sb[3][k]};
    const double work = mohr_coulomb_return_selected(m, s);
    const bool done = !m.rate_dependent & (needs_return[k] != 0);
    for (int c = 0; c < 4; ++c) sb[c][k] = done ? s[c] : sb[c][k];
    p.plastic_work(q) += p.volume(q) * (done ? work : 0.0);
    needs_return[k] = m.rate_dependent ? needs_return[k] : 0;
  }
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    if (needs_return[k] == 0) continue;
    double s[4] = {sb[0][k], sb[1][k], sb[2][k], sb[3][k]};
    return_point_stress(p, q, material_of(q), Lb[0][k], Lb[1][k], Lb[2][k], Lb[3][k], s);
    for (int c = 0; c < 4; ++c) sb[c][k] = s[c];
  }
}

template <bool WithPlasticity, class Points>
KOKKOS_FORCEINLINE_FUNCTION void finish_point_stress(const Points& p, const int q,
                                                     const PreparedMaterial& m, const double Lxx,
                                                     const double Lxy, const double Lyx,
                                                     const double Lyy, const double dt,
                                                     const double s[4]) {
  for (int k = 0; k < 4; ++k) p.stress(q, k) = s[k];
  // Volume: J of the step; equivalent deviatoric strain increment (plane strain).
  const double J = (1.0 + Lxx * dt) * (1.0 + Lyy * dt) - Lxy * Lyx * dt * dt;
  double V = p.volume(q) * J;
  // A disconnected point: cohesionless material with no tensile strength, at zero stress (the
  // apex return gives exact zeros) and larger than its initial volume. Its grains have lost
  // contact; its volume no longer means anything (Dunatunga & Kamrin 2015 make such a state
  // stress-free below a critical density). Keeping it would make the point stiffer per unit
  // mass by V / V0 when it is compressed again (time_step.hpp), and an isolated APIC point keeps
  // its affine expansion and grows exponentially (V / V0 of 2800 in 3 s measured): the step
  // would shrink 50-fold for a speck of spray. It gets V0 back: it re-enters the continuum at
  // its initial density when it lands. Mass, momentum and stress are untouched; a zero stress
  // has no elastic energy, so the energy balance is untouched too.
  if constexpr (WithPlasticity) {
    const double V0 = p.volume0(q);
    const bool reset =
        m.disconnects & (s[0] == 0.0) & (s[1] == 0.0) & (s[2] == 0.0) & (s[3] == 0.0) & (V > V0);
    V = reset ? V0 : V;
  }
  p.volume(q) = V;
  const double de[3] = {Lxx * dt, Lyy * dt, 0.5 * (Lxy + Lyx) * dt};
  const double em = (de[0] + de[1]) / 3.0;
  const double d0 = de[0] - em, d1 = de[1] - em, d2 = -em;
  p.deviatoric_strain(q) +=
      math::sqrt(2.0 / 3.0 * (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * de[2] * de[2]));
}

// The stress, volume, plastic work and equivalent shear strain of point q, from the velocity
// gradient L of the step. `Points`: Particles, or PointArrays (particles.hpp) on the host.
template <bool WithPlasticity, class Points>
KOKKOS_FORCEINLINE_FUNCTION void update_point_stress(const Points& p, const int q,
                                                     const PreparedMaterial& m, const double Lxx,
                                                     const double Lxy, const double Lyx,
                                                     const double Lyy, const double dt) {
  double s[4];
  const bool plastic = trial_point_stress<WithPlasticity>(p, q, m, Lxx, Lxy, Lyx, Lyy, dt, s);
  if (WithPlasticity && plastic) return_point_stress(p, q, m, Lxx, Lxy, Lyx, Lyy, s);
  finish_point_stress<WithPlasticity>(p, q, m, Lxx, Lxy, Lyx, Lyy, dt, s);
}

template <class ExecSpace, bool WithPlasticity, class MemorySpace>
void stress_update(const Particles<MemorySpace>& p,
                   const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials, double dt) {
  Kokkos::parallel_for(
      WithPlasticity ? "lsi::mpm::stress_update_plastic" : "lsi::mpm::stress_update_elastic",
      range_policy<ExecSpace>(0, p.count), KOKKOS_LAMBDA(const int q) {
        update_point_stress<WithPlasticity>(
            p, q, materials(p.material(q)), p.velocity_gradient(q, 0, 0),
            p.velocity_gradient(q, 0, 1), p.velocity_gradient(q, 1, 0),
            p.velocity_gradient(q, 1, 1), dt);
      });
}

}  // namespace lsi::mpm
