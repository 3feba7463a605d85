// Unit tests of the constitutive functions (kernels/mpm/constitutive): the Mohr-Coulomb return
// mapping `mohr_coulomb_return` (and its branch-free form `mohr_coulomb_return_selected`)
// and the Jaumann rotation `jaumann_rotate`. Host-only calls of
// KOKKOS_INLINE_FUNCTIONs; plain TESTs (no backend typing), Kokkos is initialised by the shared
// main all the same.
//
// The oracles share no code with the kernel:
//  * trial states are built from a known point sigma on the yield surface plus a known plastic
//    corrector, trial = sigma + sum_k dg_k D n_g,k with dg_k > 0 and n_g,k the flow directions of the
//    planes active at sigma; the return must give back sigma (exact for linear elasticity and
//    perfect plasticity: the return mapping is a linear projection once the active set is known);
//  * for associated flow, the closest point in the energy norm is found by brute force: every
//    subset of at most three of the six Mohr-Coulomb planes is solved as an equality-constrained
//    quadratic programme, and the feasible candidate with the smallest distance is the projection
//    (KKT vertex enumeration);
//  * for any flow rule, the KKT conditions of the return: trial - returned lies in the cone spanned
//    by D n_g of the planes active at the returned point (non-negative multipliers, found by
//    enumerating subsets of at most three generators, Caratheodory in 3D).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/mpm/constitutive/jaumann.hpp"
#include "kernels/mpm/constitutive/mohr_coulomb.hpp"
#include "support/tolerances.hpp"

namespace {
using lsi::mpm::jaumann_rotate;
using lsi::mpm::Material;
using lsi::mpm::mohr_coulomb_return;
using V3 = std::array<double, 3>;
using lsi::test::kIntegratedRel;
using lsi::test::kRoundOffAbs;
using lsi::test::kTwoRoutesRel;

// Of the stress scale: the return mapping (rotation to principal axes and back, a linear
// projection on the active set) to round-off.
constexpr double kReturnRel = 1e-9;
// Of the work scale sigma^2 / E: a plastic work that is zero or positive, to round-off.
constexpr double kWorkRoundOffRel = 1e-12;
// Radians: the in-plane principal angle recomputed from round-off-perturbed components.
constexpr double kDirectionRad = 1e-9;
// Of the stress scale: a 1e-6 Pa offset from a principal tie times the return's slope (of order
// 1), far above round-off (1e-16 of 9e4 Pa).
constexpr double kTieOffsetRel = 1e-8;
// Of the largest coefficient: the oracle's least-squares coefficients count as non-negative.
constexpr double kOracleNonNegativeRel = 1e-9;

constexpr double kPi = 3.14159265358979323846;
double deg(double d) { return d * kPi / 180.0; }

Material mc(double phi_deg, double psi_deg, double c, double cutoff = 1e300) {
  Material m;
  m.model = Material::Model::MohrCoulomb;
  m.density = 2000.0;
  m.young_modulus = 5e7;
  m.poisson_ratio = 0.3;
  m.friction_angle = deg(phi_deg);
  m.dilatancy_angle = deg(psi_deg);
  m.cohesion = c;
  m.tension_cutoff = cutoff;  // 1e300: min(cutoff, apex) = apex, i.e. no separate cut-off
  return m;
}

// ---- small 3-vector / 3x3 helpers (principal space) ----
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 add(const V3& a, const V3& b, double s = 1.0) {
  return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
}
double norm(const V3& a) { return std::sqrt(dot(a, a)); }

// D x (isotropic elasticity in principal space) and C x = D^-1 x.
V3 stiff(const Material& m, const V3& x) {
  const double G = m.young_modulus / (2 * (1 + m.poisson_ratio));
  const double L =
      m.young_modulus * m.poisson_ratio / ((1 + m.poisson_ratio) * (1 - 2 * m.poisson_ratio));
  const double tr = x[0] + x[1] + x[2];
  return {L * tr + 2 * G * x[0], L * tr + 2 * G * x[1], L * tr + 2 * G * x[2]};
}
V3 compl_(const Material& m, const V3& x) {
  const double E = m.young_modulus, nu = m.poisson_ratio, tr = x[0] + x[1] + x[2];
  return {((1 + nu) * x[0] - nu * tr) / E, ((1 + nu) * x[1] - nu * tr) / E,
          ((1 + nu) * x[2] - nu * tr) / E};
}
double energy_dist2(const Material& m, const V3& a, const V3& b) {
  const V3 d = add(a, b, -1.0);
  return dot(d, compl_(m, d));
}

// Solves A x = b (3x3 or smaller, n <= 3) by Gaussian elimination with partial pivoting. Returns
// false if singular (relative pivot below 1e-10).
bool solve(int n, double A[3][3], double b[3], double x[3]) {
  double M[3][4];
  double amax = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      M[i][j] = A[i][j];
      amax = std::max(amax, std::fabs(A[i][j]));
    }
    M[i][n] = b[i];
  }
  for (int c = 0; c < n; ++c) {
    int piv = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(M[r][c]) > std::fabs(M[piv][c])) piv = r;
    if (std::fabs(M[piv][c]) < 1e-10 * amax) return false;
    for (int j = 0; j <= n; ++j) std::swap(M[c][j], M[piv][j]);
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = M[r][c] / M[c][c];
      for (int j = c; j <= n; ++j) M[r][j] -= f * M[c][j];
    }
  }
  for (int i = 0; i < n; ++i) x[i] = M[i][n] / M[i][i];
  return true;
}

