// `--set /json/pointer=value` (io/scene_overrides.hpp), and the scene parser's ranges against the
// one table the sweep kernel checks samples with (sweeps/sampled_scene.hpp, scene_field_range).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/json_fields.hpp"
#include "io/scene_overrides.hpp"
#include "io/scene_parser.hpp"
#include "model/input_error.hpp"
#include "sweeps/sampled_scene.hpp"

namespace {

using nlohmann::json;

json base_scene() {
  return json::parse(R"({
    "name": "s",
    "landslide": { "thickness_m": 2.0, "velocity_m_s": 6, "density_kg_m3": 1800,
                   "shape": {"kind": "front-body-tail", "body_squares": 6},
                   "material": {} },
    "barrier": { "height_m": 4, "base_width_m": 4.0, "top_width_m": 1.0, "face_angle_deg": 80,
                 "density_kg_m3": 2400 },
    "methods": { "empirical": {}, "analytical": {}, "list": [1, 2] }
  })");
}

std::string error_of(json doc, const std::vector<std::string>& sets) {
  try {
    lsi::apply_overrides(doc, sets);
  } catch (const lsi::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneOverrides, SetNumbersStringsObjectsAndArrayElementsInOrder) {
  json doc = base_scene();
  lsi::apply_overrides(
      doc, {"/landslide/velocity_m_s=8", "/name=my name", "/name=\"quoted\"", "/barrier/fixed=true",
            "/landslide/shape={\"kind\": \"rectangle\"}", "/methods/list/1=5", "/methods/list/-=7",
            "/landslide/velocity_m_s=9.5"});
  EXPECT_EQ(doc["landslide"]["velocity_m_s"], 9.5);  // the later override wins
  EXPECT_EQ(doc["name"], "quoted");                  // JSON string; "my name" was not JSON
  EXPECT_EQ(doc["barrier"]["fixed"], true);
  EXPECT_EQ(doc["landslide"]["shape"], json({{"kind", "rectangle"}}));
  EXPECT_EQ(doc["methods"]["list"], json({1, 5, 7}));
  json plain = base_scene();
  lsi::apply_overrides(plain, {"/name=not json"});
  EXPECT_EQ(plain["name"], "not json");
}

TEST(SceneOverrides, MalformedOrMisplacedOverridesNameThemselves) {
  const json doc = base_scene();
  struct Case {
    std::string set, expect;
  } cases[] = {
      {"velocity=8", "--set 'velocity=8': must be /json/pointer=value"},
      {"/landslide/velocity_m_s", "must be /json/pointer=value"},
      {"=8", "must be /json/pointer=value"},
      {"/nothing/here=1", "--set '/nothing/here=1': /nothing is not in the scene"},
      {"/methods/list/5=1", "/methods/list has 2 elements (index 5"},
      {"/methods/list/x=1", "/methods/list has 2 elements (index x"},
      {"/methods/list/99999999999999999999=1", "has 2 elements"},
      {"/name/x=1", "/name is a string, not an object or array"},
      {"/a~2=1", "is not a JSON pointer"},
  };
  for (const Case& c : cases) {
    const std::string m = error_of(doc, {c.set});
    EXPECT_NE(m.find(c.expect), std::string::npos) << c.set << ": " << m;
  }
}

// Every numeric scene key a study may sample is accepted by the parser exactly where the sweep
// kernel's table admits it: a value outside is refused with the key's range message, one inside is
// not refused for its range (another check, e.g. the face in the base, may still refuse it).
TEST(SceneFieldRanges, TheParserRefusesExactlyTheValuesOutsideTheTable) {
  using namespace lsi::sweeps;
  const double candidates[] = {-1.0, -1e-300, 0.0, 1e-300, 1e-3, 0.3,  0.5, 0.9999,  1.0,  2.5,
                               5.0,  5.5,     45,  89.99,  90.0, 90.5, 1e6, 1e6 + 1, 1e300};
  for (int f = 0; f < scene_field_count; ++f) {
    if (f == top_width_m) continue;  // its upper bound is the base width: a check of its own
    const std::string pointer = scene_field_pointer[f];
    const std::string key = pointer.substr(pointer.rfind('/') + 1);
    for (const double v : candidates) {
      json doc = base_scene();
      doc["methods"].erase("list");  // the overrides' array, not a scene key
      if (f == length_m) doc["landslide"]["shape"] = {{"kind", "rectangle"}, {"length_m", 10}};
      if (f == barrier_mass_kg_per_m) doc["barrier"].erase("density_kg_m3");
      doc[json::json_pointer(pointer)] = v;
      std::string message;
      try {
        lsi::parse_scene(doc);
      } catch (const lsi::InputError& e) {
        message = e.what();
      }
      const std::string refusal = key + " = " + lsi::format_value(json(v)) + ": must be";
      const bool refused_for_range = message.find(refusal) != std::string::npos;
      EXPECT_EQ(refused_for_range, !in_range(v, scene_field_range(f)))
          << pointer << " = " << v << ": " << (message.empty() ? "accepted" : message);
    }
  }
}

}  // namespace
