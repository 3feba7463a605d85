// The error bars of MPM outputs from a convergence study: the file that ci/reference_convergence.py
// writes (ci/reference_convergence.json). For every case it holds the scene's landslide,
// barrier and MPM settings at the base resolution and, per output, the value there, its spread
// (the larger change to a finer cell or a smaller Courant number) and whether it converged.
// `lsi compare --convergence FILE` attaches them to the MPM results of the scenes they belong to.
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/method_result.hpp"
#include "io/mpm_scene.hpp"
#include "model/scene.hpp"

namespace lsi {

struct OutputSpread {
  double value = 0.0;   // at the base resolution (SI)
  double spread = 0.0;  // the error bar (SI, >= 0)
  bool converged = false;
};

struct CaseConvergence {
  nlohmann::json landslide, barrier;  // the scene's blocks as the study ran them
  MpmSettings mpm;                    // the base resolution's settings
  std::map<std::string, OutputSpread> outputs;
};

struct ConvergenceStudy {
  std::string source;   // the file
  std::string command;  // how it was made
  int base_cells = 0, finer_cells = 0;
  double base_courant = 0.0, finer_courant = 0.0;
  std::map<std::string, CaseConvergence> cases;
};

// The outputs a convergence study may give, in table order: the MethodResult scalars and extras
// of an MPM impact.
const std::vector<std::string>& convergence_outputs();

// Reads and checks the file; throws InputError naming the field, the value and what is allowed.
ConvergenceStudy load_convergence_study(const std::string& path);

// Attaches the case's error bars to the scene's MPM result when the study ran this scene (same
// name, landslide, barrier and MPM settings) and its base values are what this run gave (within
// kConvergenceStaleRelative: else the study is stale, run by other code): extras
// `<output>_spread` (SI) and `<output>_converged` (1 or 0) per output. Returns "" when attached,
// else why not (for a message).
inline constexpr double kConvergenceStaleRelative = 0.02;
std::string attach_convergence(const ConvergenceStudy& study, const Scene& scene,
                               MethodResult& mpm);

}  // namespace lsi
