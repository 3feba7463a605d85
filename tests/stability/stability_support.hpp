// Shared pieces of the stability matrix (docs/vv/stability.md): scenes built from a base JSON with a
// merge patch, and the "no NaN / Inf anywhere" check of a MethodResult.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/method_result.hpp"
#include "model/scene.hpp"
#include "io/scene_parser.hpp"

namespace lsi::stability {

using nlohmann::json;

// RFC 7396 merge patch of `patch` (JSON text) into a copy of `base`; null removes a key.
inline json patched(json base, const std::string& patch) {
  if (!patch.empty()) base.merge_patch(json::parse(patch));
  return base;
}

inline Scene scene_of(const json& j) { return parse_scene(j); }

// scenes/former-reference/L3-B3.json (3 m at 12.5 m/s, 60 deg earth barrier, free) at h / 4, the
// landslide saturated (the default phases) or, with `"phases": "dry"` patched in, dry.
inline json fast_flow_on_earth_barrier_h4() {
  return json::parse(R"({
    "name": "L3-B3-h4",
    "landslide": {
      "thickness_m": 3.0, "velocity_m_s": 12.5, "density_kg_m3": 1800,
      "shape": {"kind": "front-body-tail", "body_squares": 4},
      "material": {"porosity": 0.5, "friction_angle_deg": 20, "cohesion_kpa": 0,
                   "young_modulus_mpa": 2, "poisson_ratio": 0.25,
                   "hydraulic_conductivity_m_s": 0.0001, "liquid_bulk_modulus_mpa": 30,
                   "liquid_viscosity_kpa_s": 1e-06}
    },
    "barrier": {"height_m": 5, "base_width_m": 6, "top_width_m": 2, "face_angle_deg": 60,
                "density_kg_m3": 2000, "base_friction": 0.5, "face_friction": 0.3,
                "fixed": false},
    "methods": {"mpm": {"cell_size_m": 0.75, "end_time_s": 5.86}}
  })");
}

// True when every value is finite.
inline bool all_finite(const std::vector<double>& v, size_t* first_bad = nullptr) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) {
      if (first_bad) *first_bad = i;
      return false;
    }
  return true;
}

// Which non-finite scalars a result may hold, each by design (documented in docs/theory/models.md and
// docs/reference/scene_schema.md), never NaN written as a number:
//  * final_displacement = +infinity: the barrier of a closed form never stops (no base
//    friction); NaN: an MPM run ended while the barrier still slid (end_state says so, and
//    displacement_at_end holds how far it got);
//  * barrier_stop_time = +infinity: it never stops (barrier_start_time / barrier_stop_time are
//    not given, empty, where the barrier does not move);
//  * min_overturning_safety / min_sliding_safety = +infinity: no overturning moment / no
//    push at any instant.
struct NonFiniteAllowed {
  bool infinite_final_displacement = false;
};

// Checks every history, series and scalar of `r` (gtest failures name the field).
inline void expect_no_nan(const MethodResult& r, const std::string& where,
                          NonFiniteAllowed allowed = {}) {
  for (const HistoryField& field : history_fields()) {
    const char* name = field.name;
    const std::vector<double>* h = &(r.*(field.member));
    size_t bad = 0;
    EXPECT_TRUE(all_finite(*h, &bad)) << where << ": " << name << "[" << bad << "] = " << (*h)[bad];
    if (!h->empty()) {
      EXPECT_EQ(h->size(), r.time.size()) << where << ": " << name;
    }
  }
  for (const auto& [name, s] : r.series) {
    size_t bad = 0;
    EXPECT_TRUE(all_finite(s.values, &bad))
        << where << ": series " << name << "[" << bad << "] = " << s.values[bad];
    EXPECT_EQ(s.values.size(), r.time.size()) << where << ": series " << name;
  }
  EXPECT_TRUE(std::isfinite(r.peak_force)) << where << ": peak_force = " << r.peak_force;
  EXPECT_TRUE(std::isfinite(r.rise_time)) << where << ": rise_time = " << r.rise_time;
  EXPECT_TRUE(std::isfinite(r.impact_duration))
      << where << ": impact_duration = " << r.impact_duration;
  if (allowed.infinite_final_displacement) {
    if (has_final_displacement(r.end_state))
      EXPECT_FALSE(std::isnan(r.final_displacement)) << where << ": final_displacement is NaN";
    else
      EXPECT_TRUE(std::isnan(r.final_displacement))
          << where << ": a run cut short while the barrier slid has no final displacement, got "
          << r.final_displacement;
    EXPECT_FALSE(r.final_displacement < 0.0)
        << where << ": final_displacement = " << r.final_displacement;
  } else {
    EXPECT_TRUE(std::isfinite(r.final_displacement))
        << where << ": final_displacement = " << r.final_displacement;
  }
  // The start and stop times are given together, and not given only where the barrier of a
  // closed form does not move.
  EXPECT_EQ(r.scalars.barrier_start_time.has_value(), r.scalars.barrier_stop_time.has_value())
      << where;
  if (!r.barrier_model.empty() && !r.scalars.barrier_start_time) {
    EXPECT_EQ(r.final_displacement, 0.0) << where << ": no start time but the barrier moved";
  }
  for (const auto& [name, v] : named_scalars(r)) {
    if (name == "barrier_stop_time" && std::isinf(v)) {
      EXPECT_TRUE(std::isinf(r.final_displacement))
          << where << ": stops never, displacement finite";
      continue;
    }
    if ((name == "min_overturning_safety" || name == "min_sliding_safety") && v == INFINITY)
      continue;
    EXPECT_TRUE(std::isfinite(v)) << where << ": " << name << " = " << v;
  }
}

}  // namespace lsi::stability
