// The accuracy study's results: closed forms timed on the base scene, errors of every run against
// the reference series, convergence tables; JSON for the plots and Markdown for people.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <thread>

#include "app/accuracy_study.hpp"
#include "model/closed_form_methods.hpp"
#include "io/json_fields.hpp"
#include "model/scene.hpp"
#include "model/time_call.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time
#include "io/scene_parser.hpp"

namespace lsi {
namespace {
using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// JSON has no inf/nan: they are written as the strings "inf", "-inf", "nan".
json number(double v) { return std::isfinite(v) ? json(v) : json(json_fields::format_number(v)); }
double read_number(const json& j) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) return std::strtod(j.get<std::string>().c_str(), nullptr);
  return kNaN;
}

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  return "unknown";
}

std::map<std::string, double> closed_form_outputs(const MethodResult& m) {
  return {{"peak_force", m.peak_force},
          {"rise_time", m.rise_time},
          {"impact_duration", m.impact_duration},
          {"final_displacement", m.final_displacement}};
}

// Fixed notation with `digits` significant digits; "-" for NaN, "never" for +inf.
std::string fmt(double v, int digits = 4) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "never" : "-inf";
  std::ostringstream s;
  s << std::setprecision(digits) << v;
  return s.str();
}
std::string percent(double v) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::showpos << std::fixed << std::setprecision(std::abs(v) < 0.1 ? 2 : 1) << 100 * v
    << " %";
  return s.str();
}

const char* unit_of(const std::string& output) {
  if (output == "peak_force") return "kN/m";
  if (output == "final_displacement") return "m";
  if (output == "overtopped_volume") return "m^2";
  if (output == "energy_residual") return "1";
  return "s";
}
double display(const std::string& output, double v) { return output == "peak_force" ? v / 1e3 : v; }

}  // namespace

std::vector<ClosedFormTiming> time_closed_forms(const AccuracyStudy& study) {
  json doc = study.scene_document;
  // The closed forms with the scene's parameters where it gives them (a scene without a methods
  // block runs both with their defaults).
  const json methods =
      doc.contains("methods") && doc["methods"].is_object() ? doc["methods"] : json::object();
  doc["methods"] = {{"empirical", methods.value("empirical", json::object())},
                    {"analytical", methods.value("analytical", json::object())}};
  const Scene scene = parse_scene(doc);
  std::vector<ClosedFormTiming> out;
  for (const std::string method : {"empirical", "analytical"}) {
    ClosedFormTiming t;
    t.method = method;
    MethodResult r;
    // Median of 5 timings, each the mean over >= 20 ms of calls (the machine is noisy).
    std::vector<double> times;
    for (int rep = 0; rep < 5; ++rep)
      times.push_back(time_call(
          [&] { return method == "empirical" ? run_empirical(scene) : run_analytical(scene); }, r));
    std::sort(times.begin(), times.end());
    t.seconds_per_evaluation = times[2];
    t.outputs = closed_form_outputs(r);
    out.push_back(std::move(t));
  }
  return out;
}

