#include "model/design_verify.hpp"

#include <algorithm>
#include <cmath>

#include "model/concurrent_runs.hpp"
#include "model/mpm_footprint.hpp"
#include "model/input_error.hpp"
#include "model/messages.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "kernels/common/math.hpp"

namespace lsi {

SceneBarrier barrier_with_mass(const SceneBarrier& b, double m) {
  SceneBarrier out = b;
  if (b.mass_kg_per_m) {
    out.mass_kg_per_m = m;
    return out;
  }
  const double rho = *b.density_kg_m3, beta = math::degrees_to_radians(b.face_angle_deg);
  for (double f : {1.0, 0.9, 1.1, 0.8, 1.25, 0.7, 1.5, 0.6, 1.75, 0.5, 2.0}) {
    out.height_m = f * b.height_m;
    out.base_width_m = 2.0 * m / (rho * out.height_m) - b.top_width_m;
    const double run = b.face_angle_deg == 90.0 ? 0.0 : out.height_m / std::tan(beta);
    if (out.base_width_m >= b.top_width_m && run <= out.base_width_m - b.top_width_m + 1e-9)
      return out;
  }
  throw InputError("barrier: no trapezoid of face angle " + format_number(b.face_angle_deg) +
                   " deg and top width " + format_number(b.top_width_m) +
                   " m holds the designed mass " + std::to_string(std::llround(m)) +
                   " kg/m at a height of 0.5 to 2 times " + format_number(b.height_m) + " m");
}

bool design_checked(const MassDesign& d, const std::vector<std::string>& methods) {
  return d.status == "found" &&
         (methods.empty() || std::find(methods.begin(), methods.end(), d.method) != methods.end());
}

std::vector<DesignCheck> verify_designs(const Scene& scene, const std::vector<MassDesign>& designs,
                                        double max_displacement_m,
                                        const std::vector<std::string>& methods) {
  if (!scene.methods.mpm)
    throw InputError(
        "methods.mpm: missing: checking a design runs the MPM (docs/reference/scene_schema.md)");
  std::vector<DesignCheck> out;
  std::vector<std::size_t> to_run;  // the checks whose barrier exists: their MPM runs
  for (const MassDesign& d : designs) {
    if (!design_checked(d, methods)) continue;
    DesignCheck c;
    c.method = d.method;
    c.mass_kg_per_m = d.mass_kg_per_m;
    try {
      c.barrier = barrier_with_mass(scene.barrier, d.mass_kg_per_m);
      to_run.push_back(out.size());
    } catch (const InputError& e) {
      c.skipped = e.what();
    }
    out.push_back(std::move(c));
  }
  // The runs side by side (model/concurrent_runs.hpp), as many as fit in the memory.
  const int runs = campaign_runs_that_fit(to_run.size(), {&scene});
  run_concurrently(
      to_run.size(),
      [&](std::size_t k) {
        DesignCheck& c = out[to_run[k]];
        Scene s = scene;
        s.barrier = c.barrier;
        s.name = scene.name + "-" + c.method + "-design";
        MpmOutcome o = run_mpm_case(impact_case(s));
        c.mpm = std::move(o.result);
        c.within = has_final_displacement(c.mpm.end_state) &&
                   c.mpm.final_displacement <= max_displacement_m;
      },
      runs, "the MPM on the designed barriers");
  return out;
}

}  // namespace lsi
