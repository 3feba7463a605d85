// Study-file parser; the schema is documented in docs/reference/scene_schema.md ("Study files").
#include "io/study_parser.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string_view>

#include "io/json_fields.hpp"
#include "io/points_file.hpp"
#include "io/scene_parser.hpp"
#include "io/scene_reference.hpp"
#include "io/study_points.hpp"
#include "model/mpm_runner.hpp"  // ensure_kokkos

namespace lsi {
namespace {

using nlohmann::json;
using namespace json_fields;

const std::vector<std::string> kStudyKeys = {
    "name",       "scene", "inputs",        "correlation",      "design",
    "samples",    "seed",  "methods",       "outputs",          "thresholds",
    "confidence", "stop",  "chunk_samples", "mpm_at_quantiles", "points"};
const std::vector<std::string> kDesigns = {"monte-carlo", "latin-hypercube", "sobol", "grid",
                                           "points"};
const std::vector<std::string> kDistributions = {
    "constant", "uniform", "normal", "lognormal", "truncated-normal", "discrete", "grid"};
const std::vector<std::string> kSweepMethods = {"empirical", "analytical", "mpm"};
const std::vector<std::string> kOutputs = {"peak_force", "rise_time", "impact_duration",
                                           "final_displacement"};
// Largest sample count: indices stay exact in a double and in HDF5's unsigned 64-bit columns.
constexpr double kMaxSamples = 9.0e15;
constexpr double kMaxChunk = 1 << 24;

// Which method needs a scene field: closed forms read the geometry and the landslide's bulk
// values, only the MPM reads the material and the face friction (and the closed forms with the
// momentum-consistent barrier, below).
bool only_mpm_reads(int field) {
  using namespace sweeps;
  return (field >= porosity && field <= liquid_viscosity_kpa_s) || field == face_friction;
}
std::string method_reading(int field) {
  using namespace sweeps;
  if (field < 0 || only_mpm_reads(field)) return "mpm";
  if (field >= empirical_a1 && field <= empirical_kappa) return "empirical";
  if (field >= analytical_lambda) return "analytical";
  return "";  // every method
}

// FNV-1a, 64 bit, of `bytes`, continuing from `h`.
std::uint64_t fingerprint_hash(std::string_view bytes, std::uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}
std::string hex_of(std::uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<std::string> string_list(const ObjectReader& r, const std::string& key,
                                     const std::vector<std::string>& allowed) {
  const json& v = *r.find(key);
  if (!v.is_array() || v.empty())
    r.fail_at(key, "must be a non-empty array of strings out of " + join(allowed, true));
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string path = r.path_of(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_string() ||
        std::find(allowed.begin(), allowed.end(), v[i].get<std::string>()) == allowed.end())
      fail(path + " = " + format_value(v[i]) + ": allowed: " + join(allowed, true));
    if (std::find(out.begin(), out.end(), v[i].get<std::string>()) != out.end())
      fail(path + " = " + format_value(v[i]) + ": listed twice");
    out.push_back(v[i].get<std::string>());
  }
  // Canonical order (the order of `allowed`): columns do not depend on how the user listed them.
  std::vector<std::string> ordered;
  for (const auto& a : allowed)
    if (std::find(out.begin(), out.end(), a) != out.end()) ordered.push_back(a);
  return ordered;
}

std::vector<double> number_list(const ObjectReader& r, const std::string& key, const Range& range) {
  const json* found = r.find(key);
  if (!found) r.fail_missing(key, "non-empty array of numbers");
  const json& v = *found;
  if (!v.is_array() || v.empty()) r.fail_at(key, "must be a non-empty array of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i)
    out.push_back(check_number(v[i], r.path_of(key) + "[" + std::to_string(i) + "]", range));
  return out;
}

// The scene field `path` sets (sweeps::SceneField, or -1 for one key of methods.mpm) into
// `field`; returns why a study cannot sample the path, or "" if it can.
std::string unsampleable_path(const std::string& path, int& field) {
  field = -1;
  for (int f = 0; f < sweeps::scene_field_count; ++f)
    if (path == sweeps::scene_field_pointer[f]) field = f;
  // An MPM setting is one key of methods.mpm: "/methods/mpm/KEY", KEY a plain name (letters,
  // digits, '_'). Deeper or escaped pointers ("/methods/mpm/a/0", "/methods/mpm/a~2") name no
  // setting, and some are not even valid JSON pointers (nlohmann::json would throw writing a
  // sample's value there).
  const std::string mpm_prefix = "/methods/mpm/";
  const bool mpm_key =
      path.rfind(mpm_prefix, 0) == 0 && path.size() > mpm_prefix.size() &&
      std::all_of(path.begin() + static_cast<std::ptrdiff_t>(mpm_prefix.size()), path.end(),
                  [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  if (field >= 0 || mpm_key) return "";
  std::string allowed;
  for (const char* p : sweeps::scene_field_pointer) allowed += std::string(p) + ", ";
  return "not a numeric scene key a study can sample (allowed: " + allowed +
         "or /methods/mpm/KEY, one key of the MPM settings)";
}

// Refuses an input that only a method the study does not run reads; `what` names it.
void require_a_reader(const Study& s, const StudyInput& in, const std::string& what) {
  const std::string reader = method_reading(in.field);
  // The face friction also enters the closed forms that move the barrier by momentum.
  bool read_by_momentum = false;
  if (in.field == sweeps::face_friction) {
    try {
      const Scene base = parse_scene(s.scene_document);
      read_by_momentum = (s.runs("empirical") && base.methods.empirical &&
                          base.methods.empirical->barrier_model == BarrierModel::Momentum) ||
                         (s.runs("analytical") && base.methods.analytical &&
                          base.methods.analytical->barrier_model == BarrierModel::Momentum);
    } catch (const InputError&) {
      // an invalid base scene is reported by the caller's check of the sampled scene
    }
  }
  if (!reader.empty() && !s.runs(reader) && !read_by_momentum)
    fail(what + ": only the " + reader +
         " method reads it, and the study does not run it (methods: " + join(s.methods) + ")");
}

// One input: its path, the scene field it sets, and its distribution.
StudyInput parse_input(const json& j, const std::string& at) {
  static const std::vector<std::string> keys = {
      "path", "distribution", "value", "min", "max", "mean", "sd", "values", "weights", "count"};
  const ObjectReader r(j, at, keys);
  StudyInput in;
  in.path = r.string("path");
  const std::string why = unsampleable_path(in.path, in.field);
  if (!why.empty()) r.fail_at("path", why);
  const std::string kind = r.choice("distribution", kDistributions);
  // Keys each distribution takes; any other is an error (a forgotten "sd" must not pass silently).
  const std::vector<std::string> takes =
      kind == "constant"           ? std::vector<std::string>{"value"}
      : kind == "uniform"          ? std::vector<std::string>{"min", "max"}
      : kind == "normal"           ? std::vector<std::string>{"mean", "sd"}
      : kind == "lognormal"        ? std::vector<std::string>{"mean", "sd"}
      : kind == "truncated-normal" ? std::vector<std::string>{"mean", "sd", "min", "max"}
      : kind == "discrete"         ? std::vector<std::string>{"values", "weights"}
                                   : std::vector<std::string>{"min", "max", "count", "values"};
  for (const auto& k : keys) {
    if (k == "path" || k == "distribution" || !r.has(k)) continue;
    if (std::find(takes.begin(), takes.end(), k) == takes.end())
      r.fail_at(k, "not used by distribution \"" + kind + "\" (it takes: " + join(takes) + ")");
  }
  sweeps::DistributionSpec& d = in.distribution;
  using K = sweeps::DistributionKind;
  if (kind == "constant") {
    d.kind = K::Constant;
    d.value = r.number("value", any_number());
  } else if (kind == "uniform") {
    d.kind = K::Uniform;
    d.min = r.number("min", any_number());
    d.max = r.number("max", any_number());
    if (!(d.max > d.min)) r.fail_at("max", "must be > min = " + format_number(d.min));
  } else if (kind == "normal" || kind == "lognormal") {
    d.kind = kind == "normal" ? K::Normal : K::Lognormal;
    d.mean = r.number("mean", kind == "normal" ? any_number() : greater_than(0));
    d.sd = r.number("sd", greater_than(0));
  } else if (kind == "truncated-normal") {
    d.kind = K::TruncatedNormal;
    d.mean = r.number("mean", any_number());
    d.sd = r.number("sd", greater_than(0));
    d.min = r.number("min", any_number());
    d.max = r.number("max", any_number());
    if (!(d.max > d.min)) r.fail_at("max", "must be > min = " + format_number(d.min));
    // sweeps::validate's message for an interval without probability prints these four with
    // std::stod, which throws std::out_of_range for a subnormal number: refused here.
    for (const char* key : {"mean", "sd", "min", "max"}) {
      const double v = r.number(key, any_number());
      if (v != 0 && std::fabs(v) < std::numeric_limits<double>::min())
        r.fail_at(key, "must not be subnormal (0 < |value| < " +
                           format_number(std::numeric_limits<double>::min()) + ")");
    }
  } else if (kind == "discrete") {
    d.kind = K::Discrete;
    d.values = number_list(r, "values", any_number());
    if (r.has("weights")) d.weights = number_list(r, "weights", greater_than(0));
  } else {  // grid: evenly spaced points (min, max, count) or the listed values
    d.kind = K::Discrete;
    if (r.has("values")) {
      if (r.has("min") || r.has("max") || r.has("count"))
        r.fail_at("values", "give either values or min, max and count");
      d.values = number_list(r, "values", any_number());
    } else {
      const double lo = r.number("min", any_number()), hi = r.number("max", any_number());
      const long long n = r.integer("count", interval('[', 2, 1000000, ']'));
      if (!(hi > lo)) r.fail_at("max", "must be > min = " + format_number(lo));
      if (!std::isfinite(hi - lo)) r.fail_at("max", "max - min overflows a double: must be finite");
      for (long long i = 0; i < n; ++i)
        d.values.push_back(lo + (hi - lo) * double(i) / double(n - 1));
      d.values.back() = hi;
    }
  }
  try {
    sweeps::validate(d);
  } catch (const std::invalid_argument& e) {
    fail(at + ": " + e.what());
  }
  return in;
}

// A value the input typically takes: used to check, once, that the scene accepts the path.
double typical_value(const sweeps::DistributionSpec& d) {
  using K = sweeps::DistributionKind;
  switch (d.kind) {
    case K::Constant:
      return d.value;
    case K::Uniform:
      return 0.5 * (d.min + d.max);
    case K::Normal:
    case K::Lognormal:
      return d.mean;
    case K::TruncatedNormal:
      return std::clamp(d.mean, d.min, d.max);
    case K::Discrete:
      return d.values.front();
  }
  return d.value;
}

void set_value(json& doc, const StudyInput& in, double v) {
  json& slot = doc[json::json_pointer(in.path)];
  // Counts are written as JSON integers when the value is one (the parser accepts 4.0 as well).
  if (in.field == sweeps::body_squares && std::floor(v) == v && std::fabs(v) < 9e15)
    slot = static_cast<long long>(v);
  else
    slot = v;
}

std::vector<std::vector<double>> parse_correlation(const ObjectReader& root,
                                                   const std::vector<StudyInput>& inputs) {
  const json& v = *root.find("correlation");
  if (!v.is_array()) root.fail_at("correlation", "must be an array of {inputs: [path, path], rho}");
  const std::size_t n = inputs.size();
  std::vector<std::vector<double>> c(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) c[i][i] = 1.0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string at = "correlation[" + std::to_string(k) + "]";
    const ObjectReader r(v[k], at, {"inputs", "rho"});
    const json* pair = r.find("inputs");
    if (!pair || !pair->is_array() || pair->size() != 2 || !(*pair)[0].is_string() ||
        !(*pair)[1].is_string())
      r.fail_missing("inputs",
                     "two input paths, e.g. [\"/landslide/thickness_m\", "
                     "\"/landslide/velocity_m_s\"]");
    std::size_t idx[2];
    for (int s = 0; s < 2; ++s) {
      const std::string p = (*pair)[s].get<std::string>();
      auto it = std::find_if(inputs.begin(), inputs.end(),
                             [&](const StudyInput& in) { return in.path == p; });
      if (it == inputs.end())
        fail(at + ".inputs[" + std::to_string(s) + "] = " + format_value(json(p)) +
             ": not one of the study's inputs");
      idx[s] = static_cast<std::size_t>(it - inputs.begin());
    }
    if (idx[0] == idx[1]) r.fail_at("inputs", "the two inputs must differ");
    const double rho = r.number("rho", interval('(', -1, 1, ')'));
    if (c[idx[0]][idx[1]] != 0.0) r.fail_at("inputs", "this pair is given twice");
    c[idx[0]][idx[1]] = c[idx[1]][idx[0]] = rho;
  }
  return c;
}

StudyStop parse_stop(const ObjectReader& root, const Study& s) {
  StudyStop stop;
  const ObjectReader r = root.object("stop", {"wall_time_s", "interval"});
  stop.wall_time_s = r.number_or("wall_time_s", stop.wall_time_s, greater_than(0, "s"));
  if (auto iv =
          r.optional_object("interval", {"method", "output", "statistic", "threshold",
                                         "relative_half_width", "half_width", "min_samples"})) {
    stop.has_interval_rule = true;
    stop.method = iv->choice("method", s.methods);
    stop.output = iv->choice("output", s.outputs);
    stop.statistic = iv->choice("statistic", {"mean", "exceedance"});
    if (stop.statistic == "mean") {
      if (iv->has("threshold") || iv->has("half_width"))
        iv->fail_at(iv->has("threshold") ? "threshold" : "half_width",
                    "not used by statistic \"mean\" (it takes relative_half_width)");
      stop.relative_half_width = iv->number("relative_half_width", interval('(', 0, 1, ')'));
    } else {
      if (iv->has("relative_half_width"))
        iv->fail_at("relative_half_width",
                    "not used by statistic \"exceedance\" (it takes threshold and half_width)");
      stop.threshold = iv->number("threshold", any_number());
      stop.half_width = iv->number("half_width", interval('(', 0, 0.5, ']'));
    }
    stop.min_samples = static_cast<std::uint64_t>(
        iv->has("min_samples") ? iv->integer("min_samples", interval('[', 1, kMaxSamples, ']'))
                               : 1000);
  }
  return stop;
}

// A study none of whose first kValidityProbe samples is a valid scene (a lognormal with an
// enormous sd, fractional values for an integer field) would run every sample as invalid: it is
// refused, with the first sample's reason.
constexpr std::uint64_t kValidityProbe = 256;
void require_some_valid_samples(const Study& s, const sweeps::Sampler<Kokkos::HostSpace>& sampler) {
  const std::uint64_t n = std::min(s.samples, kValidityProbe);
  std::string first_reason;
  double x[sweeps::Sampler<Kokkos::HostSpace>::max_dimensions];
  for (std::uint64_t k = 0; k < n; ++k) {
    sampler.sample(k, x);
    const std::string why = invalid_sample_reason(s, x);
    if (why.empty()) return;
    if (k == 0) first_reason = why;
  }
  fail("inputs: none of the first " + std::to_string(n) + " samples is a valid scene (sample 0: " +
       first_reason + "); check the distributions against the scene's allowed ranges");
}

// The inputs drawn from distributions (every design but "points"), their correlation, the
// sample count and the seed.
void parse_drawn_inputs(const ObjectReader& root, const std::string& design, Study& s) {
  const json* inputs = root.find("inputs");
  if (!inputs) root.fail_missing("inputs", "non-empty array of {path, distribution, ...}");
  if (!inputs->is_array() || inputs->empty() ||
      inputs->size() > static_cast<std::size_t>(sweeps::Sampler<Kokkos::HostSpace>::max_dimensions))
    root.fail_at("inputs", "must be an array of 1 to " +
                               std::to_string(sweeps::Sampler<Kokkos::HostSpace>::max_dimensions) +
                               " inputs");
  for (std::size_t k = 0; k < inputs->size(); ++k) {
    const std::string at = "inputs[" + std::to_string(k) + "]";
    StudyInput in = parse_input((*inputs)[k], at);
    for (const auto& other : s.inputs)
      if (other.path == in.path) fail(at + ".path = \"" + in.path + "\": sampled twice");
    require_a_reader(s, in, at + ".path = \"" + in.path + "\"");
    // The scene must accept the key: check once with a typical value.
    json doc = s.scene_document;
    const double v = typical_value(in.distribution);
    set_value(doc, in, v);
    try {
      parse_scene(doc);
    } catch (const InputError& e) {
      fail(at + ".path = \"" + in.path + "\": the scene with its typical value " +
           format_number(v) + " is invalid: " + e.what());
    }
    s.inputs.push_back(std::move(in));
  }
  if (root.has("correlation")) s.correlation = parse_correlation(root, s.inputs);

  // Design and sample count.
  s.design = design == "monte-carlo"       ? sweeps::Design::MonteCarlo
             : design == "latin-hypercube" ? sweeps::Design::LatinHypercube
             : design == "sobol"           ? sweeps::Design::Sobol
                                           : sweeps::Design::Grid;
  if (s.design == sweeps::Design::Grid) {
    double product = 1.0;
    for (std::size_t k = 0; k < s.inputs.size(); ++k) {
      const auto& d = s.inputs[k].distribution;
      if (d.kind == sweeps::DistributionKind::Constant) {
        s.inputs[k].distribution.kind = sweeps::DistributionKind::Discrete;
        s.inputs[k].distribution.values = {d.value};
      } else if (d.kind != sweeps::DistributionKind::Discrete || !d.weights.empty()) {
        fail("inputs[" + std::to_string(k) +
             "].distribution: the grid design takes \"grid\", "
             "\"discrete\" (without weights) or \"constant\" inputs");
      }
      product *= static_cast<double>(s.inputs[k].distribution.values.size());
    }
    if (product > kMaxSamples) root.fail_at("design", "the grid has more than 9e15 points");
    if (root.has("samples") && root.integer("samples", interval('[', 1, kMaxSamples, ']')) !=
                                   static_cast<long long>(product))
      root.fail_at("samples", "a grid design runs every grid point: " + format_number(product) +
                                  " (or leave samples out)");
    if (root.has("correlation")) root.fail_at("correlation", "not used by the grid design");
    s.samples = static_cast<std::uint64_t>(product);
  } else {
    s.samples =
        static_cast<std::uint64_t>(root.integer("samples", interval('[', 1, kMaxSamples, ']')));
  }
  s.seed =
      root.has("seed")
          ? static_cast<std::uint64_t>(root.integer("seed", interval('[', 0, kMaxSamples, ']')))
          : 0;
}

std::vector<std::string> input_paths(const Study& s) {
  std::vector<std::string> paths;
  for (const auto& in : s.inputs) paths.push_back(in.path);
  return paths;
}

// The Points design: the inputs are the columns of the points file (those `inputs` lists, each
// {"path": P}, when it is given), the samples its rows, every value checked as the scene's.
void parse_given_points(const ObjectReader& root, const std::string& base_dir, Study& s) {
  namespace fs = std::filesystem;
  for (const char* key : {"correlation", "seed"})
    if (root.has(key))
      root.fail_at(key, "not used by the points design (its samples are the rows of points.file)");
  if (!root.has("points"))
    root.fail_missing("points",
                      "{\"file\": PATH}, the CSV or HDF5 file of the points, relative to the "
                      "study file");
  const ObjectReader r = root.object("points", {"file", "dataset"});
  fs::path file(r.string("file"));
  if (file.is_relative() && !base_dir.empty()) file = fs::path(base_dir) / file;
  const PointsTable t =
      read_points_file(file.string(), file.string(), r.optional_string("dataset").value_or(""));

  const auto max_inputs =
      static_cast<std::size_t>(sweeps::Sampler<Kokkos::HostSpace>::max_dimensions);
  std::vector<std::size_t> column_of_input;
  if (const json* inputs = root.find("inputs")) {
    if (!inputs->is_array() || inputs->empty() || inputs->size() > max_inputs)
      root.fail_at("inputs", "must be an array of 1 to " + std::to_string(max_inputs) +
                                 " inputs {\"path\": P}, each a column of the points file");
    for (std::size_t k = 0; k < inputs->size(); ++k) {
      const std::string at = "inputs[" + std::to_string(k) + "]";
      if ((*inputs)[k].is_object())
        for (const auto& item : (*inputs)[k].items())
          if (item.key() != "path")
            fail(join_path(at, item.key()) +
                 ": not used by the points design (an input of given points is {\"path\": P}; "
                 "its values are the column P of points.file)");
      const ObjectReader ir((*inputs)[k], at, {"path"});
      StudyInput in;
      in.path = ir.string("path");
      const std::string why = unsampleable_path(in.path, in.field);
      if (!why.empty()) ir.fail_at("path", why);
      for (const auto& other : s.inputs)
        if (other.path == in.path) ir.fail_at("path", "listed twice");
      require_a_reader(s, in, at + ".path = \"" + in.path + "\"");
      const auto column = std::find(t.columns.begin(), t.columns.end(), in.path);
      if (column == t.columns.end())
        fail(t.shown + ": no column " + in.path + " for " + at +
             " (the header names: " + join(t.columns) + ")");
      column_of_input.push_back(static_cast<std::size_t>(column - t.columns.begin()));
      s.inputs.push_back(std::move(in));
    }
    for (const auto& name : t.columns)
      if (std::none_of(s.inputs.begin(), s.inputs.end(),
                       [&](const StudyInput& in) { return in.path == name; }))
        fail(t.shown + ": column " + format_value(json(name)) +
             ": not one of the study's inputs (inputs: " + join(input_paths(s)) + ")");
  } else {
    if (t.columns.size() > max_inputs)
      fail(t.shown + ": " + std::to_string(t.columns.size()) + " columns: at most " +
           std::to_string(max_inputs) + " inputs");
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      StudyInput in;
      in.path = t.columns[c];
      const std::string column = t.shown + ": column " + format_value(json(in.path));
      const std::string why = unsampleable_path(in.path, in.field);
      if (!why.empty()) fail(column + ": " + why);
      require_a_reader(s, in, column);
      column_of_input.push_back(c);
      s.inputs.push_back(std::move(in));
    }
  }

  const std::size_t n = t.columns.size(), dims = s.inputs.size();
  s.points.file = fs::absolute(file).lexically_normal().string();
  s.points.value.resize(t.rows * dims);
  for (std::size_t i = 0; i < t.rows; ++i)
    for (std::size_t d = 0; d < dims; ++d)
      s.points.value[i * dims + d] = t.value[i * n + column_of_input[d]];
  if (root.has("samples") &&
      root.integer("samples", interval('[', 1, kMaxSamples, ']')) != static_cast<long long>(t.rows))
    root.fail_at("samples", "the points file has " + std::to_string(t.rows) +
                                " rows, the design runs each once (or leave samples out)");
  s.samples = t.rows;
  s.design = sweeps::Design::Points;
  check_given_points(s, t);
}

}  // namespace

sweeps::SceneValues scene_values(const Scene& sc) {
  using namespace sweeps;
  SceneValues v;
  const SceneLandslide& l = sc.landslide;
  const SceneBarrier& b = sc.barrier;
  v.value[thickness_m] = l.thickness_m;
  v.value[velocity_m_s] = l.velocity_m_s;
  v.value[density_kg_m3] = l.density_kg_m3;
  v.rectangle = l.shape.kind == LandslideShape::Kind::Rectangle;
  v.value[body_squares] = l.shape.body_squares;
  v.value[length_m] = l.shape.length_m;
  v.value[flow_base_friction] = l.base_friction;
  v.saturated_flow = !(sc.methods.mpm && !sc.methods.mpm->saturated);
  v.value[porosity] = l.material.porosity;
  v.value[friction_angle_deg] = l.material.friction_angle_deg;
  v.value[cohesion_kpa] = l.material.cohesion_kpa;
  v.value[young_modulus_mpa] = l.material.young_modulus_mpa;
  v.value[poisson_ratio] = l.material.poisson_ratio;
  v.value[hydraulic_conductivity_m_s] = l.material.hydraulic_conductivity_m_s;
  v.value[liquid_bulk_modulus_mpa] = l.material.liquid_bulk_modulus_mpa;
  v.value[liquid_viscosity_kpa_s] = l.material.liquid_viscosity_kpa_s;
  v.value[height_m] = b.height_m;
  v.value[base_width_m] = b.base_width_m;
  v.value[top_width_m] = b.top_width_m;
  v.value[face_angle_deg] = b.face_angle_deg;
  v.barrier_given_by_mass = b.mass_kg_per_m.has_value();
  v.value[barrier_density_kg_m3] = b.density_kg_m3.value_or(0.0);
  v.value[barrier_mass_kg_per_m] = b.mass_kg_per_m.value_or(0.0);
  v.value[base_friction] = b.base_friction;
  v.value[face_friction] = b.face_friction;
  v.fixed = b.fixed;
  const EmpiricalParameters e = sc.methods.empirical.value_or(EmpiricalParameters{});
  v.value[empirical_a1] = e.a1;
  v.value[empirical_a2] = e.a2;
  v.value[empirical_tau] = e.tau;
  v.value[empirical_kappa] = e.kappa;
  v.empirical_momentum = e.barrier_model == BarrierModel::Momentum;
  const AnalyticalParameters a = sc.methods.analytical.value_or(AnalyticalParameters{});
  v.analytical_lambda_given = a.lambda.has_value();
  v.analytical_tau_given = a.tau.has_value();
  v.analytical_momentum = a.barrier_model == BarrierModel::Momentum;
  // Unused values must still pass the range check: 1 is inside both (0, 1] and (0, 1).
  v.value[analytical_lambda] = a.lambda.value_or(1.0);
  v.value[analytical_tau] = a.tau.value_or(0.5);
  return v;
}

Study parse_study(const json& j, const std::string& base_dir) {
  if (!j.is_object()) fail("(top level) = " + format_value(j) + ": a study must be a JSON object");
  const ObjectReader root(j, "", kStudyKeys);
  Study s;
  s.name = root.string("name");

  // The base scene: a path (relative to the study file) or the scene itself.
  s.scene_document = read_scene_reference(root, base_dir);
  try {
    s.base = parse_scene(s.scene_document);
  } catch (const InputError& e) {
    fail(std::string("scene: ") + e.what());
  }
  s.base_values = scene_values(s.base);

  // Methods: listed, or the closed forms the scene selects.
  if (root.has("methods")) {
    s.methods = string_list(root, "methods", kSweepMethods);
  } else {
    if (s.base.methods.empirical) s.methods.push_back("empirical");
    if (s.base.methods.analytical) s.methods.push_back("analytical");
    if (s.methods.empty())
      root.fail_missing("methods",
                        "the scene selects neither empirical nor analytical; list the "
                        "methods (allowed: empirical, analytical, mpm)");
  }
  if (s.runs("mpm") && !s.base.methods.mpm)
    root.fail_at("methods",
                 "\"mpm\" needs a methods.mpm block in the scene (cell_size_m, ...; "
                 "docs/reference/scene_schema.md)");
  s.outputs = root.has("outputs") ? string_list(root, "outputs", kOutputs) : kOutputs;

  const std::string design = root.choice("design", kDesigns, std::string("monte-carlo"));
  if (design == "points") {
    parse_given_points(root, base_dir, s);
  } else {
    if (root.has("points"))
      root.fail_at("points", "used only by design \"points\" (the file of the given points)");
    parse_drawn_inputs(root, design, s);
  }
  s.confidence = root.number_or("confidence", s.confidence, interval('(', 0.5, 1, ')'));

  if (root.has("thresholds")) {
    const json& t = *root.find("thresholds");
    if (!t.is_array()) root.fail_at("thresholds", "must be an array of {output, above, method?}");
    for (std::size_t k = 0; k < t.size(); ++k) {
      const ObjectReader r(t[k], "thresholds[" + std::to_string(k) + "]",
                           {"method", "output", "above"});
      StudyThreshold th;
      if (r.has("method")) th.method = r.choice("method", s.methods);
      th.output = r.choice("output", s.outputs);
      th.above = r.number("above", any_number());
      s.thresholds.push_back(th);
    }
  }
  if (root.has("stop")) s.stop = parse_stop(root, s);
  if (auto q = root.optional_object("mpm_at_quantiles", {"method", "output", "quantiles"})) {
    if (!s.base.methods.mpm)
      root.fail_at("mpm_at_quantiles", "needs a methods.mpm block in the scene (cell_size_m, ...)");
    std::vector<std::string> closed;
    for (const auto& m : s.methods)
      if (m != "mpm") closed.push_back(m);
    if (closed.empty()) root.fail_at("mpm_at_quantiles", "the study runs no closed-form method");
    StudyQuantileMpm m;
    m.method = q->choice("method", closed);
    m.output = q->choice("output", s.outputs);
    m.quantiles = number_list(*q, "quantiles", interval('(', 0, 1, ')'));
    s.mpm_at_quantiles = m;
  }

  const double default_chunk = s.runs("mpm") ? 1.0 : double(1 << 20);
  s.chunk_samples = static_cast<std::uint64_t>(
      root.has("chunk_samples") ? root.integer("chunk_samples", interval('[', 1, kMaxChunk, ']'))
                                : default_chunk);

  // The sampler checks what only it can (a positive-definite correlation, Sobol's dimensions).
  ensure_kokkos();  // the sampler keeps its tables in Views
  std::optional<sweeps::Sampler<Kokkos::HostSpace>> sampler;
  try {
    sampler.emplace(s.sampler<Kokkos::HostSpace>());
  } catch (const std::invalid_argument& e) {
    fail(std::string(root.has("correlation") ? "correlation" : "design") + ": " + e.what());
  }
  if (s.design != sweeps::Design::Points)  // given points were each checked as a scene
    require_some_valid_samples(s, *sampler);

  // What the results store: the study as read, with its scene inlined and the resolved values.
  s.source = j;
  s.source["scene"] = s.scene_document;
  s.source["design"] = design;
  s.source["samples"] = s.samples;
  if (s.design != sweeps::Design::Points) s.source["seed"] = s.seed;
  s.source["methods"] = s.methods;
  s.source["outputs"] = s.outputs;
  s.source["chunk_samples"] = s.chunk_samples;
  std::uint64_t hash = fingerprint_hash(s.source.dump());
  if (s.design == sweeps::Design::Points) {
    // The file by its absolute path (`lsi merge` reads it again), the inputs by their columns,
    // and the values themselves in the fingerprint: a points file changed since a run started is
    // another study to `--resume`.
    s.source["points"]["file"] = s.points.file;
    s.source["inputs"] = json::array();
    for (const auto& in : s.inputs) s.source["inputs"].push_back({{"path", in.path}});
    hash = fingerprint_hash(s.source.dump());
    hash = fingerprint_hash(std::string_view(reinterpret_cast<const char*>(s.points.value.data()),
                                             s.points.value.size() * sizeof(double)),
                            hash);
  }
  s.fingerprint = hex_of(hash);
  return s;
}

Study load_study(const std::string& path) {
  namespace fs = std::filesystem;
  const json doc =
      read_scene_document(path, "study");  // file errors and malformed JSON, with the path
  try {
    Study s = parse_study(doc, fs::path(path).parent_path().string());
    s.path = path;
    return s;
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

json sample_scene_document(const Study& study, const double* input_values) {
  json doc = study.scene_document;
  for (std::size_t k = 0; k < study.inputs.size(); ++k)
    set_value(doc, study.inputs[k], input_values[k]);
  return doc;
}

std::string invalid_sample_reason(const Study& study, const double* input_values) {
  try {
    parse_scene(sample_scene_document(study, input_values));
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

}  // namespace lsi
