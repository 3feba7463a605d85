// What a successfully parsed scene must satisfy (docs/reference/scene_schema.md): every number finite and
// inside its documented range, the derived quantities the methods use (lengths, areas, masses)
// finite and positive, and the MPM case built from it (model/mpm_impact.hpp, mpm_scene.hpp)
// free of non-finite values and small enough for the solver's int indices. A violation is a bug
// of the parser: it calls lsi::fuzz::bug (tests/fuzz/fuzz_target.hpp), which aborts.
#pragma once
#include "io/mpm_scene.hpp"
#include "model/scene.hpp"

namespace lsi::fuzz {

void check_scene(const Scene& scene);

enum class MpmCaseKind { Impact, Verification };
void check_mpm_case(const MpmCase& c, MpmCaseKind kind);

}  // namespace lsi::fuzz
