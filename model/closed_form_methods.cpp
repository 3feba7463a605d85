#include "model/closed_form_methods.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/closed_form/barrier_geometry.hpp"
#include "kernels/closed_form/barrier_sliding.hpp"
#include "kernels/closed_form/barrier_stability.hpp"
#include "kernels/closed_form/empirical_model.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/inverse_design.hpp"
#include "kernels/closed_form/momentum_barrier.hpp"
#include "kernels/closed_form/peak_force_families.hpp"
#include "kernels/closed_form/two_body_model.hpp"
#include "model/input_error.hpp"
#include "model/messages.hpp"
#include "sweeps/sampled_scene.hpp"

namespace lsi {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

BarrierGeometry geometry_of(const SceneBarrier& b) {
  BarrierGeometry g;
  g.height = b.height_m;
  g.base_width = b.base_width_m;
  g.top_width = b.top_width_m;
  g.face_angle = math::degrees_to_radians(b.face_angle_deg);
  return g;
}

SlidingBlock block_of(const SceneBarrier& b, double mass, const FaceResolution& face) {
  return SlidingBlock{mass, b.base_friction, face.sliding_drive(b.base_friction)};
}

// Uniform samples on [0, t_end] plus the breakpoints, sorted and unique.
std::vector<double> time_grid(double t_end, std::vector<double> breakpoints) {
  std::vector<double> t(history_samples);
  for (int i = 0; i < history_samples; ++i) t[i] = t_end * i / (history_samples - 1);
  for (double b : breakpoints)
    if (std::isfinite(b) && b > 0.0 && b < t_end) t.push_back(b);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

// Fills the force and barrier parts of a result from a pulse; the caller adds the energy.
template <class Energy>
void fill_histories(MethodResult& r, const Scene& scene, const ForcePulse& pulse,
                    const FaceResolution& face, double barrier_mass, Energy&& energy) {
  const SceneBarrier& b = scene.barrier;
  BarrierMotion motion;
  if (!b.fixed) motion = barrier_motion(pulse, block_of(b, barrier_mass, face));
  const double stop = motion.moves ? motion.stop_time : 0.0;
  const double t_end =
      1.1 * (std::isfinite(stop) ? std::max(pulse.duration, stop) : 2.0 * pulse.duration);
  r.time = time_grid(t_end, {pulse.rise_time, pulse.duration, motion.start_time, stop});
  for (double t : r.time) {
    const double F = pulse.force(t);
    r.force.push_back(F);
    r.force_horizontal.push_back(F * face.horizontal);
    r.force_vertical.push_back(F * face.vertical_down);
    r.landslide_kinetic_energy.push_back(energy(t));
    r.barrier_velocity.push_back(motion.velocity(t));
    r.barrier_displacement.push_back(motion.displacement(t));
  }
  r.peak_force = pulse.peak;
  r.rise_time = pulse.rise_time;
  r.impact_duration = pulse.duration;
  r.final_displacement = b.fixed ? 0.0 : motion.final_displacement;
  r.scalars.peak_force_horizontal = pulse.peak * face.horizontal;
  r.scalars.impulse = pulse.pulse_impulse();
  if (!b.fixed && motion.moves) {
    r.scalars.barrier_start_time = motion.start_time;
    r.scalars.barrier_stop_time = motion.stop_time;
  }
  // Static safety under this history (the resultant at half the flow thickness).
  const double mass = std::isfinite(barrier_mass) ? barrier_mass : scene.barrier.mass();
  const StabilityCheck s = barrier_stability(
      r.time.data(), r.force.data(), static_cast<int>(r.time.size()), geometry_of(b), face, mass,
      b.base_friction, 0.5 * scene.landslide.thickness_m);
  r.scalars.min_sliding_safety = s.min_sliding_safety;
  r.scalars.min_overturning_safety = s.min_overturning_safety;
  r.scalars.overturning_resultant_height = s.resultant_height;
}

// The momentum-consistent barrier (kernels/closed_form/momentum_barrier.hpp) under a
// fixed-barrier pulse: the face resolved with the scene's face friction.
MomentumBarrierSetup momentum_setup(const Scene& scene, const ForcePulse& fixed_pulse,
                                    double barrier_mass) {
  MomentumBarrierSetup s;
  s.landslide_mass = scene.landslide.mass_kg_per_m();
  s.velocity = scene.landslide.velocity_m_s;
  s.barrier_mass = scene.barrier.fixed ? std::numeric_limits<double>::infinity() : barrier_mass;
  s.base_friction = scene.barrier.base_friction;
  s.face = resolve_face_force(math::degrees_to_radians(scene.barrier.face_angle_deg),
                              scene.barrier.face_friction);
  s.fixed_pulse =
      momentum_capped_pulse(fixed_pulse, s.landslide_mass, s.velocity, s.face.horizontal);
  s.flow_friction = flow_friction_deceleration(scene);
  return s;
}

// Histories and summaries of the momentum-consistent barrier: the force the barrier receives
// (not the fixed pulse), the flow's horizontal kinetic energy, the barrier's motion.
void fill_momentum_histories(MethodResult& r, const Scene& scene, const MomentumBarrierSetup& s) {
  const MomentumBarrierResult first = momentum_barrier(s);
  if (!first.ok)
    throw InputError(
        "the momentum-consistent barrier could not be integrated for this scene "
        "(a non-finite model input)");
  const double end = std::isfinite(first.stop_time) ? std::max(first.contact_end, first.stop_time)
                                                    : 2.0 * first.contact_end;
  r.time =
      time_grid(1.1 * end, {first.rise_time, first.contact_end, first.start_time, first.stop_time});
  std::vector<MomentumBarrierState> st(r.time.size());
  const MomentumBarrierResult res =
      momentum_barrier(s, r.time.data(), int(r.time.size()), st.data());
  const double m1 = s.landslide_mass;
  for (const MomentumBarrierState& x : st) {
    r.force.push_back(x.force);
    r.force_horizontal.push_back(x.force * s.face.horizontal);
    r.force_vertical.push_back(x.force * s.face.vertical_down);
    r.landslide_kinetic_energy.push_back(0.5 * m1 * x.landslide_velocity * x.landslide_velocity);
    r.barrier_velocity.push_back(x.barrier_velocity);
    r.barrier_displacement.push_back(x.barrier_displacement);
  }
  r.peak_force = res.peak_force;
  r.rise_time = res.rise_time;
  r.impact_duration = res.contact_end;
  r.final_displacement = scene.barrier.fixed ? 0.0 : res.final_displacement;
  r.barrier_model = "momentum";
  r.scalars.peak_force_horizontal = res.peak_force * s.face.horizontal;
  double impulse = 0.0;  // the barrier's, from the force it received
  for (size_t i = 1; i < r.time.size(); ++i)
    impulse += 0.5 * (r.force[i] + r.force[i - 1]) * (r.time[i] - r.time[i - 1]);
  r.scalars.impulse = impulse;
  r.scalars.flow_friction_deceleration = s.flow_friction;
  r.scalars.largest_barrier_velocity = res.largest_barrier_velocity;
  if (!scene.barrier.fixed && res.start_time >= 0.0) {
    r.scalars.barrier_start_time = res.start_time;
    r.scalars.barrier_stop_time = res.stop_time;
  }
  const double mass = scene.barrier.mass();
  const StabilityCheck stab = barrier_stability(
      r.time.data(), r.force.data(), static_cast<int>(r.time.size()), geometry_of(scene.barrier),
      s.face, mass, scene.barrier.base_friction, 0.5 * scene.landslide.thickness_m);
  r.scalars.min_sliding_safety = stab.min_sliding_safety;
  r.scalars.min_overturning_safety = stab.min_overturning_safety;
  r.scalars.overturning_resultant_height = stab.resultant_height;
}

EmpiricalCoefficients empirical_coefficients(const Scene& scene) {
  EmpiricalCoefficients c;
  if (scene.methods.empirical) {
    c.a1 = scene.methods.empirical->a1;
    c.a2 = scene.methods.empirical->a2;
    c.tau = scene.methods.empirical->tau;
    c.kappa = scene.methods.empirical->kappa;
  }
  return c;
}

bool momentum(const std::optional<EmpiricalParameters>& p) {
  return p && p->barrier_model == BarrierModel::Momentum;
}
bool momentum(const std::optional<AnalyticalParameters>& p) {
  return p && p->barrier_model == BarrierModel::Momentum;
}

TwoBodyCoefficients two_body_coefficients(const Scene& scene, bool fixed) {
  // The momentum-consistent variant's pulse is the fixed barrier's, free barrier or not.
  TwoBodyCoefficients c =
      default_two_body_coefficients(fixed || momentum(scene.methods.analytical));
  if (scene.methods.analytical) {
    if (scene.methods.analytical->lambda) c.lambda = *scene.methods.analytical->lambda;
    if (scene.methods.analytical->tau) c.tau = *scene.methods.analytical->tau;
  }
  return c;
}

double face_angle(const Scene& s) { return math::degrees_to_radians(s.barrier.face_angle_deg); }

// The scene's impacts: one place that turns scene values into model inputs.
EmpiricalImpact empirical_impact_of(const Scene& scene) {
  const SceneLandslide& l = scene.landslide;
  return empirical_impact(l.thickness_m, l.velocity_m_s, l.density_kg_m3, l.mass_kg_per_m(),
                          face_angle(scene), empirical_coefficients(scene));
}

// m2 = +infinity for a fixed barrier.
TwoBodyImpact two_body_impact_of(const Scene& scene, double m2) {
  const SceneLandslide& l = scene.landslide;
  return two_body_impact(l.mass_kg_per_m(), l.velocity_m_s, l.equivalent_length_m(), m2,
                         two_body_coefficients(scene, scene.barrier.fixed));
}

MethodResult empirical_with_mass(const Scene& scene, double barrier_mass) {
  const EmpiricalImpact imp = empirical_impact_of(scene);
  MethodResult r;
  r.method = "empirical";
  if (momentum(scene.methods.empirical)) {
    fill_momentum_histories(r, scene, momentum_setup(scene, imp.pulse, barrier_mass));
  } else {
    r.barrier_model = "paper";
    fill_histories(r, scene, imp.pulse, resolve_face_force(face_angle(scene)), barrier_mass,
                   [&](double t) { return imp.landslide_kinetic_energy(t); });
  }
  r.scalars.froude_number = imp.froude;
  r.scalars.alpha = imp.alpha;
  r.scalars.normal_velocity = imp.normal_velocity;
  r.scalars.peak_force_dynamic = imp.peak_dynamic;
  r.scalars.peak_force_static = imp.peak_static;
  r.scalars.landslide_mass = imp.landslide_mass;
  return r;
}

MethodResult analytical_with_mass(const Scene& scene, double barrier_mass) {
  const bool fixed = scene.barrier.fixed;
  const double m2 = fixed ? std::numeric_limits<double>::infinity() : barrier_mass;
  const TwoBodyCoefficients c = two_body_coefficients(scene, fixed);
  MethodResult r;
  r.method = "analytical";
  if (momentum(scene.methods.analytical)) {
    const SceneLandslide& l = scene.landslide;
    const FaceResolution face = resolve_face_force(face_angle(scene), scene.barrier.face_friction);
    const ForcePulse pulse =
        momentum_two_body_pulse(l.mass_kg_per_m(), l.velocity_m_s, l.equivalent_length_m(),
                                c.lambda, c.tau, face.horizontal);
    fill_momentum_histories(r, scene, momentum_setup(scene, pulse, m2));
    r.scalars.lambda = c.lambda;
    r.scalars.tau = c.tau;
    r.scalars.landslide_mass = l.mass_kg_per_m();
    return r;
  }
  r.barrier_model = "paper";
  const TwoBodyImpact imp = two_body_impact_of(scene, m2);
  fill_histories(r, scene, imp.pulse, resolve_face_force(face_angle(scene)), m2,
                 [&](double t) { return imp.landslide_kinetic_energy(t); });
  r.scalars.lambda = c.lambda;
  r.scalars.tau = c.tau;
  r.scalars.reduced_mass = imp.reduced_mass;
  r.scalars.max_shortening = imp.max_shortening;
  r.scalars.K1 = imp.K1;
  r.scalars.q1 = imp.q1;
  r.scalars.common_velocity = imp.common_velocity;
  r.scalars.landslide_mass = imp.landslide_mass;
  return r;
}

// A closed form evaluated outside the range its arithmetic can represent (a coefficient of 1e308,
// a velocity of 1e-300) gives NaN or an infinity somewhere. Such a result is refused: it names
// the method, the first value that is not a number and the scene's inputs of the model. The only
// infinities that are results are a barrier that never stops (final displacement, stop time) and
// a load that cannot make it slide or overturn (the safety factors); the "not given" values are
// NaN by design (the literature formulas give no durations, a barrier that never moves no start
// or stop time).
void require_computable(const MethodResult& r, const Scene& scene) {
  auto fail = [&](const std::string& what, double v) {
    const SceneLandslide& l = scene.landslide;
    const nlohmann::json& src = scene.source;
    const nlohmann::json block = src.contains("methods") && src["methods"].contains(r.method)
                                     ? src["methods"][r.method]
                                     : nlohmann::json::object();
    throw InputError(
        "methods." + r.method + ": " + what + " = " + format_number(v) +
        " for this scene: its inputs lie outside the range in which the " + r.method +
        " model can be computed (landslide thickness_m = " + format_number(l.thickness_m) +
        ", velocity_m_s = " + format_number(l.velocity_m_s) + ", density_kg_m3 = " +
        format_number(l.density_kg_m3) + "; barrier mass " + format_number(scene.barrier.mass()) +
        " kg/m, base_friction = " + format_number(scene.barrier.base_friction) + "; methods." +
        r.method + " = " + block.dump() + ")");
  };
  const bool durations = r.method != "literature";
  const std::pair<const char*, double> scalars[] = {{"peak_force", r.peak_force},
                                                    {"rise_time", r.rise_time},
                                                    {"impact_duration", r.impact_duration}};
  for (const auto& [name, v] : scalars)
    if ((durations || std::string(name) == "peak_force") && !std::isfinite(v)) fail(name, v);
  if (durations && !(std::isfinite(r.final_displacement) || r.final_displacement == INFINITY))
    fail("final_displacement", r.final_displacement);
  for (const ScalarField& f : scalar_fields()) {
    const std::optional<double>& v = r.scalars.*(f.member);
    if (!v) continue;  // not given (a barrier that never moves has no start or stop time)
    const std::string key = f.name;
    const bool may_be_infinite = key == "barrier_stop_time" || key == "min_sliding_safety" ||
                                 key == "min_overturning_safety";
    if (!(std::isfinite(*v) || (may_be_infinite && *v == INFINITY))) fail(key, *v);
  }
  for (const HistoryField& h : history_fields())
    for (const double v : r.*(h.member))
      if (!std::isfinite(v)) fail(std::string("the history ") + h.name + " holds", v);
  for (const auto& [name, series] : r.series)
    for (const double v : series.values)
      if (!std::isfinite(v)) fail("the history " + name + " holds", v);
}

}  // namespace

double flow_friction_deceleration(const Scene& scene) {
  const SceneLandslide& l = scene.landslide;
  const bool dry = scene.methods.mpm && !scene.methods.mpm->saturated;
  return sweeps::flow_friction_deceleration(l.base_friction, l.material.porosity, l.density_kg_m3,
                                            !dry);
}

MethodResult run_empirical(const Scene& scene) {
  return empirical_with_mass(scene, scene.barrier.mass());
}

MethodResult run_analytical(const Scene& scene) {
  return analytical_with_mass(scene, scene.barrier.mass());
}

MethodResult run_literature(const Scene& scene) {
  const LiteratureParameters p = scene.methods.literature.value_or(LiteratureParameters{});
  const SceneLandslide& l = scene.landslide;
  const double vn = l.velocity_m_s * std::sin(face_angle(scene));
  MethodResult r;
  r.method = "literature";
  const double k = p.hydrostatic_k.value_or(nan), alpha = p.hydrodynamic_alpha.value_or(nan);
  if (p.family == "hydrostatic") {
    r.peak_force = hydrostatic_peak_force(k, l.density_kg_m3, l.thickness_m);
  } else if (p.family == "hydrodynamic") {
    r.peak_force = hydrodynamic_peak_force(alpha, l.density_kg_m3, vn, l.thickness_m);
  } else {
    r.peak_force = mixed_peak_force(alpha, k, l.density_kg_m3, vn, l.thickness_m);
  }
  if (!std::isfinite(r.peak_force))
    throw InputError("methods.literature: family \"" + p.family +
                     "\" needs hydrostatic_k and/or hydrodynamic_alpha");
  r.rise_time = r.impact_duration = r.final_displacement = nan;
  const FaceResolution face = resolve_face_force(face_angle(scene));
  r.scalars.peak_force_horizontal = r.peak_force * face.horizontal;
  r.scalars.hydrostatic_k = p.hydrostatic_k;
  r.scalars.hydrodynamic_alpha = p.hydrodynamic_alpha;
  return r;
}

std::vector<MethodResult> run_closed_form_methods(const Scene& scene,
                                                  const std::vector<std::string>& only) {
  auto wanted = [&](const std::string& m, bool in_scene) {
    if (only.empty()) return in_scene;
    return std::find(only.begin(), only.end(), m) != only.end();
  };
  std::vector<MethodResult> out;
  if (wanted("empirical", scene.methods.empirical.has_value())) out.push_back(run_empirical(scene));
  if (wanted("analytical", scene.methods.analytical.has_value()))
    out.push_back(run_analytical(scene));
  if (wanted("literature", scene.methods.literature.has_value())) {
    if (!scene.methods.literature)
      throw InputError(
          "--methods literature: the scene has no methods.literature block "
          "(it needs the family and its coefficients)");
    out.push_back(run_literature(scene));
  }
  for (const auto& r : out) require_computable(r, scene);
  return out;
}

std::vector<MassDesign> design_barrier_mass(const Scene& scene, double max_displacement_m,
                                            const std::vector<std::string>& only) {
  if (!(max_displacement_m > 0.0) || !std::isfinite(max_displacement_m))
    throw InputError("--max-displacement = " + std::to_string(max_displacement_m) +
                     ": must be a finite number > 0 (m)");
  if (scene.barrier.fixed)
    throw InputError(
        "barrier.fixed = true: a fixed barrier does not move; set it to false to "
        "size the mass of a free barrier");
  std::vector<MassDesign> out;
  for (const char* method : {"empirical", "analytical"}) {
    const bool in_scene = std::string(method) == "empirical" ? scene.methods.empirical.has_value()
                                                             : scene.methods.analytical.has_value();
    if (only.empty() ? !in_scene : std::find(only.begin(), only.end(), method) == only.end())
      continue;
    auto run = [&](double m) {
      return std::string(method) == "empirical" ? empirical_with_mass(scene, m)
                                                : analytical_with_mass(scene, m);
    };
    // The search needs only the final displacement: no histories, no stability check per mass.
    const bool empirical = std::string(method) == "empirical";
    const bool by_momentum =
        empirical ? momentum(scene.methods.empirical) : momentum(scene.methods.analytical);
    const ForcePulse empirical_pulse = empirical_impact_of(scene).pulse;  // independent of m2
    const double beta = face_angle(scene), mu_b = scene.barrier.base_friction;
    ForcePulse fixed_pulse = empirical_pulse;  // the momentum variant's, independent of m2
    if (by_momentum && !empirical) {
      const SceneLandslide& l = scene.landslide;
      const TwoBodyCoefficients c = two_body_coefficients(scene, true);
      fixed_pulse = momentum_two_body_pulse(
          l.mass_kg_per_m(), l.velocity_m_s, l.equivalent_length_m(), c.lambda, c.tau,
          resolve_face_force(beta, scene.barrier.face_friction).horizontal);
    }
    const auto found = minimum_barrier_mass(
        [&](double m) {
          if (by_momentum)
            return momentum_barrier(momentum_setup(scene, fixed_pulse, m)).final_displacement;
          const ForcePulse p = empirical ? empirical_pulse : two_body_impact_of(scene, m).pulse;
          return final_displacement_under(p, m, mu_b, beta);
        },
        max_displacement_m);
    MassDesign d;
    d.method = method;
    d.mass_kg_per_m = found.mass;
    d.displacement_m = found.displacement;
    using S = MassForDisplacement::Status;
    d.status = found.status == S::Found          ? "found"
               : found.status == S::AnyMassWorks ? "any mass works"
                                                 : "no mass up to 1e9 kg/m";
    if (found.status == S::Found && scene.barrier.density_kg_m3) {
      // Keep the top width and the face angle; choose the height; solve the base width.
      const double rho = *scene.barrier.density_kg_m3, b = scene.barrier.top_width_m;
      const MethodResult at_mass = run(found.mass);
      for (double f : {0.75, 1.0, 1.25, 1.5}) {
        Scene s = scene;
        s.barrier.height_m = f * scene.barrier.height_m;
        s.barrier.base_width_m = 2.0 * found.mass / (rho * s.barrier.height_m) - b;
        const BarrierGeometry g = geometry_of(s.barrier);
        if (!(g.downstream_run_out() >= -1e-9)) continue;  // face angle does not fit
        const StabilityCheck st = barrier_stability(
            at_mass.time.data(), at_mass.force.data(), static_cast<int>(at_mass.time.size()), g,
            by_momentum ? resolve_face_force(g.face_angle, s.barrier.face_friction)
                        : resolve_face_force(g.face_angle),
            found.mass, s.barrier.base_friction, 0.5 * s.landslide.thickness_m);
        d.geometries.push_back(
            {s.barrier.height_m, s.barrier.base_width_m, b, st.min_overturning_safety});
      }
    }
    out.push_back(d);
  }
  return out;
}

}  // namespace lsi