// The six planes of the (unsorted) Mohr-Coulomb surface, plane k over the ordered pair (i, j),
// i != j:  F_k(s) = (s_i - s_j) + (s_i + s_j) sin(phi) - 2 c cos(phi) = N_k . s - b.
struct Planes {
  std::vector<V3> nf, ng;  // yield normals and flow (plastic potential) normals
  double b;
};
Planes planes(const Material& m) {
  Planes P;
  const double sf = std::sin(m.friction_angle), sg = std::sin(m.dilatancy_angle);
  P.b = 2 * m.cohesion * std::cos(m.friction_angle);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      V3 nf{0, 0, 0}, ng{0, 0, 0};
      nf[i] = 1 + sf;
      nf[j] = -1 + sf;
      ng[i] = 1 + sg;
      ng[j] = -1 + sg;
      P.nf.push_back(nf);
      P.ng.push_back(ng);
    }
  return P;
}
// Yield function on sorted principal values (the kernel's f, written independently).
double yield(const Material& m, V3 s) {
  std::sort(s.begin(), s.end(), std::greater<>());
  return (s[0] - s[2]) + (s[0] + s[2]) * std::sin(m.friction_angle) -
         2 * m.cohesion * std::cos(m.friction_angle);
}

// Closest point in the energy norm (associated flow) by enumeration of active sets.
V3 brute_force_projection(const Material& m, const V3& t) {
  const Planes P = planes(m);
  const double scale = norm(t) + m.cohesion;
  double best = 1e300;
  V3 arg = t;
  const int np = static_cast<int>(P.nf.size());
  auto consider = [&](const V3& x) {
    for (int k = 0; k < np; ++k)
      if (dot(P.nf[k], x) - P.b > 1e-10 * scale) return;  // infeasible
    const double d = energy_dist2(m, t, x);
    if (d < best) {
      best = d;
      arg = x;
    }
  };
  consider(t);
  std::vector<int> idx;
  for (int mask = 1; mask < (1 << np); ++mask) {
    idx.clear();
    for (int k = 0; k < np; ++k)
      if (mask & (1 << k)) idx.push_back(k);
    if (idx.size() > 3) continue;
    const int n = static_cast<int>(idx.size());
    // x = t - D N lambda,  N^T x = b  ->  (N^T D N) lambda = N^T t - b
    double A[3][3], rhs[3], lam[3];
    std::vector<V3> DN;
    for (int a = 0; a < n; ++a) DN.push_back(stiff(m, P.nf[idx[a]]));
    for (int a = 0; a < n; ++a) {
      for (int c = 0; c < n; ++c) A[a][c] = dot(P.nf[idx[a]], DN[c]);
      rhs[a] = dot(P.nf[idx[a]], t) - P.b;
    }
    if (!solve(n, A, rhs, lam)) continue;
    V3 x = t;
    for (int a = 0; a < n; ++a) x = add(x, DN[a], -lam[a]);
    consider(x);
  }
  return arg;
}

// Residual of the best non-negative combination of at most three of the generators `gens`
// reproducing `target`: every subset of size n <= 3 is solved by least squares (normal
// equations); the smallest residual norm among solutions with coefficients >= 0 (to 1e-9 of the
// largest) is returned.
double cone_residual(const std::vector<V3>& gens, const V3& target) {
  double best = norm(target);
  const int ng = static_cast<int>(gens.size());
  for (int mask = 1; mask < (1 << ng); ++mask) {
    std::vector<int> idx;
    for (int k = 0; k < ng; ++k)
      if (mask & (1 << k)) idx.push_back(k);
    if (idx.size() > 3) continue;
    const int n = static_cast<int>(idx.size());
    double A[3][3], rhs[3], x[3];
    for (int a = 0; a < n; ++a) {
      for (int c = 0; c < n; ++c) A[a][c] = dot(gens[idx[a]], gens[idx[c]]);
      rhs[a] = dot(gens[idx[a]], target);
    }
    if (!solve(n, A, rhs, x)) continue;
    double xmax = 0.0;
    for (int a = 0; a < n; ++a) xmax = std::max(xmax, std::fabs(x[a]));
    bool nonneg = true;
    for (int a = 0; a < n; ++a) nonneg = nonneg && x[a] >= -kOracleNonNegativeRel * xmax;
    if (!nonneg) continue;
    V3 r = target;
    for (int a = 0; a < n; ++a) r = add(r, gens[idx[a]], -x[a]);
    best = std::min(best, norm(r));
  }
  return best;
}