json accuracy_report(const AccuracyStudy& study, const std::vector<std::vector<AccuracyRun>>& runs,
                     const std::vector<ClosedFormTiming>& closed_forms) {
  json rep;
  rep["study"] = study.source;
  const char* threads = std::getenv("OMP_NUM_THREADS");
  rep["machine"] = {{"cpu", cpu_model()},
                    {"hardware_threads", std::thread::hardware_concurrency()},
                    {"omp_num_threads", threads ? threads : "unset"},
                    {"lsi_revision", LSI_GIT_REVISION}};
  // The reference: per output, the best estimate of the reference series (or of the series a
  // series compares to).
  const auto best_of = [&](size_t k) {
    std::map<std::string, double> best;
    for (const auto& o : accuracy_output_names()) best[o] = output_convergence(runs[k], o).best;
    return best;
  };
  const auto index_of = [&](const std::string& name) {
    for (size_t k = 0; k < study.series.size(); ++k)
      if (study.series[k].name == name) return k;
    return study.series.size();
  };
  size_t ref = 0;
  for (size_t i = 0; i < study.series.size(); ++i)
    if (study.series[i].reference) ref = i;
  const std::map<std::string, double> reference = best_of(ref);
  json jref = json::object();
  for (const auto& o : accuracy_output_names())
    jref[o] = {{"value", number(reference.at(o))},
               {"source", output_convergence(runs[ref], o).best_source},
               {"series", study.series[ref].name}};
  rep["reference"] = jref;
  json jseries = json::array();
  for (size_t i = 0; i < study.series.size(); ++i) {
    const AccuracySeries& s = study.series[i];
    json js = {{"name", s.name},
               {"parameter", s.parameter},
               {"set", s.set},
               {"reference", s.reference},
               {"outputs", s.outputs}};
    const std::map<std::string, double> against =
        s.compare_to.empty() ? reference : best_of(index_of(s.compare_to));
    js["compared_to"] = s.compare_to.empty() ? study.series[ref].name : s.compare_to;
    json jruns = json::array();
    for (const AccuracyRun& r : runs[i]) {
      json jr = to_json(r);
      json errors = json::object();
      for (const auto& o : s.outputs) {
        const auto it = r.outputs.find(o);
        errors[o] = number(r.finished && it != r.outputs.end()
                               ? accuracy_error(o, it->second, against.at(o))
                               : kNaN);
      }
      jr["errors"] = errors;
      jruns.push_back(jr);
    }
    js["runs"] = jruns;
    json conv = json::object();
    for (const auto& o : s.outputs) {
      const OutputConvergence c = output_convergence(runs[i], o);
      const bool three = c.runs >= 3;
      // Richardson's value and the GCI only mean something for monotonic convergence.
      const bool monotonic = three && c.finest.kind == sweeps::Convergence::Monotonic;
      if (c.exact) {
        conv[o] = {{"runs", c.runs},
                   {"kind", c.runs >= 2 ? "against the exact value 0" : "too few runs"},
                   {"order", number(c.order_to_exact)},
                   {"order_next_coarser", number(c.order_to_exact_next)},
                   {"extrapolated", 0.0},
                   {"relative_change", number(kNaN)},
                   {"gci_fine", number(kNaN)},
                   {"asymptotic_ratio", number(kNaN)},
                   {"best", 0.0},
                   {"best_source", c.best_source}};
      } else {
        conv[o] = {{"runs", c.runs},
                   {"kind", three ? describe(c.finest.kind) : "too few runs"},
                   {"order", number(three ? c.finest.order : kNaN)},
                   {"order_next_coarser", number(c.order_next)},
                   {"extrapolated", number(monotonic ? c.finest.extrapolated : kNaN)},
                   {"relative_change", number(three ? c.finest.relative_change : kNaN)},
                   {"gci_fine", number(monotonic ? c.finest.gci_fine : kNaN)},
                   {"asymptotic_ratio", number(monotonic ? c.finest.asymptotic_ratio : kNaN)},
                   {"best", number(c.best)},
                   {"best_source", c.best_source}};
      }
    }
    js["convergence"] = conv;
    jseries.push_back(js);
  }
  rep["series"] = jseries;
  json jcf = json::array();
  for (const auto& t : closed_forms) {
    json outs = json::object(), errs = json::object();
    for (const auto& [o, v] : t.outputs) {
      outs[o] = number(v);
      errs[o] = number(accuracy_error(o, v, reference.at(o)));
    }
    jcf.push_back({{"method", t.method},
                   {"seconds_per_evaluation", t.seconds_per_evaluation},
                   {"outputs", outs},
                   {"errors", errs}});
  }
  rep["closed_forms"] = jcf;
  return rep;
}

