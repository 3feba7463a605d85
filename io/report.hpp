// Human (table) and machine (JSON) summaries of method results, SI units in JSON.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/closed_form_methods.hpp"
#include "model/design_verify.hpp"
#include "model/method_result.hpp"
#include "model/scene.hpp"

namespace lsi {

// {"empirical": {"peak_force": N/m, "rise_time": s, "impact_duration": s,
//                "final_displacement": m or null if the barrier never stops (a closed form
//                without base friction); left out where not known (an MPM run cut short: its
//                "end_state" says why)}, ...}
nlohmann::json summary_json(const std::vector<MethodResult>& results);
std::string summary_table(const Scene& scene, const std::vector<MethodResult>& results);

// With `checks` (design_verify.hpp): the MPM's displacement and safety for each checked design.
nlohmann::json design_json(const std::vector<MassDesign>& designs, double max_displacement_m,
                           const std::vector<DesignCheck>& checks = {});
std::string design_table(const Scene& scene, const std::vector<MassDesign>& designs,
                         double max_displacement_m, const std::vector<DesignCheck>& checks = {});

// One row per scene: peak force, impact duration, final displacement per method, and the mass
// that limits the displacement to `max_displacement_m` (the paper's Tables 4 and 6).
struct ComparisonRow {
  std::string scene;
  std::vector<MethodResult> results;
  std::vector<MassDesign> designs;
  std::vector<DesignCheck> checks;  // the MPM on designed barriers (compare --verify-design)
};
std::string comparison_table(const std::vector<ComparisonRow>& rows, double max_displacement_m);
nlohmann::json comparison_json(const std::vector<ComparisonRow>& rows, double max_displacement_m);

}  // namespace lsi