// ---- stress tensor <-> principal values ----
// Components {sxx, syy, sxy, szz} from the in-plane principal pair (major >= minor), its
// direction angle theta (major axis from x), and szz.
std::array<double, 4> tensor(double major, double minor, double theta, double szz) {
  const double c = 0.5 * (major + minor), r = 0.5 * (major - minor);
  return {c + r * std::cos(2 * theta), c - r * std::cos(2 * theta), r * std::sin(2 * theta), szz};
}
struct Principal {
  double major, minor, zz, radius, angle2;  // angle2 = atan2(2 sxy, sxx - syy) = 2 theta
};
Principal principal(const std::array<double, 4>& s) {
  Principal p;
  const double c = 0.5 * (s[0] + s[1]), h = 0.5 * (s[0] - s[1]);
  p.radius = std::hypot(h, s[2]);
  p.major = c + p.radius;
  p.minor = c - p.radius;
  p.zz = s[3];
  p.angle2 = std::atan2(s[2], h);
  return p;
}
V3 sorted_principal(const std::array<double, 4>& s) {
  const Principal p = principal(s);
  V3 v{p.major, p.minor, p.zz};
  std::sort(v.begin(), v.end(), std::greater<>());
  return v;
}
// Builds a tensor whose sorted principal values are `v` (v[0] >= v[1] >= v[2]), with the
// out-of-plane stress being v[zz_rank] and the in-plane major axis at angle theta.
std::array<double, 4> tensor_from_sorted(const V3& v, int zz_rank, double theta) {
  double in[2];
  int k = 0;
  for (int i = 0; i < 3; ++i)
    if (i != zz_rank) in[k++] = v[i];
  return tensor(in[0], in[1], theta, v[zz_rank]);
}

bool same_order(const std::array<double, 4>& trial, const std::array<double, 4>& ret, double tol) {
  // The returned principal values must be ordered like the trial's: the largest of the trial
  // (in-plane major, in-plane minor or zz) is still (one of) the largest, etc.
  const Principal pt = principal(trial), pr = principal(ret);
  const double t[3] = {pt.major, pt.minor, pt.zz}, r[3] = {pr.major, pr.minor, pr.zz};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (t[i] > t[j] && r[i] < r[j] - tol) return false;
  return true;
}

// Random trial principal values (sorted): odd draws uniform in [-200, 100] kPa^3; even draws
// around the apex c cot(phi) (mean within +-60 kPa of it, deviatoric part up to 60 kPa), where
// the main-plane return may leave the sextant across one edge or both and the region selection
// (plane / edge / apex) is decided.
V3 random_trial(std::mt19937& rng, const Material& m, int rep) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  V3 t;
  if (rep % 2) {
    t = {-200e3 + 300e3 * U(rng), -200e3 + 300e3 * U(rng), -200e3 + 300e3 * U(rng)};
  } else {
    const double a = m.cohesion / std::tan(m.friction_angle) + 60e3 * U(rng);
    t = {a + 60e3 * U(rng), a + 60e3 * U(rng), a + 60e3 * U(rng)};
  }
  std::sort(t.begin(), t.end(), std::greater<>());
  return t;
}

struct Case {
  double phi, psi, c;
};
// Associated (psi = phi) and non-associated (psi = 0, and an intermediate psi) flow, with and
// without cohesion, for a range of friction angles.
const std::vector<Case> kCases = {
    {30, 30, 0.0}, {30, 0, 0.0},  {30, 30, 20e3}, {30, 0, 20e3},  {35, 10, 5e3}, {20, 20, 50e3},
    {20, 0, 50e3}, {45, 45, 1e3}, {45, 15, 1e3},  {10, 10, 80e3}, {40, 0, 0.0},  {25, 25, 10e3},
};

// (a) A state strictly inside the surface is returned unchanged, bit for bit, with zero work.
TEST(MohrCoulombReturn, ElasticStateIsUnchanged) {
  for (const Case& k : kCases) {
    const Material m = mc(k.phi, k.psi, k.c);
    // Compressive, mildly deviatoric: s1 - s3 = 20 kPa at a mean of -100 kPa; f < 0 for
    // phi >= 10 deg even with c = 0 ((s1 - s3) < -(s1 + s3) sin(phi) = 190 kPa * 0.17 = 33 kPa).
    const std::array<double, 4> s0 = tensor(-90e3, -110e3, 0.3, -100e3);
    ASSERT_LT(yield(m, sorted_principal(s0)), 0.0);
    double s[4] = {s0[0], s0[1], s0[2], s0[3]};
    const double w = mohr_coulomb_return(m, s);
    EXPECT_EQ(w, 0.0) << k.phi << " " << k.psi << " " << k.c;  // exactly: no plastic step taken
    for (int i = 0; i < 4; ++i) EXPECT_EQ(s[i], s0[i]) << i;   // untouched
  }
}

