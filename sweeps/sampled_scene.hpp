// One sample of a sweep as the closed-form models see it: the numeric scene values in a flat,
// device-copyable struct, their validity check and the evaluation of the empirical and analytical
// models. Used inside the batched sweep kernel (sweeps/closed_form_sweep.hpp): no allocation, no
// strings, no I/O.
//
// The ranges below are the one definition of the numeric scene keys' ranges: the scene parser
// (io/scene_parser.cpp) reads them from here. The checks beyond single ranges (the top width
// against the base width, the face in the base) are repeated there with its messages; a test on
// random samples checks that a sample is valid here exactly when the scene parser accepts it.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/closed_form/barrier_sliding.hpp"
#include "kernels/closed_form/empirical_model.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/momentum_barrier.hpp"
#include "kernels/closed_form/two_body_model.hpp"
#include "kernels/common/constants.hpp"
#include "kernels/common/math.hpp"

namespace lsi::sweeps {

// The numeric scene keys a study may sample (JSON pointers in scene_field_pointer).
enum SceneField : int {
  thickness_m,
  velocity_m_s,
  density_kg_m3,
  body_squares,
  length_m,
  flow_base_friction,
  porosity,
  friction_angle_deg,
  cohesion_kpa,
  young_modulus_mpa,
  poisson_ratio,
  hydraulic_conductivity_m_s,
  liquid_bulk_modulus_mpa,
  liquid_viscosity_kpa_s,
  height_m,
  base_width_m,
  top_width_m,
  face_angle_deg,
  barrier_density_kg_m3,
  barrier_mass_kg_per_m,
  base_friction,
  face_friction,
  empirical_a1,
  empirical_a2,
  empirical_tau,
  empirical_kappa,
  analytical_lambda,
  analytical_tau,
  scene_field_count
};

inline constexpr const char* scene_field_pointer[scene_field_count] = {
    "/landslide/thickness_m",
    "/landslide/velocity_m_s",
    "/landslide/density_kg_m3",
    "/landslide/shape/body_squares",
    "/landslide/shape/length_m",
    "/landslide/base_friction",
    "/landslide/material/porosity",
    "/landslide/material/friction_angle_deg",
    "/landslide/material/cohesion_kpa",
    "/landslide/material/young_modulus_mpa",
    "/landslide/material/poisson_ratio",
    "/landslide/material/hydraulic_conductivity_m_s",
    "/landslide/material/liquid_bulk_modulus_mpa",
    "/landslide/material/liquid_viscosity_kpa_s",
    "/barrier/height_m",
    "/barrier/base_width_m",
    "/barrier/top_width_m",
    "/barrier/face_angle_deg",
    "/barrier/density_kg_m3",
    "/barrier/mass_kg_per_m",
    "/barrier/base_friction",
    "/barrier/face_friction",
    "/methods/empirical/a1",
    "/methods/empirical/a2",
    "/methods/empirical/tau",
    "/methods/empirical/kappa",
    "/methods/analytical/lambda",
    "/methods/analytical/tau"};

// The fields by name, as the enum spells them: the last key of the pointer, with the landslide's
// or barrier's density and base friction and the methods' coefficients told apart (the keyword
// arguments of the Python module's closed forms, python/closed_forms.cpp).
inline constexpr const char* scene_field_name[scene_field_count] = {
    "thickness_m",
    "velocity_m_s",
    "density_kg_m3",
    "body_squares",
    "length_m",
    "flow_base_friction",
    "porosity",
    "friction_angle_deg",
    "cohesion_kpa",
    "young_modulus_mpa",
    "poisson_ratio",
    "hydraulic_conductivity_m_s",
    "liquid_bulk_modulus_mpa",
    "liquid_viscosity_kpa_s",
    "height_m",
    "base_width_m",
    "top_width_m",
    "face_angle_deg",
    "barrier_density_kg_m3",
    "barrier_mass_kg_per_m",
    "base_friction",
    "face_friction",
    "empirical_a1",
    "empirical_a2",
    "empirical_tau",
    "empirical_kappa",
    "analytical_lambda",
    "analytical_tau",
};

// Allowed range of each field: lo/hi with open or closed ends (infinite = unbounded); `integer`
// for counts. top_width_m's upper bound is base_width_m and face_angle_deg must also fit the
// face in the base (checked separately).
struct FieldRange {
  double lo, hi;
  bool lo_closed, hi_closed, integer;
};
inline constexpr double unbounded = math::infinity();
// A function rather than a table at namespace scope: device code (a CUDA build checks samples on
// the GPU) cannot read the host's global arrays. A switch rather than a local constexpr array:
// GCC built the 27-entry array on the stack at every call (a 648-byte memcpy per sample in the
// sweep kernel, 12 % of its time in perf); the switch folds to constants once inlined.
KOKKOS_INLINE_FUNCTION constexpr FieldRange scene_field_range(int field) {
  switch (field) {
    case thickness_m:
      return {0, unbounded, false, false, false};  // > 0
    case velocity_m_s:
      return {0, unbounded, false, false, false};  // > 0
    case density_kg_m3:
      return {0, unbounded, false, false, false};  // > 0
    case body_squares:
      return {0, 1000000, true, true, true};  // integer in [0, 1e6]
    case length_m:
      return {0, unbounded, false, false, false};  // > 0
    case porosity:
      return {0, 1, false, false, false};  // (0, 1)
    case friction_angle_deg:
      return {0, 90, true, false, false};  // [0, 90)
    case cohesion_kpa:
      return {0, unbounded, true, false, false};  // >= 0
    case young_modulus_mpa:
      return {0, unbounded, false, false, false};  // > 0
    case poisson_ratio:
      return {-1, 0.5, false, false, false};  // (-1, 0.5)
    case hydraulic_conductivity_m_s:
      return {0, unbounded, false, false, false};  // > 0
    case liquid_bulk_modulus_mpa:
      return {0, unbounded, false, false, false};  // > 0
    case liquid_viscosity_kpa_s:
      return {0, unbounded, false, false, false};  // > 0
    case height_m:
      return {0, unbounded, false, false, false};  // > 0
    case base_width_m:
      return {0, unbounded, false, false, false};  // > 0
    case top_width_m:
      return {0, unbounded, true, true, false};  // [0, base_width_m]
    case face_angle_deg:
      return {0, 90, false, true, false};  // (0, 90]
    case barrier_density_kg_m3:
      return {0, unbounded, false, false, false};  // > 0
    case barrier_mass_kg_per_m:
      return {0, unbounded, false, false, false};  // > 0
    case base_friction:
      return {0, unbounded, true, false, false};  // >= 0
    case face_friction:
      return {0, unbounded, true, false, false};  // >= 0
    case flow_base_friction:
      return {0, unbounded, true, false, false};  // >= 0
    case empirical_a1:
      return {0, unbounded, false, false, false};  // > 0
    case empirical_a2:
      return {-5, 5, true, true, false};  // [-5, 5]
    case empirical_tau:
      return {0, 1, false, false, false};  // (0, 1)
    case empirical_kappa:
      return {0, unbounded, true, false, false};  // >= 0
    case analytical_lambda:
      return {0, 1, false, true, false};  // (0, 1]
    case analytical_tau:
      return {0, 1, false, false, false};  // (0, 1)
    default:
      return {0, 0, false, false, false};  // not a field: nothing is in range
  }
}

// The same tolerance as the scene parser's face run-out check H / tan(beta) <= B - b.
inline constexpr double face_run_out_tolerance_m = 1e-9;

struct SceneValues {
  double value[scene_field_count] = {};
  bool rectangle = false;  // landslide shape kind (else front-body-tail)
  bool barrier_given_by_mass = false;
  bool fixed = false;
  bool analytical_lambda_given = false, analytical_tau_given = false;
  // The barrier model of each closed form (model/scene.hpp, BarrierModel): false = the paper's.
  bool empirical_momentum = false, analytical_momentum = false;
  bool saturated_flow = true;  // the flow's base friction acts on its grains' share of the weight
};

// The flow's base friction as a deceleration of the flow, F1 / m1 (m/s^2): tan(phi_b) g times the
// share of the weight its grains carry onto the base: 1 - n rho_L / rho_m for a saturated flow at
// hydrostatic pore pressure (what the MPM's Coulomb base acts on, the effective stress plus
// (1 - n) p), 1 for a dry one (model/closed_form_methods.cpp uses the same).
KOKKOS_INLINE_FUNCTION double flow_friction_deceleration(double base_friction, double porosity,
                                                         double density, bool saturated) {
  const double share = saturated ? 1.0 - porosity * 1000.0 / density : 1.0;
  return base_friction * gravity * (share > 0.0 ? share : 0.0);
}

// One expression without branches (NaN and +-inf are never valid), so that a loop of checks over
// a block of samples vectorises (closed_form_sweep.hpp). A finite v is an integer where it equals
// its nearest integer: nearbyint, which GCC vectorises (floor it does not, under the default
// -ftrapping-math).
KOKKOS_INLINE_FUNCTION bool in_range(double v, const FieldRange& r) {
  const bool finite = (v == v) & (v != unbounded) & (v != -unbounded);
  const bool above = r.lo_closed ? v >= r.lo : v > r.lo;
  const bool below = r.hi_closed ? v <= r.hi : v < r.hi;
  return finite & above & below & (!r.integer | (v == math::nearbyint(v)));
}

// Whether a scene of s's kind leaves field f unchecked: the fields it does not use (e.g.
// length_m, used only by a rectangle).
KOKKOS_INLINE_FUNCTION bool field_unused(const SceneValues& s, int f) {
  return (f == body_squares && s.rectangle) || (f == length_m && !s.rectangle) ||
         (f == barrier_density_kg_m3 && s.barrier_given_by_mass) ||
         (f == barrier_mass_kg_per_m && !s.barrier_given_by_mass);
}

// Whether value v of a used field f other than top_width_m fails its check, r its range:
// positive_invalid = f == empirical_kappa with the momentum-consistent empirical variant, which
// has no static load after the pulse (the parser: methods.empirical.kappa must be 0 with it).
KOKKOS_INLINE_FUNCTION bool value_invalid(double v, const FieldRange& r, bool positive_invalid) {
  return (!in_range(v, r)) | (positive_invalid & (v > 0.0));
}

// Whether field f of a sample fails its check: its range, and the checks between fields that
// name f (the top width against the base width; kappa with the momentum-consistent empirical
// variant). Only the fields the scene uses are checked.
KOKKOS_INLINE_FUNCTION bool field_invalid(const SceneValues& s, int f) {
  if (field_unused(s, f)) return false;
  if (f == top_width_m) {
    const double b = s.value[top_width_m];
    return !(b >= 0.0 && b <= s.value[base_width_m] && math::isfinite(b));
  }
  return value_invalid(s.value[f], scene_field_range(f),
                       f == empirical_kappa && s.empirical_momentum);
}

// Whether the upstream face, which runs out H / tan(beta) horizontally, does not fit in B - b.
KOKKOS_INLINE_FUNCTION bool face_runs_out(const SceneValues& s) {
  const double beta_deg = s.value[face_angle_deg];
  if (beta_deg == 90.0) return false;
  const double run_out = s.value[height_m] / math::tan(math::degrees_to_radians(beta_deg));
  return run_out > s.value[base_width_m] - s.value[top_width_m] + face_run_out_tolerance_m;
}

// The first invalid field of a sample, or -1 if the scene is valid; a face that does not fit
// is face_angle_deg's, after every field's own check.
KOKKOS_INLINE_FUNCTION int first_invalid_field(const SceneValues& s) {
  for (int f = 0; f < scene_field_count; ++f)
    if (field_invalid(s, f)) return f;
  return face_runs_out(s) ? face_angle_deg : -1;
}

// The checks of a sweep's samples: when the base scene is valid and a sample differs from it
// only in the sampled fields, only those fields (and the top width, when the base width is
// sampled) can fail, and the face only when one of its four dimensions is sampled; the others
// are skipped, in the same order, so that the first invalid field is the same. With an invalid
// base scene every check is made.
struct SampleChecks {
  int fields[scene_field_count] = {};
  int field_count = 0;
  bool face = true;
};

inline SampleChecks sample_checks(const SceneValues& base, const int* targets, int target_count) {
  SampleChecks c;
  bool sampled[scene_field_count] = {};
  for (int d = 0; d < target_count; ++d)
    if (targets[d] >= 0 && targets[d] < scene_field_count) sampled[targets[d]] = true;
  const bool all = first_invalid_field(base) >= 0;
  for (int f = 0; f < scene_field_count; ++f)
    if (all || sampled[f] || (f == top_width_m && sampled[base_width_m]))
      c.fields[c.field_count++] = f;
  c.face = all || sampled[height_m] || sampled[base_width_m] || sampled[top_width_m] ||
           sampled[face_angle_deg];
  return c;
}

// first_invalid_field of a sample of the scene `checks` were made for.
KOKKOS_INLINE_FUNCTION int first_invalid_field(const SceneValues& s, const SampleChecks& checks) {
  for (int k = 0; k < checks.field_count; ++k)
    if (field_invalid(s, checks.fields[k])) return checks.fields[k];
  return checks.face && face_runs_out(s) ? face_angle_deg : -1;
}

// Model inputs derived from the scene values (as model/closed_form_methods.cpp derives them).
struct ModelInputs {
  double landslide_mass, equivalent_length, barrier_mass, face_angle_rad;
};
KOKKOS_INLINE_FUNCTION ModelInputs model_inputs(const SceneValues& s) {
  ModelInputs m;
  const double h = s.value[thickness_m];
  // 45 deg front + i squares + 3h tail: L1,0 = (2 + i) h; a rectangle: its length.
  m.equivalent_length = s.rectangle ? s.value[length_m] : (2.0 + s.value[body_squares]) * h;
  m.landslide_mass = s.value[density_kg_m3] * m.equivalent_length * h;
  const double area = 0.5 * (s.value[base_width_m] + s.value[top_width_m]) * s.value[height_m];
  m.barrier_mass = s.fixed ? unbounded
                           : (s.barrier_given_by_mass ? s.value[barrier_mass_kg_per_m]
                                                      : s.value[barrier_density_kg_m3] * area);
  m.face_angle_rad = math::degrees_to_radians(s.value[face_angle_deg]);
  return m;
}

// The four scalar outputs of a closed-form method, in this order in the sweep tables.
enum ClosedFormOutput : int {
  peak_force,
  rise_time,
  impact_duration,
  final_displacement,
  closed_form_output_count
};
inline constexpr const char* closed_form_output_name[closed_form_output_count] = {
    "peak_force", "rise_time", "impact_duration", "final_displacement"};
inline constexpr const char* closed_form_output_units[closed_form_output_count] = {"N/m", "s", "s",
                                                                                   "m"};

KOKKOS_INLINE_FUNCTION void store_pulse(const ForcePulse& p, const ModelInputs& m,
                                        const SceneValues& s, double* out) {
  out[peak_force] = p.peak;
  out[rise_time] = p.rise_time;
  out[impact_duration] = p.duration;
  out[final_displacement] =
      final_displacement_under(p, m.barrier_mass, s.value[base_friction], m.face_angle_rad);
}

// The momentum-consistent barrier under a fixed-barrier pulse (momentum_barrier.hpp), with the
// face resolved with the face friction.
KOKKOS_INLINE_FUNCTION void store_momentum(const ForcePulse& fixed_pulse, const ModelInputs& m,
                                           const SceneValues& s, const FaceResolution& face,
                                           double* out) {
  MomentumBarrierSetup b;
  b.fixed_pulse =
      momentum_capped_pulse(fixed_pulse, m.landslide_mass, s.value[velocity_m_s], face.horizontal);
  b.landslide_mass = m.landslide_mass;
  b.velocity = s.value[velocity_m_s];
  b.barrier_mass = m.barrier_mass;
  b.base_friction = s.value[base_friction];
  b.face = face;
  b.flow_friction = flow_friction_deceleration(s.value[flow_base_friction], s.value[porosity],
                                               s.value[density_kg_m3], s.saturated_flow);
  const MomentumBarrierResult r = momentum_barrier(b);
  out[peak_force] = r.peak_force;
  out[rise_time] = r.rise_time;
  out[impact_duration] = r.contact_end;
  out[final_displacement] = s.fixed ? 0.0 : r.final_displacement;
}

// Empirical model (Di Perna et al. 2022) of a valid sample.
KOKKOS_INLINE_FUNCTION void evaluate_empirical(const SceneValues& s, double* out) {
  const ModelInputs m = model_inputs(s);
  EmpiricalCoefficients c;
  c.a1 = s.value[empirical_a1];
  c.a2 = s.value[empirical_a2];
  c.tau = s.value[empirical_tau];
  c.kappa = s.value[empirical_kappa];
  const EmpiricalImpact imp =
      empirical_impact(s.value[thickness_m], s.value[velocity_m_s], s.value[density_kg_m3],
                       m.landslide_mass, m.face_angle_rad, c);
  if (s.empirical_momentum)
    store_momentum(imp.pulse, m, s, resolve_face_force(m.face_angle_rad, s.value[face_friction]),
                   out);
  else
    store_pulse(imp.pulse, m, s, out);
}

// Analytical two-body model (Cuomo et al. 2022) of a valid sample; lambda and tau default to the
// paper's values for the barrier kind unless the scene (or the study) gives them.
KOKKOS_INLINE_FUNCTION void evaluate_analytical(const SceneValues& s, double* out) {
  const ModelInputs m = model_inputs(s);
  TwoBodyCoefficients c = default_two_body_coefficients(s.fixed || s.analytical_momentum);
  if (s.analytical_lambda_given) c.lambda = s.value[analytical_lambda];
  if (s.analytical_tau_given) c.tau = s.value[analytical_tau];
  if (s.analytical_momentum) {
    const FaceResolution face = resolve_face_force(m.face_angle_rad, s.value[face_friction]);
    store_momentum(momentum_two_body_pulse(m.landslide_mass, s.value[velocity_m_s],
                                           m.equivalent_length, c.lambda, c.tau, face.horizontal),
                   m, s, face, out);
    return;
  }
  const TwoBodyImpact imp = two_body_impact(m.landslide_mass, s.value[velocity_m_s],
                                            m.equivalent_length, m.barrier_mass, c);
  store_pulse(imp.pulse, m, s, out);
}

}  // namespace lsi::sweeps
