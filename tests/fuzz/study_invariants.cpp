#include "study_invariants.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/json_fields.hpp"
#include "fuzz_target.hpp"
#include "scene_invariants.hpp"
#include "io/study_parser.hpp"

namespace lsi::fuzz {
namespace {

constexpr double kMaxSamples = 9.0e15;
const std::vector<std::string> kMethods = {"empirical", "analytical", "mpm"};
const std::vector<std::string> kOutputs = {"peak_force", "rise_time", "impact_duration",
                                           "final_displacement"};

bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

// A non-empty list without repeats, out of `allowed` and in its order.
void check_subset(const std::vector<std::string>& list, const std::vector<std::string>& allowed,
                  const std::string& what) {
  require(!list.empty(), what + ": empty");
  std::size_t next = 0;
  for (const auto& s : list) {
    const auto it =
        std::find(allowed.begin() + static_cast<std::ptrdiff_t>(next), allowed.end(), s);
    require(it != allowed.end(), what + ": \"" + s + "\" not allowed, repeated or out of order");
    next = static_cast<std::size_t>(it - allowed.begin()) + 1;
  }
}

void check_input(const StudyInput& in, const Study& s) {
  const std::string at = "input " + in.path;
  if (in.field >= 0) {
    require(
        in.field < sweeps::scene_field_count && in.path == sweeps::scene_field_pointer[in.field],
        at + ": field does not match the path");
  } else {
    require(in.field == -1 && in.path.rfind("/methods/mpm/", 0) == 0,
            at + ": not a sampleable path");
    require(s.base.methods.mpm.has_value() && s.runs("mpm"), at + ": an MPM key without the MPM");
  }
  if (s.design == sweeps::Design::Points) return;  // given points: no distribution
  const sweeps::DistributionSpec& d = in.distribution;
  try {
    sweeps::validate(d);
  } catch (const std::invalid_argument& e) {
    bug(at + ": an invalid distribution was accepted: " + e.what());
  }
  for (double v : {d.value, d.min, d.max, d.mean, d.sd})
    require(std::isfinite(v), at + ": a non-finite distribution parameter");
  for (double v : d.values) require(std::isfinite(v), at + ": a non-finite value");
  for (double w : d.weights) require(std::isfinite(w) && w > 0, at + ": a weight not > 0");
}

void check_correlation(const Study& s) {
  if (s.correlation.empty()) return;
  const std::size_t n = s.inputs.size();
  require(s.correlation.size() == n, "correlation: not inputs x inputs");
  for (std::size_t i = 0; i < n; ++i) {
    require(s.correlation[i].size() == n, "correlation: not inputs x inputs");
    for (std::size_t j = 0; j < n; ++j) {
      const double r = s.correlation[i][j];
      require(i == j ? r == 1.0 : (r > -1.0 && r < 1.0 && r == s.correlation[j][i]),
              "correlation[" + std::to_string(i) + "][" + std::to_string(j) +
                  "] = " + json_fields::format_number(r));
    }
  }
  require(s.design != sweeps::Design::Grid, "a correlation with the grid design");
}

void check_rules(const Study& s) {
  for (const auto& t : s.thresholds) {
    require(t.method.empty() || s.runs(t.method), "threshold on a method not run: " + t.method);
    require(contains(s.outputs, t.output), "threshold on an output not kept: " + t.output);
    require(std::isfinite(t.above), "threshold above is not finite");
  }
  const StudyStop& stop = s.stop;
  require(stop.wall_time_s > 0 && !std::isnan(stop.wall_time_s), "stop.wall_time_s not > 0");
  if (stop.has_interval_rule) {
    require(s.runs(stop.method) && contains(s.outputs, stop.output),
            "stop.interval on what is not run");
    require(stop.min_samples >= 1 && stop.min_samples <= kMaxSamples, "stop.interval.min_samples");
    if (stop.statistic == "mean") {
      require(stop.relative_half_width > 0 && stop.relative_half_width < 1,
              "stop.interval.relative_half_width not in (0, 1)");
    } else {
      require(stop.statistic == "exceedance", "stop.interval.statistic " + stop.statistic);
      require(std::isfinite(stop.threshold), "stop.interval.threshold not finite");
      require(stop.half_width > 0 && stop.half_width <= 0.5,
              "stop.interval.half_width not in (0, 0.5]");
    }
  }
  if (s.mpm_at_quantiles) {
    const StudyQuantileMpm& q = *s.mpm_at_quantiles;
    require(s.base.methods.mpm.has_value(), "mpm_at_quantiles without methods.mpm");
    require(q.method != "mpm" && s.runs(q.method) && contains(s.outputs, q.output),
            "mpm_at_quantiles on what is not run");
    require(!q.quantiles.empty(), "mpm_at_quantiles without quantiles");
    for (double p : q.quantiles) require(p > 0 && p < 1, "a quantile not in (0, 1)");
  }
}

// What `lsi sweep` does with each sample: draw it, write it into the scene, parse that scene
// (an invalid sample is recorded with the parser's message, not an error of the study). Given
// points were each checked by the parser: every one must be a valid scene.
void check_first_samples(const Study& s) {
  const sweeps::Sampler<Kokkos::HostSpace> sampler = s.sampler<Kokkos::HostSpace>();
  std::vector<double> x(s.inputs.size());
  const std::uint64_t n = std::min<std::uint64_t>(s.samples, 2);
  for (std::uint64_t i = 0; i < n; ++i) {
    sampler.sample(i, x.data());
    const std::string reason = invalid_sample_reason(s, x.data());
    require(reason.find('\n') == std::string::npos, "an invalid sample's reason is not one line");
    require(s.design != sweeps::Design::Points || reason.empty(),
            "a given point that is not a valid scene was accepted: " + reason);
  }
  if (s.design == sweeps::Design::Points)
    require(s.points.value.size() == s.samples * s.inputs.size(),
            "given points of another size than samples x inputs");
}

}  // namespace

void check_study(const Study& s) {
  require(!s.name.empty(), "a study with an empty name");
  require(s.scene_document.is_object(), "a study whose scene is not an object");
  check_scene(s.base);
  require(!s.inputs.empty() && s.inputs.size() <= 32,
          "a study with " + std::to_string(s.inputs.size()) + " inputs");
  for (std::size_t k = 0; k < s.inputs.size(); ++k) {
    check_input(s.inputs[k], s);
    for (std::size_t j = 0; j < k; ++j)
      require(s.inputs[j].path != s.inputs[k].path, "an input sampled twice");
  }
  check_correlation(s);
  check_subset(s.methods, kMethods, "methods");
  check_subset(s.outputs, kOutputs, "outputs");
  if (s.runs("mpm")) require(s.base.methods.mpm.has_value(), "the MPM without methods.mpm");
  require(s.samples >= 1 && s.samples <= kMaxSamples, "samples = " + std::to_string(s.samples));
  require(s.seed <= kMaxSamples, "seed = " + std::to_string(s.seed));
  require(s.chunk_samples >= 1 && s.chunk_samples <= (1u << 24),
          "chunk_samples = " + std::to_string(s.chunk_samples));
  require(s.confidence > 0.5 && s.confidence < 1,
          "confidence = " + json_fields::format_number(s.confidence));
  if (s.design == sweeps::Design::Grid) {
    double product = 1;
    for (const auto& in : s.inputs) {
      require(in.distribution.kind == sweeps::DistributionKind::Discrete &&
                  in.distribution.weights.empty(),
              "a grid design input that is not a plain list of points");
      product *= static_cast<double>(in.distribution.values.size());
    }
    require(product == static_cast<double>(s.samples), "grid samples differ from the grid's size");
  }
  check_rules(s);
  require(!s.fingerprint.empty() && s.source.is_object(), "a study without source or fingerprint");
  check_first_samples(s);
}

}  // namespace lsi::fuzz