// (b) Trial states built beyond the main plane, beyond both edges and beyond the apex return to
// the surface point they were built from (f = 0 to 1e-9 relative, the principal order preserved),
// for associated and non-associated flow, with and without cohesion.
TEST(MohrCoulombReturn, ReturnsToKnownSurfacePoint) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int n_main = 0, n_upper = 0, n_lower = 0, n_apex = 0;
  double worst_f = 0.0, worst_point = 0.0;
  for (const Case& k : kCases) {
    const Material m = mc(k.phi, k.psi, k.c);
    const double sf = std::sin(m.friction_angle), cf = std::cos(m.friction_angle);
    const double sg = std::sin(m.dilatancy_angle);
    const double apex = k.c * cf / sf;
    const V3 na{1 + sg, 0, -1 + sg}, nb{0, 1 + sg, -1 + sg}, nc{1 + sg, -1 + sg, 0};
    for (int rep = 0; rep < 40; ++rep) {
      // A point on the surface: choose s3 < apex and s2 in [s3, s1], then s1 from f = 0:
      //   s1 (1 + sf) = 2 c cf + s3 (1 - sf).
      const double s3 = apex - 50e3 - 400e3 * U(rng);
      const double s1 = (2 * k.c * cf + s3 * (1 - sf)) / (1 + sf);
      const int region = rep % 4;  // 0 main plane, 1 edge s1 = s2, 2 edge s2 = s3, 3 apex
      V3 sigma, trial;
      const double mag = 1e-4 + 2e-3 * U(rng);  // plastic multiplier scale: strain ~ 1e-4..2e-3
      if (region == 0) {
        const double s2 = s3 + (0.1 + 0.8 * U(rng)) * (s1 - s3);  // strictly inside the sextant
        sigma = {s1, s2, s3};
        trial = add(sigma, stiff(m, na), mag);
      } else if (region == 1) {
        sigma = {s1, s1, s3};
        const double da = mag, db = mag * (0.05 + 0.9 * U(rng));  // da > db: s1 >= s2 in trial
        trial = add(add(sigma, stiff(m, na), da), stiff(m, nb), db);
      } else if (region == 2) {
        sigma = {s1, s3, s3};
        const double da = mag, dc = mag * (0.05 + 0.9 * U(rng));  // da > dc: s2 >= s3 in trial
        trial = add(add(sigma, stiff(m, na), da), stiff(m, nc), dc);
      } else {
        sigma = {apex, apex, apex};
        // Beyond the apex: any non-negative combination of the flow directions D n_g of the
        // planes meeting there; take a, b, c with random weights (the order s1 >= s2 >= s3 holds).
        const double wa = mag * U(rng), wb = mag * U(rng), wc = mag * U(rng);
        trial = add(add(add(sigma, stiff(m, na), wa), stiff(m, nb), wb), stiff(m, nc), wc);
        if (!(trial[0] >= trial[1] && trial[1] >= trial[2])) continue;
      }
      const int zz_rank = rep % 3;
      const double theta = 2 * kPi * U(rng);
      const std::array<double, 4> t4 = tensor_from_sorted(trial, zz_rank, theta);
      double s[4] = {t4[0], t4[1], t4[2], t4[3]};
      mohr_coulomb_return(m, s);
      const std::array<double, 4> r4 = {s[0], s[1], s[2], s[3]};
      const V3 r = sorted_principal(r4);
      const double scale = std::fabs(trial[0]) + std::fabs(trial[2]) + k.c;
      const double f = yield(m, r);
      // On the surface to round-off: |f| <= 1e-9 of the stress scale.
      EXPECT_LE(std::fabs(f), kReturnRel * scale)
          << "region " << region << " phi " << k.phi << " psi " << k.psi << " c " << k.c;
      // The surface point it was built from: the return is unique (a linear projection on the
      // active set), so it must come back to 1e-9 of the stress scale.
      const double err = norm(add(r, sigma, -1.0));
      EXPECT_LE(err, kReturnRel * scale)
          << "region " << region << " phi " << k.phi << " psi " << k.psi << " c " << k.c << " got "
          << r[0] << " " << r[1] << " " << r[2] << " want " << sigma[0] << " " << sigma[1] << " "
          << sigma[2];
      // s1 >= s2 >= s3 preserved component-wise (ties within 1e-9 of the scale).
      EXPECT_TRUE(same_order(t4, r4, kReturnRel * scale)) << "region " << region;
      worst_f = std::max(worst_f, std::fabs(f) / scale);
      worst_point = std::max(worst_point, err / scale);
      (region == 0 ? n_main : region == 1 ? n_upper : region == 2 ? n_lower : n_apex)++;
    }
  }
  EXPECT_GT(n_main, 50);
  EXPECT_GT(n_upper, 50);
  EXPECT_GT(n_lower, 50);
  EXPECT_GT(n_apex, 20);
  std::printf(
      "[measured] cases main %d upper %d lower %d apex %d; max |f|/scale %.2e, "
      "max |r - sigma|/scale %.2e\n",
      n_main, n_upper, n_lower, n_apex, worst_f, worst_point);
}

// (c) Associated flow: the returned stress is the closest admissible point in the energy norm,
// checked against a brute-force projection (KKT enumeration over the six planes), for random
// trial states anywhere (including the regions where the main-plane return leaves the sextant
// on both sides). (b) already checks the consistency condition trial - returned = sum dg D n_g
// for points built that way; here random trials probe the region selection.
TEST(MohrCoulombReturn, AssociatedReturnIsClosestPoint) {
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double worst = 0.0;
  int plastic = 0;
  for (const Case& k : kCases) {
    if (k.phi != k.psi) continue;
    const Material m = mc(k.phi, k.psi, k.c);
    for (int rep = 0; rep < 400; ++rep) {
      const V3 t = random_trial(rng, m, rep);
      if (yield(m, t) <= 0.0) continue;
      ++plastic;
      const double theta = kPi * U(rng);
      const std::array<double, 4> t4 = tensor_from_sorted(t, rep % 3, theta);
      double s[4] = {t4[0], t4[1], t4[2], t4[3]};
      mohr_coulomb_return(m, s);
      const V3 r = sorted_principal({s[0], s[1], s[2], s[3]});
      const V3 want = brute_force_projection(m, t);
      const double scale = std::fabs(t[0]) + std::fabs(t[2]) + k.c;
      // Same point to 1e-8 of the stress scale (both are exact solutions of linear systems).
      const double err = norm(add(r, want, -1.0)) / scale;
      worst = std::max(worst, err);
      EXPECT_LE(err, 1e-8) << "phi " << k.phi << " c " << k.c << " trial " << t[0] << " " << t[1]
                           << " " << t[2] << " got " << r[0] << " " << r[1] << " " << r[2]
                           << " want " << want[0] << " " << want[1] << " " << want[2];
      // And no admissible point nearby is closer (perturbation along / inside the surface):
      // distance^2 may only grow, to round-off of 1e-10 relative.
      const double d0 = energy_dist2(m, t, r);
      std::uniform_real_distribution<double> P(-1.0, 1.0);
      for (int j = 0; j < 20; ++j) {
        V3 q{r[0] + 1e-3 * scale * P(rng), r[1] + 1e-3 * scale * P(rng),
             r[2] + 1e-3 * scale * P(rng)};
        if (yield(m, q) > 0.0) continue;
        EXPECT_GE(energy_dist2(m, t, q), d0 * (1 - 1e-10));
      }
    }
  }
  EXPECT_GT(plastic, 500);
  std::printf("[measured] associated: %d plastic trials, max |r - projection|/scale %.2e\n",
              plastic, worst);
}

