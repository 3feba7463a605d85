// A study: a base scene, the uncertain or swept inputs with their distributions, the sampling
// design and what to run and keep, as read from a study file (io/study_parser.hpp). The schema
// is documented with the scene's, in docs/reference/scene_schema.md ("Study files"); `lsi sweep` runs it
// (app/sweep_runner.hpp).
#pragma once
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.hpp"
#include "sweeps/distribution.hpp"
#include "sweeps/sampled_scene.hpp"
#include "sweeps/sampler.hpp"

namespace lsi {

struct StudyInput {
  std::string path;  // JSON pointer into the scene, e.g. /landslide/thickness_m
  int field = -1;    // sweeps::SceneField, or -1 for an MPM-only key (/methods/mpm/...)
  sweeps::DistributionSpec distribution;  // unused by the Points design
};

// The Points design's samples: the rows of a points file, as given.
struct StudyPoints {
  std::string file;           // the file read (absolute path)
  std::vector<double> value;  // samples x inputs, row-major, in the order of Study::inputs
};

// P(output > above) is estimated for each method that gives the output (or only `method`).
struct StudyThreshold {
  std::string method;  // empty: every method of the study
  std::string output;  // peak_force, rise_time, impact_duration, final_displacement
  double above = 0.0;
};

// When to stop before all samples are done. Both rules are checked after each finished chunk.
struct StudyStop {
  double wall_time_s = std::numeric_limits<double>::infinity();
  // Confidence-interval rule: stop once the interval of `statistic` of method/output is narrow
  // enough: for "mean", half-width <= relative_half_width * |mean|; for "exceedance",
  // half-width <= half_width (an absolute probability).
  bool has_interval_rule = false;
  std::string method, output, statistic;  // statistic: "mean" or "exceedance"
  double threshold = 0.0;                 // exceedance: P(output > threshold)
  double relative_half_width = 0.0, half_width = 0.0;
  std::uint64_t min_samples = 1000;  // never stop on the interval before this many
};

// Study key `mpm_at_quantiles`: run the MPM on the samples at these quantiles of method/output.
struct StudyQuantileMpm {
  std::string method, output;
  std::vector<double> quantiles;  // each in (0, 1)
};

struct Study {
  std::string name;
  std::string path;                 // the study file ("" if not read from a file)
  nlohmann::json scene_document;    // the base scene as JSON
  Scene base;                       // ... parsed
  sweeps::SceneValues base_values;  // ... as the closed-form sweep kernel sees it
  std::vector<StudyInput> inputs;
  std::vector<std::vector<double>> correlation;  // empty, or inputs x inputs
  sweeps::Design design = sweeps::Design::MonteCarlo;
  std::uint64_t seed = 0;
  std::uint64_t samples = 0;
  std::vector<std::string> methods;  // out of empirical, analytical, mpm (in this order)
  std::vector<std::string> outputs;  // out of peak_force, rise_time, impact_duration,
                                     // final_displacement (in this order)
  std::vector<StudyThreshold> thresholds;
  double confidence = 0.95;
  StudyStop stop;
  std::optional<StudyQuantileMpm> mpm_at_quantiles;
  StudyPoints points;               // the Points design only
  std::uint64_t chunk_samples = 0;  // samples per chunk (the unit of work and of resume)
  nlohmann::json source;            // the study with its scene inlined (stored in results)
  std::string fingerprint;          // hash of `source`: results of other studies are refused

  bool runs(const std::string& method) const;
  // The study's sampler: counter-based, sample i's inputs depend on i alone (every sampler of
  // the study draws the same; the Points design reads row i). Throws std::invalid_argument as
  // sweeps::Sampler does.
  template <class MemorySpace>
  sweeps::Sampler<MemorySpace> sampler() const {
    if (design == sweeps::Design::Points)
      return sweeps::Sampler<MemorySpace>(points.value, static_cast<int>(inputs.size()), samples);
    std::vector<sweeps::DistributionSpec> specs;
    for (const auto& in : inputs) specs.push_back(in.distribution);
    return sweeps::Sampler<MemorySpace>(specs, correlation, design, seed, samples);
  }
  // Result columns: "<method>/<output>" for every method and output kept.
  std::vector<std::string> output_columns() const;
};

}  // namespace lsi
