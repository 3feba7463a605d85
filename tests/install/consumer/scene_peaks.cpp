// A scene file run through an installed lsi's driver: parsed by lsi::io, its closed-form methods
// and its MPM run by lsi::model. Prints one line per method: its name and its peak force (N/m).
//   usage: scene_peaks SCENE.json
#include <cstdio>
#include <exception>
#include <vector>

#include "io/scene_parser.hpp"
#include "model/closed_form_methods.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENE.json\n", argv[0]);
    return 2;
  }
  try {
    const lsi::Scene scene = lsi::load_scene(argv[1]);
    std::vector<lsi::MethodResult> results = lsi::run_closed_form_methods(scene);
    if (scene.methods.mpm) results.push_back(lsi::run_mpm_case(lsi::impact_case(scene)).result);
    for (const auto& r : results) std::printf("%s %.17g\n", r.method.c_str(), r.peak_force);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