// A return point other than the apex that satisfies the KKT conditions: sigma = trial -
// sum_k dg_k D n_g,k over one or two planes k (all six candidates), dg_k >= 0, sigma on those
// planes and admissible for all six. Returns true and sets `out` if one exists.
bool non_apex_kkt_point(const Material& m, const V3& t, V3& out) {
  const Planes P = planes(m);
  const int np = static_cast<int>(P.nf.size());
  const double scale = norm(t) + m.cohesion;
  const double a = m.cohesion / std::tan(m.friction_angle);
  for (int i = 0; i < np; ++i)
    for (int j = i; j < np; ++j) {
      const int idx[2] = {i, j};
      const int n = (i == j) ? 1 : 2;
      double A[3][3], rhs[3], lam[3];
      for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c) A[r][c] = dot(P.nf[idx[r]], stiff(m, P.ng[idx[c]]));
        rhs[r] = dot(P.nf[idx[r]], t) - P.b;
      }
      if (!solve(n, A, rhs, lam)) continue;
      bool ok = true;
      V3 x = t;
      for (int r = 0; r < n; ++r) {
        ok = ok && lam[r] >= 0.0;
        x = add(x, stiff(m, P.ng[idx[r]]), -lam[r]);
      }
      for (int k = 0; k < np && ok; ++k) ok = dot(P.nf[k], x) - P.b <= 1e-10 * scale;
      if (ok && norm(add(x, V3{a, a, a}, -1.0)) > 1e-6 * scale) {
        out = x;
        return true;
      }
    }
  return false;
}

// (b'/c') Any flow rule: the KKT conditions of the return, for random trials. The returned point
// is on the surface and trial - returned = D (sum dg_k n_g,k) with dg_k >= 0 over the planes active
// at the returned point: the residual of the best non-negative combination is round-off.
// Exception, by construction of the non-associated model: beyond the apex, a trial whose mean
// stress cannot be brought down to the apex by the flow directions (psi = 0: the plastic flow is
// isochoric, so the mean stress of the trial is kept; if it exceeds c cot(phi) no point of the
// cone satisfies the KKT conditions) is set to the apex (tension failure). For those the test
// checks instead that no other KKT point (on a plane or an edge) exists, i.e. the apex was not
// chosen in place of a valid return.
TEST(MohrCoulombReturn, KktConditionsForAnyFlowRule) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double worst = 0.0;
  int plastic = 0, apex = 0, apex_no_kkt = 0;
  for (const Case& k : kCases) {
    const Material m = mc(k.phi, k.psi, k.c);
    const Planes P = planes(m);
    const double a = k.c / std::tan(m.friction_angle);
    for (int rep = 0; rep < 400; ++rep) {
      const V3 t = random_trial(rng, m, rep);
      if (yield(m, t) <= 0.0) continue;
      ++plastic;
      const std::array<double, 4> t4 = tensor_from_sorted(t, rep % 3, 0.7 * rep);
      double s[4] = {t4[0], t4[1], t4[2], t4[3]};
      mohr_coulomb_return(m, s);
      const V3 r = sorted_principal({s[0], s[1], s[2], s[3]});
      const double scale = std::fabs(t[0]) + std::fabs(t[2]) + k.c;
      EXPECT_LE(std::fabs(yield(m, r)), kReturnRel * scale);  // on the surface, round-off
      std::vector<V3> gens;
      for (size_t p = 0; p < P.nf.size(); ++p)
        if (std::fabs(dot(P.nf[p], r) - P.b) <= kReturnRel * scale)
          gens.push_back(stiff(m, P.ng[p]));
      const bool at_apex = std::fabs(r[0] - a) + std::fabs(r[2] - a) <= kReturnRel * scale;
      apex += at_apex;
      const V3 d = add(t, r, -1.0);
      const double res = cone_residual(gens, d) / (norm(d) + 1e-300);
      if (at_apex && k.psi != k.phi && res > 1e-8) {
        ++apex_no_kkt;
        V3 other{0, 0, 0};
        EXPECT_FALSE(non_apex_kkt_point(m, t, other))
            << "apex chosen although a plane/edge return exists: phi " << k.phi << " psi " << k.psi
            << " c " << k.c << " trial " << t[0] << " " << t[1] << " " << t[2] << " -> " << other[0]
            << " " << other[1] << " " << other[2];
        continue;
      }
      worst = std::max(worst, res);
      // Relative residual 1e-8: round-off of a 3x3 solve on D n ~ G-scaled vectors.
      EXPECT_LE(res, 1e-8) << "phi " << k.phi << " psi " << k.psi << " c " << k.c << " trial "
                           << t[0] << " " << t[1] << " " << t[2] << " got " << r[0] << " " << r[1]
                           << " " << r[2] << " active " << gens.size();
    }
  }
  EXPECT_GT(plastic, 1000);
  std::printf(
      "[measured] KKT: %d plastic trials (%d at the apex, %d of them non-associated "
      "without a KKT point), max relative residual %.2e\n",
      plastic, apex, apex_no_kkt, worst);
}

