// Fuzz target: the scene parser, as `lsi run SCENE.json` reaches it (app/main.cpp).
//
//   bytes -> json_fields::parse_json_document (malformed JSON, overflow, duplicate keys)
//         -> an MPM verification scene (`mpm_case`): parse_mpm_case
//            otherwise: parse_scene, and for a scene with `methods.mpm` the MPM impact case
//            builder impact_case (it only computes the domain, materials and bodies; no grid is
//            allocated and no MPM step runs)
//
// Every rejection must be an lsi::InputError with a one-line message; what is accepted must
// satisfy tests/fuzz/scene_invariants.hpp, and its stored source must read back to the same
// scene (the HDF5 results keep it as text).
#include <string>

#include "io/json_fields.hpp"
#include "model/mpm_impact.hpp"
#include "io/mpm_scene.hpp"
#include "model/scene.hpp"
#include "fuzz_target.hpp"
#include "scene_invariants.hpp"
#include "io/scene_parser.hpp"

namespace {

using lsi::fuzz::require;

// The source of an accepted scene, written and read back, parses to the same values.
void check_round_trip(const lsi::Scene& scene) {
  const std::string text = scene.source.dump(2);
  lsi::Scene again;
  try {
    again = lsi::parse_scene(lsi::json_fields::parse_json_document(text, "round trip"));
  } catch (const lsi::InputError& e) {
    lsi::fuzz::bug(std::string("an accepted scene, written and read back, is rejected: ") +
                   e.what());
  }
  require(again.source == scene.source, "the scene's source does not read back to itself");
  require(again.landslide.thickness_m == scene.landslide.thickness_m &&
              again.landslide.mass_kg_per_m() == scene.landslide.mass_kg_per_m() &&
              again.barrier.mass() == scene.barrier.mass(),
          "the scene read back from its source has other values");
}

void parse_scene_bytes(const std::string& text) {
  const nlohmann::json doc = lsi::json_fields::parse_json_document(text, "fuzz-input");
  if (lsi::is_mpm_case(doc)) {
    lsi::fuzz::check_mpm_case(lsi::parse_mpm_case(doc), lsi::fuzz::MpmCaseKind::Verification);
    return;
  }
  const lsi::Scene scene = lsi::parse_scene(doc);
  lsi::fuzz::check_scene(scene);
  check_round_trip(scene);
  if (scene.methods.mpm)
    lsi::fuzz::check_mpm_case(lsi::impact_case(scene), lsi::fuzz::MpmCaseKind::Impact);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = lsi::fuzz::as_text(data, size);
  lsi::fuzz::expect_only_input_errors("scene", [&] { parse_scene_bytes(text); });
  return 0;
}
