#include "app/accuracy_study.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include "io/json_fields.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "model/scene.hpp"
#include "io/scene_reference.hpp"
#include "io/scene_parser.hpp"

namespace lsi {
namespace {
using nlohmann::json;
using namespace json_fields;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const std::vector<std::string> kParameters = {"cells_per_thickness", "particles_per_cell",
                                              "courant"};

std::vector<std::string> parse_outputs(const ObjectReader& r, const std::string& key,
                                       const std::vector<std::string>& fallback) {
  const json* o = r.find(key);
  if (!o) return fallback;
  if (!o->is_array() || o->empty())
    r.fail_at(key, "must be a non-empty array of output names (" +
                       join(accuracy_output_names(), true) + ")");
  std::vector<std::string> out;
  for (size_t i = 0; i < o->size(); ++i) {
    const json& v = (*o)[i];
    const auto& names = accuracy_output_names();
    if (!v.is_string() ||
        std::find(names.begin(), names.end(), v.get<std::string>()) == names.end())
      fail(r.path_of(key) + "[" + std::to_string(i) + "] = " + format_value(v) +
           ": must be one of " + join(names, true));
    if (std::find(out.begin(), out.end(), v.get<std::string>()) != out.end())
      fail(r.path_of(key) + "[" + std::to_string(i) + "] = " + format_value(v) + ": listed twice");
    out.push_back(v.get<std::string>());
  }
  return out;
}

Range parameter_range(const std::string& parameter) {
  if (parameter == "cells_per_thickness") return at_least(4.0, "cells");  // cell <= h / 4
  if (parameter == "particles_per_cell") return interval('[', 1.0, 64.0, ']', "points");
  return interval('(', 0.0, 10.0, ']');  // Courant number
}

AccuracySeries parse_series(const json& j, const std::string& path,
                            const std::vector<std::string>& default_outputs) {
  const ObjectReader r(
      j, path, {"name", "parameter", "values", "set", "reference", "compare_to", "outputs"});
  AccuracySeries s;
  s.name = r.string("name");
  s.parameter = r.choice("parameter", kParameters);
  const json* values = r.find("values");
  if (!values) r.fail_missing("values", "an array of at least one value of " + s.parameter);
  if (!values->is_array() || values->empty())
    r.fail_at("values", "must be a non-empty array of numbers");
  const Range range = parameter_range(s.parameter);
  for (size_t i = 0; i < values->size(); ++i) {
    const std::string p = r.path_of("values") + "[" + std::to_string(i) + "]";
    const double v = check_number((*values)[i], p, range);
    if (s.parameter != "courant" && v != std::round(v))
      fail(p + " = " + format_number(v) + ": must be a whole number");
    if (s.parameter == "particles_per_cell") {
      const double side = std::round(std::sqrt(v));
      if (side * side != v)
        fail(p + " = " + format_number(v) + ": must be a square (1, 4, 9, ...)");
    }
    for (const double w : s.values)
      if (w == v) fail(p + " = " + format_number(v) + ": listed twice");
    s.values.push_back(v);
  }
  s.set = json::object();
  if (const json* set = r.find("set")) {
    if (!set->is_object()) r.fail_at("set", "must be an object of JSON pointer -> value");
    for (const auto& [pointer, value] : set->items()) {
      try {
        (void)json::json_pointer(pointer);
      } catch (const json::exception&) {
        fail(r.path_of("set") + "[\"" + pointer +
             "\"]: not a JSON pointer (e.g. /methods/mpm/transfer)");
      }
      s.set[pointer] = value;
    }
  }
  s.reference = r.boolean_or("reference", false);
  s.compare_to = r.optional_string("compare_to").value_or("");
  s.outputs = parse_outputs(r, "outputs", default_outputs);
  return s;
}

double largest_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

const std::vector<std::string>& accuracy_output_names() {
  static const std::vector<std::string> names = {"peak_force",        "rise_time",
                                                 "impact_duration",   "final_displacement",
                                                 "overtopped_volume", "energy_residual"};
  return names;
}

double accuracy_spacing(const std::string& parameter, double value) {
  if (parameter == "cells_per_thickness") return 1.0 / value;            // cell / thickness
  if (parameter == "particles_per_cell") return 1.0 / std::sqrt(value);  // point spacing / cell
  return value;                                                          // dt ∝ Courant
}

std::string series_file_stem(const std::string& name) {
  std::string s;
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      s += static_cast<char>(std::tolower(c));
    else if (!s.empty() && s.back() != '-')
      s += '-';
  }
  while (!s.empty() && s.back() == '-') s.pop_back();
  return s.empty() ? "series" : s;
}

AccuracyStudy parse_accuracy_study(const json& j, const std::string& base_dir) {
  if (!j.is_object())
    fail("(top level) = " + format_value(j) + ": an accuracy study must be a JSON object");
  const ObjectReader root(j, "", {"name", "scene", "outputs", "series"});
  AccuracyStudy st;
  st.name = root.string("name");
  st.scene_document = read_scene_reference(root, base_dir);
  try {
    (void)parse_scene(st.scene_document);
  } catch (const InputError& e) {
    fail(std::string("scene: ") + e.what());
  }
  if (!st.scene_document.contains("landslide"))
    fail("scene: an accuracy study needs a landslide-barrier scene (landslide, barrier)");
  st.outputs = parse_outputs(
      root, "outputs", {"peak_force", "impact_duration", "final_displacement", "energy_residual"});
  const json* series = root.find("series");
  if (!series) root.fail_missing("series", "an array of series of MPM runs");
  if (!series->is_array() || series->empty())
    root.fail_at("series", "must be a non-empty array of series");
  int references = 0;
  for (size_t i = 0; i < series->size(); ++i) {
    const std::string path = "series[" + std::to_string(i) + "]";
    AccuracySeries s = parse_series((*series)[i], path, st.outputs);
    for (const auto& other : st.series) {
      if (other.name == s.name) fail(path + ".name = \"" + s.name + "\": used twice");
      if (series_file_stem(other.name) == series_file_stem(s.name))
        fail(path + ".name = \"" + s.name + "\": its run files would have the names of series \"" +
             other.name + "\"'s (both " + series_file_stem(s.name) +
             "-...): names must differ in their letters or digits");
    }
    references += s.reference ? 1 : 0;
    // Every run's scene must be valid now, not after an hour of runs.
    for (const double v : s.values) {
      try {
        (void)impact_case(parse_scene(accuracy_run_scene(st, s, v)));  // specs only: cheap
      } catch (const InputError& e) {
        fail(path + " (" + s.name + "), " + s.parameter + " = " + format_number(v) + ": " +
             e.what());
      } catch (const json::exception& e) {
        fail(path + ".set: " + e.what());
      }
    }
    if (s.reference && s.values.size() < 3)
      fail(path + ".values: the reference series needs at least 3 runs (Richardson extrapolation)");
    st.series.push_back(std::move(s));
  }
  for (size_t i = 0; i < st.series.size(); ++i) {
    const std::string& target = st.series[i].compare_to;
    if (!target.empty() && std::none_of(st.series.begin(), st.series.end(),
                                        [&](const AccuracySeries& x) { return x.name == target; }))
      fail("series[" + std::to_string(i) + "].compare_to = \"" + target +
           "\": no series has this name");
  }
  if (references != 1)
    fail("series: exactly one series must have \"reference\": true (found " +
         std::to_string(references) + ")");
  st.source = j;
  st.source["scene"] = st.scene_document;
  return st;
}

AccuracyStudy load_accuracy_study(const std::string& path) {
  const json doc = read_scene_document(path, "accuracy study");
  try {
    return parse_accuracy_study(doc, std::filesystem::path(path).parent_path().string());
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

json accuracy_run_scene(const AccuracyStudy& study, const AccuracySeries& series, double value) {
  json s = study.scene_document;
  // Only the MPM runs: the closed forms are timed separately by the study.
  if (s.contains("methods") && s["methods"].is_object()) {
    json methods = json::object();
    if (s["methods"].contains("mpm")) methods["mpm"] = s["methods"]["mpm"];
    s["methods"] = methods;
  }
  for (const auto& [pointer, v] : series.set.items()) s[json::json_pointer(pointer)] = v;
  json& mpm = s["methods"]["mpm"];
  if (series.parameter == "cells_per_thickness") {
    const double h = s.at("landslide").at("thickness_m").get<double>();
    mpm["cell_size_m"] = h / value;
  } else if (series.parameter == "particles_per_cell") {
    mpm["particles_per_cell"] = static_cast<int>(value);
  } else {
    mpm["courant"] = value;
  }
  s["name"] = study.scene_document.value("name", std::string("scene")) + " " + series.name + " " +
              series.parameter + "=" + format_number(value);
  return s;
}

AccuracyRun run_accuracy_case(const json& scene, const AccuracySeries& series, double value) {
  const Scene s = parse_scene(scene);
  const MpmOutcome o = run_mpm_case(impact_case(s));
  AccuracyRun r;
  r.value = value;
  r.h = accuracy_spacing(series.parameter, value);
  r.status = o.status();
  r.finished = o.finished();
  r.solver_seconds = o.run().solver_seconds;
  r.steps = static_cast<double>(o.run().steps);
  r.particles = static_cast<double>(o.run().particles);
  r.threads = o.run().threads;
  r.result = o.result;
  const MethodResult& m = r.result;
  r.outputs["peak_force"] = m.peak_force;
  r.outputs["rise_time"] = m.rise_time;
  r.outputs["impact_duration"] = m.impact_duration;
  r.outputs["final_displacement"] = m.final_displacement;
  // At the end of the run.
  r.outputs["overtopped_volume"] = m.scalars.overtopped_volume_m2.value_or(kNaN);
  const auto it = m.series.find("energy_residual");
  r.outputs["energy_residual"] = it == m.series.end() ? kNaN : largest_abs(it->second.values);
  return r;
}

json to_json(const AccuracyRun& r) {
  json o = json::object();
  for (const auto& [k, v] : r.outputs) o[k] = std::isfinite(v) ? json(v) : json(format_number(v));
  return {{"value", r.value},
          {"h", r.h},
          {"status", r.status},
          {"finished", r.finished},
          {"solver_seconds", r.solver_seconds},
          {"steps", r.steps},
          {"particles", r.particles},
          {"threads", r.threads},
          {"outputs", o}};
}

AccuracyRun accuracy_run_from_json(const json& j) {
  AccuracyRun r;
  r.value = j.at("value").get<double>();
  r.h = j.at("h").get<double>();
  r.status = j.at("status").get<std::string>();
  r.finished = j.at("finished").get<bool>();
  r.solver_seconds = j.at("solver_seconds").get<double>();
  r.steps = j.at("steps").get<double>();
  r.particles = j.at("particles").get<double>();
  r.threads = j.value("threads", 0);  // 0: not recorded
  for (const auto& [k, v] : j.at("outputs").items()) {
    if (v.is_number())
      r.outputs[k] = v.get<double>();
    else
      r.outputs[k] = std::strtod(v.get<std::string>().c_str(), nullptr);  // "inf", "nan"
  }
  return r;
}

OutputConvergence output_convergence(const std::vector<AccuracyRun>& runs,
                                     const std::string& output) {
  std::vector<std::pair<double, double>> hv;  // (h, value), finished and finite
  for (const auto& r : runs) {
    const auto it = r.outputs.find(output);
    if (r.finished && it != r.outputs.end() && std::isfinite(it->second))
      hv.emplace_back(r.h, it->second);
  }
  std::sort(hv.begin(), hv.end());  // finest first
  OutputConvergence c;
  c.runs = static_cast<int>(hv.size());
  c.order_next = kNaN;
  c.order_to_exact = c.order_to_exact_next = kNaN;
  if (output == "energy_residual") {  // exact value known
    c.exact = true;
    c.best = 0.0;
    c.best_source = "exact";
    const auto order = [&](size_t k) {  // pair k, k+1
      const double e1 = std::abs(hv[k].second), e2 = std::abs(hv[k + 1].second);
      return e1 > 0 && e2 > 0 ? std::log(e2 / e1) / std::log(hv[k + 1].first / hv[k].first) : kNaN;
    };
    if (hv.size() >= 2) c.order_to_exact = order(0);
    if (hv.size() >= 3) c.order_to_exact_next = order(1);
  } else if (!hv.empty()) {
    c.best = hv[0].second;
    c.best_source = "finest run";
  } else {
    c.best = kNaN;
    c.best_source = "none";
  }
  if (hv.size() >= 3) {
    c.finest = sweeps::grid_convergence({hv[0].first, hv[1].first, hv[2].first},
                                        {hv[0].second, hv[1].second, hv[2].second});
    if (output != "energy_residual" && c.finest.kind == sweeps::Convergence::Monotonic &&
        std::isfinite(c.finest.extrapolated)) {
      c.best = c.finest.extrapolated;
      c.best_source = "richardson";
    }
  }
  if (hv.size() >= 4) {
    const auto next = sweeps::grid_convergence({hv[1].first, hv[2].first, hv[3].first},
                                               {hv[1].second, hv[2].second, hv[3].second});
    c.order_next = next.order;
  }
  return c;
}

double accuracy_error(const std::string& output, double value, double reference) {
  if (!std::isfinite(value) || !std::isfinite(reference)) return kNaN;
  if (output == "energy_residual" || reference == 0.0) return value - reference;
  return (value - reference) / std::abs(reference);
}

}  // namespace lsi