// (d) Tension cut-off: principal stresses above the cut-off are capped at it, the others are
// untouched, the in-plane directions kept; it applies to otherwise elastic states and after a
// Mohr-Coulomb return, and never above the apex c cot(phi).
TEST(MohrCoulombReturn, TensionCutoffCapsMajorPrincipalStress) {
  const double T = 5e3;
  const Material m = mc(30, 0, 10e3, T);  // apex c cot(30) = 17.3 kPa > T
  {
    // Elastic for the cone (f = 4 + 6 - 17.3 kPa < 0) but s1 = 8 kPa and s2 = 6 kPa > T.
    const std::array<double, 4> t4 = tensor(8e3, 4e3, 0.4, 6e3);
    ASSERT_LT(yield(m, sorted_principal(t4)), 0.0);
    double s[4] = {t4[0], t4[1], t4[2], t4[3]};
    const double w = mohr_coulomb_return(m, s);
    const Principal p = principal({s[0], s[1], s[2], s[3]});
    EXPECT_NEAR(p.major, T, kReturnRel * T);    // capped exactly (round-off of the rotation back)
    EXPECT_NEAR(p.zz, T, kReturnRel * T);       // also above T: capped
    EXPECT_NEAR(p.minor, 4e3, kReturnRel * T);  // below T: unchanged
    EXPECT_NEAR(p.angle2, principal(t4).angle2, kRoundOffAbs);  // direction kept
    EXPECT_GT(w, 0.0);  // a plastic step with positive work (checked in general below)
  }
  {
    // Strongly deviatoric with a tensile major stress: the cone return, then the cap.
    const std::array<double, 4> t4 = tensor(40e3, -100e3, 1.1, -30e3);
    double s[4] = {t4[0], t4[1], t4[2], t4[3]};
    mohr_coulomb_return(m, s);
    const V3 r = sorted_principal({s[0], s[1], s[2], s[3]});
    EXPECT_LE(r[0], T * (1 + 1e-12));            // capped
    EXPECT_LE(yield(m, r), kReturnRel * 100e3);  // and admissible for the cone
  }
  {
    // A cut-off requested above the apex is limited to the apex c cot(phi).
    const Material m2 = mc(30, 30, 10e3, 1e6);
    const double apex = 10e3 / std::tan(deg(30));
    const std::array<double, 4> t4 = tensor(60e3, 50e3, 0.2, 55e3);  // hydrostatic-ish tension
    double s[4] = {t4[0], t4[1], t4[2], t4[3]};
    mohr_coulomb_return(m2, s);
    const V3 r = sorted_principal({s[0], s[1], s[2], s[3]});
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(r[i], apex, kReturnRel * apex);
  }
  {
    // Default material (tension_cutoff = 0), cohesionless: no tensile principal stress survives.
    Material m3 = mc(30, 0, 0.0);
    m3.tension_cutoff = 0.0;
    const std::array<double, 4> t4 = tensor(1e3, -5e3, 0.3, -2e3);
    double s[4] = {t4[0], t4[1], t4[2], t4[3]};
    mohr_coulomb_return(m3, s);
    const V3 r = sorted_principal({s[0], s[1], s[2], s[3]});
    EXPECT_LE(r[0], kReturnRel * 5e3);
  }
}

// (e) The plastic work density returned is >= 0 for every plastic step (random trials, all
// cases, with and without a cut-off), and equals sigma : C^-1 (trial - sigma) recomputed here.
TEST(MohrCoulombReturn, PlasticWorkIsNonNegative) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double min_work = 1e300;
  int n = 0;
  for (const Case& k : kCases)
    for (double cutoff : {1e300, 0.0, 0.3 * k.c}) {
      const Material m = mc(k.phi, k.psi, k.c, cutoff);
      for (int rep = 0; rep < 200; ++rep) {
        const V3 t = random_trial(rng, m, rep);
        const std::array<double, 4> t4 = tensor_from_sorted(t, rep % 3, 0.37 * rep);
        double s[4] = {t4[0], t4[1], t4[2], t4[3]};
        const double w = mohr_coulomb_return(m, s);
        const V3 r = sorted_principal({s[0], s[1], s[2], s[3]});
        const double want = dot(r, compl_(m, add(t, r, -1.0)));
        const double scale = (std::fabs(t[0]) + std::fabs(t[2]) + k.c);
        const double wscale = scale * scale / m.young_modulus;  // J/m^3 of a stress scale
        // Non-negative up to round-off (1e-12 of the work scale sigma^2 / E).
        EXPECT_GE(w, -kWorkRoundOffRel * wscale)
            << "phi " << k.phi << " psi " << k.psi << " c " << k.c << " cutoff " << cutoff;
        EXPECT_NEAR(w, want, kReturnRel * wscale);  // the definition, to round-off
        if (w != 0.0) {
          ++n;
          min_work = std::min(min_work, w / wscale);
        }
      }
    }
  EXPECT_GT(n, 1000);
  std::printf("[measured] plastic work: %d plastic steps, min work / (sigma^2/E) = %.3e\n", n,
              min_work);
}

