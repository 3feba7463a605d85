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

namespace detail {
// In-plane principal decomposition of (sxx, syy, sxy): centre, radius, cos(2 theta), sin(2 theta).
struct InPlane {
  double centre, radius, c2, s2;
};
KOKKOS_INLINE_FUNCTION InPlane in_plane(const double s[4]) {
  InPlane p;
  p.centre = 0.5 * (s[0] + s[1]);
  const double h = 0.5 * (s[0] - s[1]);
  p.radius = math::sqrt(h * h + s[2] * s[2]);
  if (p.radius > 0.0) {
    p.c2 = h / p.radius;
    p.s2 = s[2] / p.radius;
  } else {
    p.c2 = 1.0;
    p.s2 = 0.0;
  }
  return p;
}
}  // namespace detail

KOKKOS_INLINE_FUNCTION double mohr_coulomb_return(const PreparedMaterial& pm, double s[4]) {
  const Material& m = pm.material;
  const detail::InPlane ip = detail::in_plane(s);
  // Principal values: in-plane major (0), in-plane minor (1), out-of-plane (2); sorted order.
  double p[3] = {ip.centre + ip.radius, ip.centre - ip.radius, s[3]};
  int order[3] = {0, 1, 2};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2 - a; ++b)
      if (p[order[b]] < p[order[b + 1]]) {
        const int t = order[b];
        order[b] = order[b + 1];
        order[b + 1] = t;
      }
  const double trial[3] = {p[order[0]], p[order[1]], p[order[2]]};   // s1 >= s2 >= s3
  double r[3] = {trial[0], trial[1], trial[2]};

  const double sphi = pm.sin_phi, cphi = pm.cos_phi, spsi = pm.sin_psi;
  const double c = m.cohesion;
  const double G = pm.shear_modulus, L = pm.lame_lambda;
  auto f_planes = [&](double a, double b) { return (a - b) + (a + b) * sphi - 2.0 * c * cphi; };
  const double scale = math::fabs(trial[0]) + math::fabs(trial[2]) + c + 1e-300;
  const double f = f_planes(trial[0], trial[2]);
  bool plastic = false;
  if (f > 1e-12 * scale) {
    plastic = true;
    // D n for the three planes' flow directions (principal space).
    const double ls = 2.0 * L * spsi;
    const double Dna[3] = {ls + 2.0 * G * (1.0 + spsi), ls, ls + 2.0 * G * (-1.0 + spsi)};
    const double Dnb[3] = {ls, ls + 2.0 * G * (1.0 + spsi), ls + 2.0 * G * (-1.0 + spsi)};
    const double Dnc[3] = {ls + 2.0 * G * (1.0 + spsi), ls + 2.0 * G * (-1.0 + spsi), ls};
    const double A = 4.0 * L * sphi * spsi + 4.0 * G * (1.0 + sphi * spsi);
    // Main plane.
    double dg = f / A;
    for (int i = 0; i < 3; ++i) r[i] = trial[i] - dg * Dna[i];
    bool ok = r[0] >= r[1] && r[1] >= r[2];
    if (!ok) {
      // Edge: s1 = s2 (planes a, b) if s2 came out above s1, else s2 = s3 (planes a, c).
      const bool upper = r[1] > r[0];
      const double fb = upper ? f_planes(trial[1], trial[2]) : f_planes(trial[0], trial[1]);
      const double B = 4.0 * L * sphi * spsi +
                       (upper ? 2.0 * G * (1.0 - sphi) * (1.0 - spsi)
                              : 2.0 * G * (1.0 + sphi) * (1.0 + spsi));
      const double det = A * A - B * B;
      const double da = (A * f - B * fb) / det, db = (A * fb - B * f) / det;
      const double* Dn2 = upper ? Dnb : Dnc;
      for (int i = 0; i < 3; ++i) r[i] = trial[i] - da * Dna[i] - db * Dn2[i];
      ok = da >= 0.0 && db >= 0.0 && r[0] >= r[1] - 1e-12 * scale &&
           r[1] >= r[2] - 1e-12 * scale;
    }
    const double apex = sphi > 0.0 ? c * cphi / sphi : 1e300;
    if (!ok || (r[0] + r[1] + r[2]) / 3.0 > apex) {
      r[0] = r[1] = r[2] = apex;
    }
  }
  // Tension cut-off (never above the apex of the cone).
  const double cutoff = math::min(m.tension_cutoff, sphi > 0.0 ? c * cphi / sphi : 1e300);
  for (int i = 0; i < 3; ++i) {
    if (r[i] > cutoff) {
      r[i] = cutoff;
      plastic = true;
    }
  }
  if (!plastic) return 0.0;
  // Plastic strain increment C^-1 (trial - returned) and its work with the returned stress.
  const double E = m.young_modulus, nu = m.poisson_ratio;
  const double d[3] = {trial[0] - r[0], trial[1] - r[1], trial[2] - r[2]};
  const double trd = d[0] + d[1] + d[2];
  double work = 0.0;
  for (int i = 0; i < 3; ++i) work += r[i] * ((1.0 + nu) * d[i] - nu * trd) / E;
  // Back to components: the in-plane pair keeps its principal directions.
  double back[3];
  for (int k = 0; k < 3; ++k) back[order[k]] = r[k];
  const double centre = 0.5 * (back[0] + back[1]), radius = 0.5 * (back[0] - back[1]);
  s[0] = centre + radius * ip.c2;
  s[1] = centre - radius * ip.c2;
  s[2] = radius * ip.s2;
  s[3] = back[2];
  return work;
}

KOKKOS_INLINE_FUNCTION double mohr_coulomb_return(const Material& m, double s[4]) {
  return mohr_coulomb_return(PreparedMaterial(m), s);
}

}  // namespace lsi::mpm
