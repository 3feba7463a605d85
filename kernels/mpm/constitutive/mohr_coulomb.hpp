// Mohr-Coulomb perfect plasticity with a non-associated flow rule (dilatancy psi), cohesion and a
// tension cut-off, in plane strain. Tension positive; principal stresses s1 >= s2 >= s3 (sigma_zz
// is one of them). Yield and plastic potential:
//   f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi),    g = (s1 - s3) + (s1 + s3) sin(psi)
// Return mapping in principal space (closest-point for the elastic metric, exact for linear
// elasticity and perfect plasticity; de Souza Neto, Peric & Owen, "Computational Methods for
// Plasticity", 2008, ch. 8): the main plane; if the returned stresses leave the sextant, one of the
// two edges (s1 = s2 or s2 = s3, two active planes); if that fails too, the apex
// s1 = s2 = s3 = c cot(phi). Finally principal stresses above the tension cut-off are capped.
// mohr_coulomb_return() takes these routes with branches (the device's and the scalar path);
// mohr_coulomb_return_selected() computes them all and selects, for loops that vectorise.
// Returns the plastic work density of the step, sigma : d eps_p (J/m^3).
#pragma once
#include "kernels/mpm/constitutive/material.hpp"

namespace lsi::mpm {

// The trial stress in principal space: in-plane major a >= minor b (centre +- radius, h the
// half difference of the normal stresses) and the out-of-plane z = s_zz, ordered
// s1 >= s2 >= s3 in `value` (ties keep the in-plane value first, a stable sort of a, b, z).
// Selections on single comparisons only: a loop over points keeps them as vector masks (GCC
// vectorises no selection on a combination of comparisons).
struct PrincipalTrial {
  double h, radius, a, b, z, value[3];
};

KOKKOS_FORCEINLINE_FUNCTION PrincipalTrial principal_trial(const double s[4]) {
  PrincipalTrial t;
  const double centre = 0.5 * (s[0] + s[1]);
  t.h = 0.5 * (s[0] - s[1]);
  t.radius = math::sqrt(t.h * t.h + s[2] * s[2]);
  const double a = centre + t.radius, b = centre - t.radius, z = s[3];
  t.a = a;
  t.b = b;
  t.z = z;
  const double a_or_z = z > a ? a : z;  // the smaller of a and z
  t.value[0] = z > a ? z : a;
  t.value[1] = a_or_z > b ? a_or_z : b;
  t.value[2] = z > b ? b : z;
  return t;
}

// The yield function of the planes through principal values p >= q.
KOKKOS_FORCEINLINE_FUNCTION double yield_planes(const PreparedMaterial& pm, const double p,
                                                const double q) {
  return (p - q) + (p + q) * pm.sin_phi - 2.0 * pm.material.cohesion * pm.cos_phi;
}

// The stress scale of the return's tolerances.
KOKKOS_FORCEINLINE_FUNCTION double return_scale(const PreparedMaterial& pm,
                                                const PrincipalTrial& t) {
  return math::fabs(t.value[0]) + math::fabs(t.value[2]) + pm.material.cohesion + 1e-300;
}

// D n (principal space) of the three planes' flow directions: the main plane's
// {up, ls, down}; the edges' second planes mix the same three values.
struct FlowDirections {
  double up, ls, down;
};

KOKKOS_FORCEINLINE_FUNCTION FlowDirections flow_directions(const PreparedMaterial& pm) {
  const double ls = 2.0 * pm.lame_lambda * pm.sin_psi;
  return {ls + 2.0 * pm.shear_modulus * (1.0 + pm.sin_psi), ls,
          ls + 2.0 * pm.shear_modulus * (-1.0 + pm.sin_psi)};
}

// Caps the returned principal values r at the tension cut-off (never above the apex of the
// cone); returns whether any was capped. No branches.
KOKKOS_FORCEINLINE_FUNCTION bool tension_cap(const PreparedMaterial& pm, double r[3]) {
  const double cap = pm.principal_cap;
  const bool capped = (r[0] > cap) | (r[1] > cap) | (r[2] > cap);
  for (int i = 0; i < 3; ++i) r[i] = r[i] > cap ? cap : r[i];
  return capped;
}

// The plastic work density of the return from t to the principal values r, sigma : d eps_p with
// d eps_p = C^-1 (trial - returned); and the returned stress in components, written to s (the
// in-plane pair keeps the trial's principal directions: cos 2 theta = h / radius,
// sin 2 theta = s_xy / radius). No branches.
KOKKOS_FORCEINLINE_FUNCTION double returned_stress(const PreparedMaterial& pm,
                                                   const PrincipalTrial& t, const double r[3],
                                                   double s[4]) {
  const double nu = pm.material.poisson_ratio;
  const double d[3] = {t.value[0] - r[0], t.value[1] - r[1], t.value[2] - r[2]};
  const double trd = d[0] + d[1] + d[2];
  double work = 0.0;
  for (int i = 0; i < 3; ++i) work += r[i] * ((1.0 + nu) * d[i] - nu * trd);
  work *= pm.inverse_young;
  // Which of r is s_zz's: r[0] where z came first (z > a), r[2] where last (z <= b), else r[1].
  const double ra = t.z > t.a ? r[1] : r[0], rb = t.z > t.b ? r[2] : r[1];
  const double r12 = t.z > t.b ? r[1] : r[2];
  const double rz = t.z > t.a ? r[0] : r12;
  const double centre_r = 0.5 * (ra + rb), radius_r = 0.5 * (ra - rb);
  const bool rotated = t.radius > 0.0;
  const double k = radius_r / (rotated ? t.radius : 1.0);
  s[0] = centre_r + (rotated ? k * t.h : radius_r);
  s[1] = centre_r - (rotated ? k * t.h : radius_r);
  s[2] = rotated ? k * s[2] : 0.0;
  s[3] = rz;
  return work;
}

// The main plane's return of the trial principal values (f: their yield function > 0):
// r = trial - dg D n_a with dg = f / A.
KOKKOS_FORCEINLINE_FUNCTION void main_plane_return(const PreparedMaterial& pm,
                                                   const double trial[3], const double f,
                                                   const FlowDirections& D, double r[3]) {
  const double Dna[3] = {D.up, D.ls, D.down};
  const double dg = f * pm.inverse_main;
  for (int i = 0; i < 3; ++i) r[i] = trial[i] - dg * Dna[i];
}

// The return to an edge (two active planes) of the trial principal values (f: the main
// plane's yield function): s1 = s2 (planes a, b) where `upper`, else s2 = s3 (planes a, c).
// Returns whether it holds: both plastic multipliers non-negative and the order of r kept
// (within the tolerance tol). No branches.
KOKKOS_FORCEINLINE_FUNCTION bool edge_return(const PreparedMaterial& pm, const double trial[3],
                                             const double f, const bool upper,
                                             const FlowDirections& D, const double tol,
                                             double r[3]) {
  // Its second plane through s2, s3 (upper) or s1, s2 (lower): the inputs selected, not the
  // results, so that a loop over points keeps one computation (and vectorises).
  const double p = upper ? trial[1] : trial[0], q = upper ? trial[2] : trial[1];
  const double fb = yield_planes(pm, p, q);
  const double A = pm.main_plane, B = upper ? pm.edge_upper : pm.edge_lower;
  const double inv_det = upper ? pm.inverse_det_upper : pm.inverse_det_lower;
  const double da = (A * f - B * fb) * inv_det, db = (A * fb - B * f) * inv_det;
  const double Dna[3] = {D.up, D.ls, D.down};
  // D n of the second plane: b (s1 = s2 side) for the upper edge, c for the lower.
  const double Dn2[3] = {upper ? D.ls : D.up, upper ? D.up : D.down, upper ? D.down : D.ls};
  for (int i = 0; i < 3; ++i) r[i] = trial[i] - da * Dna[i] - db * Dn2[i];
  return (da >= 0.0) & (db >= 0.0) & (r[0] >= r[1] - tol) & (r[1] >= r[2] - tol);
}

// Whether returned principal values r stay ordered r1 >= r2 >= r3 (a main-plane return that
// holds).
KOKKOS_FORCEINLINE_FUNCTION bool ordered(const double r[3]) {
  return (r[0] >= r[1]) & (r[1] >= r[2]);
}

// The material's constants of the return (A, B, the apex, the cap, 1/E and the reciprocals that
// replace its divisions) are computed once per material (PreparedMaterial, material.hpp): on the
// common path (a main-plane return) the function divides once, to write the stress back.
KOKKOS_INLINE_FUNCTION double mohr_coulomb_return(const PreparedMaterial& pm, double s[4]) {
  const PrincipalTrial t = principal_trial(s);
  const double* const trial = t.value;
  double r[3] = {trial[0], trial[1], trial[2]};
  const double scale = return_scale(pm, t);
  const double f = yield_planes(pm, trial[0], trial[2]);
  bool plastic = false;
  if (f > 1e-12 * scale) {
    plastic = true;
    const FlowDirections D = flow_directions(pm);
    main_plane_return(pm, trial, f, D, r);
    bool ok = ordered(r);
    // Edge: s1 = s2 if s2 came out above s1, else s2 = s3.
    if (!ok) ok = edge_return(pm, trial, f, r[1] > r[0], D, 1e-12 * scale, r);
    if (!ok || (r[0] + r[1] + r[2]) / 3.0 > pm.apex) r[0] = r[1] = r[2] = pm.apex;
  }
  plastic |= tension_cap(pm, r);
  if (!plastic) return 0.0;
  return returned_stress(pm, t, r, s);
}

// mohr_coulomb_return() without branches, so that a loop over points vectorises (the host's
// blocked G2P, stress_update.hpp): the main plane's and the edge's returns are both computed
// and the one that holds selected (else the apex), then the tension cut-off. The same
// operations as mohr_coulomb_return() on the route it takes, so the same stress and plastic
// work density up to the compiler's contraction of multiply-adds.
KOKKOS_FORCEINLINE_FUNCTION double mohr_coulomb_return_selected(const PreparedMaterial& pm,
                                                                double s[4]) {
  const PrincipalTrial t = principal_trial(s);
  const double* const trial = t.value;
  const double scale = return_scale(pm, t);
  const double f = yield_planes(pm, trial[0], trial[2]);
  const bool yields = f > 1e-12 * scale;
  const FlowDirections D = flow_directions(pm);
  double main[3], edge[3], r[3];
  main_plane_return(pm, trial, f, D, main);
  const bool main_holds = ordered(main);
  const bool edge_holds = edge_return(pm, trial, f, main[1] > main[0], D, 1e-12 * scale, edge);
  for (int i = 0; i < 3; ++i) r[i] = main_holds ? main[i] : edge[i];
  const bool apex = !(main_holds | edge_holds) | ((r[0] + r[1] + r[2]) / 3.0 > pm.apex);
  // One selection a statement: GCC's if-conversion gave up on the nested one.
  const bool to_apex = yields & apex, to_plane = yields & !apex;
  for (int i = 0; i < 3; ++i) r[i] = to_plane ? r[i] : trial[i];
  for (int i = 0; i < 3; ++i) r[i] = to_apex ? pm.apex : r[i];
  const bool plastic = tension_cap(pm, r) | yields;
  double returned[4] = {s[0], s[1], s[2], s[3]};
  const double work = returned_stress(pm, t, r, returned);
  for (int i = 0; i < 4; ++i) s[i] = plastic ? returned[i] : s[i];
  return plastic ? work : 0.0;
}

KOKKOS_INLINE_FUNCTION double mohr_coulomb_return(const Material& m, double s[4]) {
  return mohr_coulomb_return(PreparedMaterial(m), s);
}

}  // namespace lsi::mpm