// (f) The in-plane principal directions are preserved: the returned 2 sxy / (sxx - syy) (the
// angle atan2(2 sxy, sxx - syy)) equals the trial's whenever the returned in-plane pair is
// distinct (not on the apex and not on an edge where the two in-plane stresses are equal).
TEST(MohrCoulombReturn, InPlanePrincipalDirectionsPreserved) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int checked = 0;
  double worst = 0.0;
  for (const Case& k : kCases) {
    const Material m = mc(k.phi, k.psi, k.c);
    for (int rep = 0; rep < 200; ++rep) {
      const V3 t = random_trial(rng, m, rep);
      if (yield(m, t) <= 0.0) continue;
      const std::array<double, 4> t4 = tensor_from_sorted(t, rep % 3, kPi * U(rng));
      double s[4] = {t4[0], t4[1], t4[2], t4[3]};
      mohr_coulomb_return(m, s);
      const Principal pr = principal({s[0], s[1], s[2], s[3]}), pt = principal(t4);
      const double scale = std::fabs(t[0]) + std::fabs(t[2]) + k.c;
      if (pr.radius < 1e-6 * scale) continue;  // in-plane pair equal: direction undefined
      ++checked;
      double d = std::fabs(pr.angle2 - pt.angle2);
      d = std::min(d, 2 * kPi - d);
      worst = std::max(worst, d);
      // 1e-9 rad: the angle is recomputed from round-off-perturbed components.
      EXPECT_LE(d, kDirectionRad);
      // The ratio itself (sxx - syy may vanish at 45 deg: compare cross-multiplied).
      EXPECT_NEAR(s[2] * (t4[0] - t4[1]), t4[2] * (s[0] - s[1]), kReturnRel * scale * scale);
    }
  }
  EXPECT_GT(checked, 500);
  std::printf("[measured] in-plane direction: %d checked, max angle change %.2e rad\n", checked,
              worst);
}

// (f2) Ties in the principal order. The return sorts s_zz among the in-plane pair a >= b (three
// cases from two comparisons; an exact tie keeps the in-plane value first). A plastic trial with
// a tied pair returns to the edge where the pair stays equal (the main plane would pull the two
// apart in the wrong order), so the result must not depend on how the tie was broken: it is
// continuous from both sides. Exact ties: with s_xy = 0 and representable halves, a = s_xx and
// b = s_yy exactly. Tolerance 1e-8 of the stress scale: the 1e-6 Pa offset times the slope of the
// return (of order 1), far above round-off (1e-16 of 9e4 Pa).
TEST(MohrCoulombReturn, PrincipalTiesReturnContinuously) {
  const Material m = mc(30.0, 10.0, 5e3);
  const double sxx = -1.0e4, syy = -9.0e4;  // a = -1e4, b = -9e4 (f > 0: plastic)
  auto ret = [&](double szz) {
    std::array<double, 4> s{sxx, syy, 0.0, szz};
    mohr_coulomb_return(m, s.data());
    return s;
  };
  for (const double tie : {sxx, syy}) {
    const std::array<double, 4> at = ret(tie), below = ret(tie - 1e-6), above = ret(tie + 1e-6);
    ASSERT_NE(at[0], sxx);  // it did return
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(at[k], below[k], kTieOffsetRel * 9e4) << "tie at " << tie << ", component " << k;
      EXPECT_NEAR(at[k], above[k], kTieOffsetRel * 9e4) << "tie at " << tie << ", component " << k;
    }
    // On the edge: the tied pair (s_zz and the in-plane value it ties) stays equal.
    const double in_plane = tie == sxx ? at[0] : at[1];
    EXPECT_NEAR(at[3], in_plane, kTwoRoutesRel * 9e4) << "tie at " << tie;
  }
}