std::string accuracy_markdown(const json& rep) {
  std::ostringstream md;
  const json& st = rep.at("study");
  md << "# Accuracy study: " << st.value("name", std::string()) << "\n\n"
     << "Base scene `" << st.at("scene").value("name", std::string())
     << "`; machine: " << rep.at("machine").at("cpu").get<std::string>() << ", "
     << rep.at("machine").at("hardware_threads").get<unsigned>() << " hardware threads, "
     << "OMP_NUM_THREADS=" << rep.at("machine").at("omp_num_threads").get<std::string>() << ", lsi "
     << rep.at("machine").at("lsi_revision").get<std::string>() << ".\n\n"
     << "Errors are against the reference below (relative; the energy residual is absolute, its "
        "exact value being 0). Wall time is the solver loop of one run (no set-up, no I/O), one "
        "repetition on a shared machine: read ratios, not absolute values.\n\n";
  md << "## Reference\n\n| output | value | from |\n|---|---|---|\n";
  for (const auto& [o, r] : rep.at("reference").items())
    md << "| " << o << " [" << unit_of(o) << "] | " << fmt(display(o, read_number(r.at("value"))))
       << " | " << r.at("source").get<std::string>() << " of `" << r.at("series").get<std::string>()
       << "` |\n";
  for (const json& s : rep.at("series")) {
    const auto outputs = s.at("outputs").get<std::vector<std::string>>();
    md << "\n## " << s.at("name").get<std::string>()
       << (s.at("reference").get<bool>() ? " (reference)" : "") << "\n\n"
       << "Settings: `" << s.at("set").dump() << "`; refined: `"
       << s.at("parameter").get<std::string>() << "`; errors against the best estimate of `"
       << s.at("compared_to").get<std::string>() << "`.\n\n";
    md << "| " << s.at("parameter").get<std::string>() << " | status | points | steps | wall s |";
    for (const auto& o : outputs) md << " " << o << " [" << unit_of(o) << "] | error |";
    md << "\n|---|---|---|---|---|";
    for (size_t k = 0; k < outputs.size(); ++k) md << "---|---|";
    md << "\n";
    for (const json& r : s.at("runs")) {
      md << "| " << fmt(r.at("value").get<double>()) << " | " << r.at("status").get<std::string>()
         << " | " << fmt(r.at("particles").get<double>(), 7) << " | "
         << fmt(r.at("steps").get<double>(), 8) << " | "
         << fmt(r.at("solver_seconds").get<double>(), 3) << " |";
      for (const auto& o : outputs) {
        const double v = read_number(r.at("outputs").value(o, json("nan")));
        const double e = read_number(r.at("errors").value(o, json("nan")));
        md << " " << fmt(display(o, v)) << " | "
           << (o == "energy_residual" ? fmt(e, 2) : percent(e)) << " |";
      }
      md << "\n";
    }
    md << "\nConvergence of the three finest finished runs (Celik et al. 2008): observed order p, "
          "order of the next-coarser triple, Richardson value and fine-grid GCI (monotonic "
          "convergence only). The energy residual, exactly 0, gets the order of its own decay over "
          "the two finest runs (and the next pair).\n\n"
       << "| output | runs | kind | p | p (next) | extrapolated | GCI fine |\n"
       << "|---|---|---|---|---|---|---|\n";
    for (const auto& o : outputs) {
      const json& c = s.at("convergence").at(o);
      md << "| " << o << " | " << c.at("runs").get<int>() << " | "
         << c.at("kind").get<std::string>() << " | " << fmt(read_number(c.at("order")), 3) << " | "
         << fmt(read_number(c.at("order_next_coarser")), 3) << " | "
         << fmt(display(o, read_number(c.at("extrapolated")))) << " | "
         << percent(read_number(c.at("gci_fine"))) << " |\n";
    }
  }
  md << "\n## Closed forms against the reference\n\n| method | s per evaluation |";
  const std::vector<std::string> cf = {"peak_force", "rise_time", "impact_duration",
                                       "final_displacement"};
  for (const auto& o : cf) md << " " << o << " [" << unit_of(o) << "] | error |";
  md << "\n|---|---|";
  for (size_t k = 0; k < cf.size(); ++k) md << "---|---|";
  md << "\n";
  for (const json& c : rep.at("closed_forms")) {
    md << "| " << c.at("method").get<std::string>() << " | "
       << fmt(c.at("seconds_per_evaluation").get<double>(), 3) << " |";
    for (const auto& o : cf)
      md << " " << fmt(display(o, read_number(c.at("outputs").at(o)))) << " | "
         << percent(read_number(c.at("errors").at(o))) << " |";
    md << "\n";
  }
  return md.str();
}

}  // namespace lsi
