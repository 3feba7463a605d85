// Runs the closed-form design methods on a scene: time histories and summaries (MethodResult).
// Empirical-only or analytical-only work never starts Kokkos or allocates a grid.
#pragma once
#include <vector>

#include "model/method_result.hpp"
#include "model/scene.hpp"

namespace lsi {

// Number of uniform samples of each time history (breakpoints T1, T2, t*, stop are added).
inline constexpr int history_samples = 1001;

MethodResult run_empirical(const Scene& scene);
MethodResult run_analytical(const Scene& scene);
// Peak force only (no time history): rise_time, impact_duration and final_displacement are NaN,
// meaning "not given by this method", and are neither printed nor stored.
MethodResult run_literature(const Scene& scene);

// The flow's base friction as the momentum-consistent closed forms take it, F1 / m1 (m/s^2):
// landslide.base_friction g on the grains' share of the weight (saturated unless the scene's MPM
// runs it dry; sweeps/sampled_scene.hpp, flow_friction_deceleration).
double flow_friction_deceleration(const Scene& scene);

// Runs the methods the scene selects (or `only`, if non-empty), in the order empirical,
// analytical, literature. Throws InputError for a requested method the scene cannot run.
std::vector<MethodResult> run_closed_form_methods(const Scene& scene,
                                                  const std::vector<std::string>& only = {});

// Inverse design (paper section 4.3): minimum barrier mass per metre for a tolerable final
// displacement, by each displacement-giving method, with trapezoid geometries providing it.
struct GeometryOption {
  double height_m, base_width_m, top_width_m;
  double min_overturning_safety;  // under that method's force history
};
struct MassDesign {
  std::string method;
  std::string status;  // "found", "any mass works", "no mass up to 1e9 kg/m"
  double mass_kg_per_m = 0.0;
  double displacement_m = 0.0;
  std::vector<GeometryOption> geometries;  // only when the barrier density is known
};
std::vector<MassDesign> design_barrier_mass(const Scene& scene, double max_displacement_m,
                                            const std::vector<std::string>& only = {});

}  // namespace lsi