// (g) Jaumann rotation under a rigid spin (L antisymmetric, L_xy = -omega, L_yx = omega, spin
// w = (L_xy - L_yx)/2 = -omega): per step, the trace is unchanged to round-off and the von Mises
// stress to O(dt^2) (forward Euler of a rotation grows the deviatoric radius by
// sqrt(1 + 4 w^2 dt^2)); over many small steps, the stress is R(omega t) sigma0 R^T.
// (h) The branch-free return (mohr_coulomb_return_selected, the host G2P's vectorised path)
// gives mohr_coulomb_return's stress and work on every route: elastic, the main plane, either
// edge and the apex, each with and without the tension cut-off. Every route must be exercised.
TEST(MohrCoulombReturn, SelectedReturnEqualsTheBranchingReturn) {
  std::mt19937 rng(57);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int elastic = 0, main_plane = 0, upper_edge = 0, lower_edge = 0, apex = 0;
  for (const Case& k : kCases)
    for (double cutoff : {1e300, 0.0, 0.3 * k.c}) {
      const lsi::mpm::PreparedMaterial m(mc(k.phi, k.psi, k.c, cutoff));
      for (int rep = 0; rep < 200; ++rep) {
        const V3 t = random_trial(rng, m.material, rep);
        const std::array<double, 4> t4 = tensor_from_sorted(t, rep % 3, kPi * U(rng));
        double full[4] = {t4[0], t4[1], t4[2], t4[3]}, sel[4] = {t4[0], t4[1], t4[2], t4[3]};
        const double w_full = mohr_coulomb_return(m, full);
        const double w_sel = lsi::mpm::mohr_coulomb_return_selected(m, sel);
        // The same operations in the same order on each route: equal to the last bit but for
        // the compiler's contraction of multiply-adds (round-off of the stress scale).
        const double scale = std::fabs(t[0]) + std::fabs(t[2]) + k.c;
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(sel[i], full[i], kRoundOffAbs + 1e-14 * scale);
        EXPECT_NEAR(w_sel, w_full, 1e-14 * scale * scale / m.material.young_modulus);
        // The route, from the return's own candidates.
        const lsi::mpm::PrincipalTrial pt = lsi::mpm::principal_trial(t4.data());
        const double f = lsi::mpm::yield_planes(m, pt.value[0], pt.value[2]);
        const double tol = 1e-12 * lsi::mpm::return_scale(m, pt);
        if (!(f > tol)) {
          ++elastic;
          continue;
        }
        const lsi::mpm::FlowDirections D = lsi::mpm::flow_directions(m);
        double r[3];
        lsi::mpm::main_plane_return(m, pt.value, f, D, r);
        const bool upper = r[1] > r[0];
        if (lsi::mpm::ordered(r) && (r[0] + r[1] + r[2]) / 3.0 <= m.apex)
          ++main_plane;
        else if (!lsi::mpm::ordered(r) && lsi::mpm::edge_return(m, pt.value, f, upper, D, tol, r) &&
                 (r[0] + r[1] + r[2]) / 3.0 <= m.apex)
          ++(upper ? upper_edge : lower_edge);
        else
          ++apex;
      }
    }
  std::printf(
      "[measured] routes: elastic %d, main plane %d, upper edge %d, lower edge %d, apex %d\n",
      elastic, main_plane, upper_edge, lower_edge, apex);
  // Of the 7200 trials, each route takes a tenth or more (a fixed seed).
  EXPECT_GT(elastic, 500);
  EXPECT_GT(main_plane, 500);
  EXPECT_GT(upper_edge, 500);
  EXPECT_GT(lower_edge, 500);
  EXPECT_GT(apex, 500);
}

TEST(JaumannRotate, RigidRotationInvariantsAndAngle) {
  const std::array<double, 4> s0 = tensor(-20e3, -80e3, 0.3, -45e3);  // major axis at 0.3 rad
  auto von_mises = [](const double s[4]) {
    const double a = s[0] - s[1], b = s[1] - s[3], c = s[3] - s[0];
    return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * s[2] * s[2]);
  };
  const double omega = 2.0;  // rad/s
  // One step: the relative change of the von Mises stress is <= 2 (w dt)^2 (3 R^2 <= q^2), and
  // scales as dt^2 (ratio ~4 when dt halves).
  double change[2];
  for (int k = 0; k < 2; ++k) {
    const double dt = 1e-3 / (1 << k);
    double s[4] = {s0[0], s0[1], s0[2], s0[3]};
    const double q0 = von_mises(s), tr0 = s[0] + s[1] + s[3];
    jaumann_rotate(s, -omega, dt);
    EXPECT_NEAR(s[0] + s[1] + s[3], tr0, kTwoRoutesRel * std::fabs(tr0));  // trace: round-off
    EXPECT_DOUBLE_EQ(s[3], s0[3]);                                         // szz is not rotated
    change[k] = std::fabs(von_mises(s) - q0) / q0;
    EXPECT_LE(change[k], 2.0 * (omega * dt) * (omega * dt) * (1 + 1e-6));
  }
  EXPECT_NEAR(change[0] / change[1], 4.0, 0.05);  // second order: halving dt quarters it
  // Many steps: a quarter turn (pi/2) in N steps.
  const double total = kPi / 2, T = total / omega;
  const int N = 20000;
  const double dt = T / N;
  double s[4] = {s0[0], s0[1], s0[2], s0[3]};
  for (int i = 0; i < N; ++i) jaumann_rotate(s, -omega, dt);
  const Principal p0 = principal(s0), p1 = principal({s[0], s[1], s[2], s[3]});
  double dth = 0.5 * (p1.angle2 - p0.angle2) - total;  // principal axis turned by omega T
  dth = std::remainder(dth, kPi);
  // Angle error per step ~ (2/3) (w dt)^3 (atan(2 w dt)/2 vs w dt): total ~ (2/3) theta (w dt)^2,
  // here ~1e-8 rad; bound 1e-7.
  EXPECT_LE(std::fabs(dth), 1e-7);
  // Radius drift (1 + 4 w^2 dt^2)^(N/2) - 1 ~ 2 theta w dt = 2.5e-4: bound 3e-4 relative; trace
  // exact.
  EXPECT_NEAR(p1.radius / p0.radius, 1.0, 3e-4);
  EXPECT_NEAR(s[0] + s[1], s0[0] + s0[1], kIntegratedRel * std::fabs(s0[0] + s0[1]));
  // Against R sigma0 R^T component-wise (rotation of a symmetric tensor by angle a: the
  // in-plane deviatoric part turns by 2a).
  const std::array<double, 4> want = tensor(p0.major, p0.minor, 0.5 * p0.angle2 + total, s0[3]);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(s[i], want[i], 3e-4 * p0.radius) << i;
  std::printf(
      "[measured] Jaumann: one-step von Mises change %.3e (dt=1e-3) %.3e (dt=5e-4); "
      "quarter turn in %d steps: angle error %.2e rad, radius drift %.2e\n",
      change[0], change[1], N, dth, p1.radius / p0.radius - 1);
}

}  // namespace
