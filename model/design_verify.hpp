// The design loop closed by the MPM: each closed form's minimum barrier mass for a tolerable
// displacement (design_barrier_mass) is given a barrier of the scene's kind and run through the
// MPM, whose displacement and safety under its own loads are set beside the tolerance.
#pragma once
#include <string>
#include <vector>

#include "model/closed_form_methods.hpp"
#include "model/method_result.hpp"
#include "model/scene.hpp"

namespace lsi {

struct DesignCheck {
  std::string method;          // the closed form whose design is checked
  double mass_kg_per_m = 0.0;  // its minimum mass
  SceneBarrier barrier;        // the barrier the MPM ran
  MethodResult mpm;            // the MPM's result for it
  bool within = false;         // the MPM's final displacement within the tolerance
  std::string skipped;         // why the MPM did not run (no trapezoid of the kind holds it)
};

// The barrier of `scene` with mass m (kg/m): the scene's height, top width and face angle with
// the base width that gives the mass at the scene's density (where the face would not fit, the
// nearest height that fits, from half to twice the scene's); by mass, the scene's geometry with
// that mass. Throws InputError when no such trapezoid exists.
SceneBarrier barrier_with_mass(const SceneBarrier& b, double m);

// Whether verify_designs checks design `d`: one found, by a method among `methods` (any when
// empty).
bool design_checked(const MassDesign& d, const std::vector<std::string>& methods);

// Runs the MPM (the scene's methods.mpm; InputError without it) on the designed barrier of each
// design found among `methods` (all found designs when empty), the runs side by side
// (model/concurrent_runs.hpp); the checks in the designs' order.
std::vector<DesignCheck> verify_designs(const Scene& scene, const std::vector<MassDesign>& designs,
                                        double max_displacement_m,
                                        const std::vector<std::string>& methods = {});

}  // namespace lsi
