// Mohr-Coulomb perfect plasticity with a non-associated flow rule (dilatancy psi), cohesion and a
// tension cut-off, in plane strain. Tension positive; principal stresses s1 >= s2 >= s3 (sigma_zz
// is one of them). Yield and plastic potential:
//   f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi),    g = (s1 - s3) + (s1 + s3) sin(psi)
// Return mapping in principal space (closest-point for the elastic metric, exact for linear
// elasticity and perfect plasticity; de Souza Neto, Peric & Owen, "Computational Methods for
// Plasticity", 2008, ch. 8): the main plane; if the returned stresses leave the sextant, one of the
// two edges (s1 = s2 or s2 = s3, two active planes); if that fails too, the apex
// s1 = s2 = s3 = c cot(phi). Finally principal stresses above the tension cut-off are capped.
// Returns the plastic work density of the step, sigma : d eps_p (J/m^3).
#pragma once
#include "kernels/mpm/constitutive/material.hpp"

namespace lsi::mpm {

// The material's constants of the return (A, B, the apex, the cap, 1/E and the reciprocals that
// replace its divisions) are computed once per material (PreparedMaterial, material.hpp): on the
// common path (a main-plane return) the function divides once, to write the stress back.
KOKKOS_INLINE_FUNCTION double mohr_coulomb_return(const PreparedMaterial& pm, double s[4]) {
  // Principal values: in-plane major a >= minor b (centre +- radius) and out-of-plane z = s_zz.
  const double centre = 0.5 * (s[0] + s[1]), h = 0.5 * (s[0] - s[1]);
  const double radius = math::sqrt(h * h + s[2] * s[2]);
  const double a = centre + radius, b = centre - radius, z = s[3];
  // Where z sits in the order s1 >= s2 >= s3: 0 (first), 1 or 2; ties keep the in-plane value
  // first (a stable sort of a, b, z).
  const int kz = z > b ? (z > a ? 0 : 1) : 2;
  const double trial[3] = {kz == 0 ? z : a, kz == 0 ? a : (kz == 1 ? z : b), kz == 2 ? z : b};
  double r[3] = {trial[0], trial[1], trial[2]};

  const double sphi = pm.sin_phi, cphi = pm.cos_phi, spsi = pm.sin_psi;
  const double c = pm.material.cohesion;
  const double G = pm.shear_modulus, L = pm.lame_lambda;
  auto f_planes = [&](double p, double q) { return (p - q) + (p + q) * sphi - 2.0 * c * cphi; };
  const double scale = math::fabs(trial[0]) + math::fabs(trial[2]) + c + 1e-300;
  const double f = f_planes(trial[0], trial[2]);
  bool plastic = false;
  if (f > 1e-12 * scale) {
    plastic = true;
    // D n for the three planes' flow directions (principal space).
    const double ls = 2.0 * L * spsi;
    const double up = ls + 2.0 * G * (1.0 + spsi), down = ls + 2.0 * G * (-1.0 + spsi);
    const double Dna[3] = {up, ls, down};
    // Main plane: dg = f / A.
    const double dg = f * pm.inverse_main;
    for (int i = 0; i < 3; ++i) r[i] = trial[i] - dg * Dna[i];
    bool ok = r[0] >= r[1] && r[1] >= r[2];
    if (!ok) {
      // Edge: s1 = s2 (planes a, b) if s2 came out above s1, else s2 = s3 (planes a, c).
      const bool upper = r[1] > r[0];
      const double fb = upper ? f_planes(trial[1], trial[2]) : f_planes(trial[0], trial[1]);
      const double A = pm.main_plane, B = upper ? pm.edge_upper : pm.edge_lower;
      const double inv_det = upper ? pm.inverse_det_upper : pm.inverse_det_lower;
      const double da = (A * f - B * fb) * inv_det, db = (A * fb - B * f) * inv_det;
      // D n of the second plane: b (s1 = s2 side) for the upper edge, c for the lower.
      const double Dn2[3] = {upper ? ls : up, upper ? up : down, upper ? down : ls};
      for (int i = 0; i < 3; ++i) r[i] = trial[i] - da * Dna[i] - db * Dn2[i];
      ok = da >= 0.0 && db >= 0.0 && r[0] >= r[1] - 1e-12 * scale && r[1] >= r[2] - 1e-12 * scale;
    }
    if (!ok || (r[0] + r[1] + r[2]) / 3.0 > pm.apex) r[0] = r[1] = r[2] = pm.apex;
  }
  // Tension cut-off (never above the apex of the cone).
  const double cap = pm.principal_cap;
  for (int i = 0; i < 3; ++i) {
    if (r[i] > cap) {
      r[i] = cap;
      plastic = true;
    }
  }
  if (!plastic) return 0.0;
  // Plastic strain increment C^-1 (trial - returned) and its work with the returned stress.
  const double nu = pm.material.poisson_ratio;
  const double d[3] = {trial[0] - r[0], trial[1] - r[1], trial[2] - r[2]};
  const double trd = d[0] + d[1] + d[2];
  double work = 0.0;
  for (int i = 0; i < 3; ++i) work += r[i] * ((1.0 + nu) * d[i] - nu * trd);
  work *= pm.inverse_young;
  // Back to components: the in-plane pair keeps its principal directions (those of the trial:
  // cos 2 theta = h / radius, sin 2 theta = s_xy / radius).
  const double ra = kz == 0 ? r[1] : r[0], rb = kz == 2 ? r[1] : r[2];
  const double rz = r[kz];
  const double centre_r = 0.5 * (ra + rb), radius_r = 0.5 * (ra - rb);
  if (radius > 0.0) {
    const double k = radius_r / radius;
    s[0] = centre_r + k * h;
    s[1] = centre_r - k * h;
    s[2] = k * s[2];
  } else {
    s[0] = centre_r + radius_r;
    s[1] = centre_r - radius_r;
    s[2] = 0.0;
  }
  s[3] = rz;
  return work;
}

KOKKOS_INLINE_FUNCTION double mohr_coulomb_return(const Material& m, double s[4]) {
  return mohr_coulomb_return(PreparedMaterial(m), s);
}

}  // namespace lsi::mpm
