// `lsi calibrate SCENES... [--results-dir DIR] [--objective nrms|peak-duration] [--grid NxM]
//                          [--out FILE.h5] [--format table|json]`
//
// Fits the analytical model's lambda, tau (and the empirical model's tau per case, a1 and a2 per
// group) to MPM force histories (sweeps/calibration.hpp), pools the cases into fixed- and
// free-barrier groups next to the paper's values, and compares every closed-form result (default
// and calibrated coefficients) with the MPM, with the run time of each method. docs/theory/calibration.md.
//
// For each scene the MPM history comes from DIR/<scene name>.h5 if that file has an /mpm group
// written for the same landslide, barrier and methods.mpm (`lsi compare --out-dir DIR`,
// `lsi run --out`); otherwise the MPM runs here (the scene needs methods.mpm).
//
// HDF5 layout of --out (written to a temporary name, fsync'ed and renamed: never a partial file):
//   /                       attrs objective, lambda_cells, tau_cells, profile_tolerance,
//                           confidence, lsi_version, report (the JSON report, as printed)
//   /cases/<name>           attrs group ("fixed"|"free"), source, scene (JSON) and every fitted
//                           scalar (lambda, tau, sigma_lambda, ..., empirical_tau, alpha_mpm, ...)
//     lambda [N], tau [M]   the map's axes
//     misfit_map [N x M]    misfit at (lambda[i], tau[j]); attrs dims = "lambda,tau", objective
//     empirical_tau_axis [M], empirical_misfit [M]   the empirical model's 1-D scan
//     mpm_time, mpm_force   the MPM history that was fitted
//   /groups/<fixed|free>    attrs n, <p>_mean, <p>_std, <p>_ci_low, <p>_ci_high for p = lambda,
//                           tau, empirical_tau; a1, a2 (+ _ci_low/_ci_high), paper_*; cases [n]
//   /comparison             parallel 1D datasets, one row per case x method x coefficients:
//                           case, method, coefficients (strings), lambda, tau, a1, a2,
//                           empirical_tau, peak_force, impact_duration, final_displacement,
//                           their *_rel_error against the MPM, run_time_s
#include <hdf5.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/closed_form_methods.hpp"
#include "io/hdf5_io.hpp"
#include "io/hdf5_results.hpp"
#include "model/concurrent_runs.hpp"
#include "model/mpm_footprint.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "io/output_paths.hpp"
#include "model/scene.hpp"
#include "app/subcommand.hpp"
#include "model/time_call.hpp"
#include "kernels/common/math.hpp"
#include "sweeps/calibration.hpp"
#include "io/scene_parser.hpp"

#ifndef LSI_VERSION
#define LSI_VERSION "unknown"
#endif

namespace lsi {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double confidence = 0.95;

struct Options {
  std::vector<std::string> scenes;
  std::string results_dir;
  std::string objective = "nrms";
  std::string grid = "41x41";
  std::string out;
  std::string format = "table";
  std::string barrier_model = "paper";  // the closed forms' barrier model (scene.hpp)
};

// ---------------------------------------------------------------------------------------------
// Options.

sweeps::CalibrationOptions calibration_options(const Options& o) {
  sweeps::CalibrationOptions c;
  if (o.objective == "nrms")
    c.objective = sweeps::Objective::NormalisedRms;
  else if (o.objective == "peak-duration")
    c.objective = sweeps::Objective::PeakDuration;
  else
    throw InputError("--objective " + o.objective + ": allowed: nrms, peak-duration");
  const std::regex grid_re(R"(^\s*(\d{1,9})\s*[xX]\s*(\d{1,9})\s*$)");
  std::smatch m;
  const std::string range =
      ": must be NxM (lambda cells x tau cells) with N and M integers in "
      "[2, 2001], e.g. 41x41";
  if (!std::regex_match(o.grid, m, grid_re)) throw InputError("--grid " + o.grid + range);
  const long n = std::stol(m[1].str()), k = std::stol(m[2].str());
  if (n < 2 || n > 2001 || k < 2 || k > 2001) throw InputError("--grid " + o.grid + range);
  c.lambda_cells = static_cast<int>(n);
  c.tau_cells = static_cast<int>(k);
  if (o.format != "table" && o.format != "json")
    throw InputError("--format " + o.format + ": allowed: table, json");
  if (o.barrier_model != "paper" && o.barrier_model != "momentum")
    throw InputError("--barrier-model " + o.barrier_model + ": allowed: paper, momentum");
  c.momentum = o.barrier_model == "momentum";
  if (!o.results_dir.empty() && !fs::is_directory(o.results_dir))
    throw InputError("--results-dir " + o.results_dir + ": not a directory");
  return c;
}

template <class F>
auto with_path(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind(path, 0) == 0) throw;
    throw InputError(path + ": " + what);
  }
}

// ---------------------------------------------------------------------------------------------
// Cases: the MPM history (stored or computed) and the model inputs.

struct Case {
  std::string path;
  Scene scene;
  MethodResult mpm;
  std::string source;        // "file DIR/x.h5" or "mpm run"
  double mpm_seconds = nan;  // the MPM solver's wall time
  sweeps::CalibrationCase cal;
  sweeps::TwoBodyFit fit;
  sweeps::EmpiricalFit empirical;
};

sweeps::ImpactInputs impact_inputs(const Scene& s) {
  sweeps::ImpactInputs in;
  const SceneLandslide& l = s.landslide;
  in.landslide_mass = l.mass_kg_per_m();
  in.velocity = l.velocity_m_s;
  in.equivalent_length = l.equivalent_length_m();
  in.fixed = s.barrier.fixed;
  in.barrier_mass = s.barrier.fixed ? inf : s.barrier.mass();
  in.thickness = l.thickness_m;
  in.density = l.density_kg_m3;
  in.face_angle = math::degrees_to_radians(s.barrier.face_angle_deg);
  in.kappa = s.methods.empirical ? s.methods.empirical->kappa : 0.0;
  in.base_friction = s.barrier.base_friction;
  in.face_friction = s.barrier.face_friction;
  in.flow_friction = flow_friction_deceleration(s);
  return in;
}

// The stored result is usable if it was written for the same landslide, barrier and MPM settings.
bool same_setup(const json& stored, const json& scene) {
  auto part = [](const json& j, const char* a, const char* b = nullptr) {
    if (!j.is_object() || !j.contains(a)) return json();
    if (!b) return j[a];
    return j[a].is_object() && j[a].contains(b) ? j[a][b] : json();
  };
  return part(stored, "landslide") == part(scene, "landslide") &&
         part(stored, "barrier") == part(scene, "barrier") &&
         part(stored, "methods", "mpm") == part(scene, "methods", "mpm");
}

// Where a case's MPM history comes from: a stored run (read), none usable (the case is skipped,
// with a message on stderr), or a run still to make (run_mpm).
enum class MpmSource { Stored, Skipped, ToRun };

MpmSource stored_mpm(Case& c, const std::string& results_dir) {
  const Scene& s = c.scene;
  if (!results_dir.empty()) {
    const fs::path file = fs::path(results_dir) / (s.name + ".h5");
    if (fs::exists(file)) {
      const StoredResults stored = read_results(file.string());
      const MethodResult* mpm = nullptr;
      for (const auto& r : stored.results)
        if (r.method == "mpm") mpm = &r;
      if (mpm && same_setup(stored.scene, s.source)) {
        c.mpm = *mpm;
        c.source = "file " + file.string();
        c.mpm_seconds = mpm->run ? mpm->run->solver_seconds : nan;
        if (mpm->run && !mpm->run->finished) {
          std::cerr << "lsi: " << c.path << ": the stored MPM run in " << file.string()
                    << " stopped before its end time; case skipped\n";
          return MpmSource::Skipped;
        }
        return MpmSource::Stored;
      }
      std::cerr << "lsi: note: " << file.string()
                << (mpm ? " was written for a different landslide, barrier or methods.mpm"
                        : " has no /mpm group")
                << "; running the MPM for " << c.path << "\n";
    }
  }
  if (!s.methods.mpm)
    throw InputError(
        c.path +
        ": methods.mpm: missing: calibrate needs an MPM history; add a "
        "methods.mpm block ({\"cell_size_m\": ...}, docs/reference/scene_schema.md) or give "
        "--results-dir with " +
        s.name + ".h5 holding an /mpm group");
  return MpmSource::ToRun;
}

// Runs the case's MPM; false (with a message on stderr) if the run stopped unstable. Runs of
// several cases go side by side (model/concurrent_runs.hpp).
bool run_mpm(Case& c) {
  const MpmCase mc = with_path(c.path, [&] { return impact_case(c.scene); });
  MpmOutcome o = run_mpm_case(mc);
  c.mpm = std::move(o.result);
  c.source = "mpm run";
  c.mpm_seconds = o.run().solver_seconds;
  if (!o.finished()) {
    std::cerr << "lsi: " << c.path << ": the MPM run stopped: " << o.status() << "; case skipped\n";
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// The comparison: closed forms with default and calibrated coefficients against the MPM.

struct Row {
  std::string case_name, method, coefficients;
  double lambda = nan, tau = nan, a1 = nan, a2 = nan, empirical_tau = nan;
  double peak_force = nan, impact_duration = nan, final_displacement = nan;
  double peak_error = nan, duration_error = nan, displacement_error = nan;
  double run_time_s = nan;
};

double relative_error(double x, double ref) {
  if (!std::isfinite(ref) || ref == 0.0) return nan;  // MPM never stops, or a fixed barrier
  if (!std::isfinite(x)) return inf;
  return (x - ref) / ref;
}

Row closed_form_row(const Case& c, const std::string& method, const std::string& coefficients,
                    const Scene& scene) {
  Row r;
  r.case_name = c.scene.name;
  r.method = method;
  r.coefficients = coefficients;
  MethodResult res;
  if (method == "analytical") {
    r.run_time_s = time_call([&] { return run_analytical(scene); }, res);
    r.lambda = res.scalars.lambda.value();
    r.tau = res.scalars.tau.value();
  } else {
    r.run_time_s = time_call([&] { return run_empirical(scene); }, res);
    const EmpiricalParameters p = scene.methods.empirical.value_or(EmpiricalParameters{});
    r.a1 = p.a1;
    r.a2 = p.a2;
    r.empirical_tau = p.tau;
  }
  r.peak_force = res.peak_force;
  r.impact_duration = res.impact_duration;
  r.final_displacement = res.final_displacement;
  r.peak_error = relative_error(r.peak_force, c.mpm.peak_force);
  r.duration_error = relative_error(r.impact_duration, c.mpm.impact_duration);
  r.displacement_error = relative_error(r.final_displacement, c.mpm.final_displacement);
  if (c.scene.barrier.fixed && r.final_displacement == 0.0 && c.mpm.final_displacement == 0.0)
    r.displacement_error = 0.0;
  return r;
}

Scene with_analytical(const Scene& s, double lambda, double tau, BarrierModel model) {
  Scene x = s;
  AnalyticalParameters p;
  p.barrier_model = model;
  if (std::isfinite(lambda)) p.lambda = lambda;
  if (std::isfinite(tau)) p.tau = tau;
  x.methods.analytical = p;
  return x;
}

Scene with_empirical(const Scene& s, double a1, double a2, double tau, BarrierModel model) {
  Scene x = s;
  EmpiricalParameters p;  // defaults: the paper's a1, a2, tau, kappa 0
  p.barrier_model = model;
  if (s.methods.empirical && model == BarrierModel::Paper) p.kappa = s.methods.empirical->kappa;
  if (std::isfinite(a1)) p.a1 = a1;
  if (std::isfinite(a2)) p.a2 = a2;
  if (std::isfinite(tau)) p.tau = tau;
  x.methods.empirical = p;
  return x;
}

// ---------------------------------------------------------------------------------------------
// Reports.

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json range_json(const sweeps::Range& r) { return json::array({num(r.low), num(r.high)}); }
json stat_json(const sweeps::GroupStatistic& s) {
  return {{"n", s.n},
          {"mean", num(s.mean)},
          {"std", num(s.stddev)},
          {"ci", range_json(s.ci)},
          {"confidence", s.confidence}};
}
const char* group_name(bool fixed) { return fixed ? "fixed" : "free"; }

json case_json(const Case& c) {
  const auto& f = c.fit;
  const auto& e = c.empirical;
  return {{"name", c.scene.name},
          {"scene", c.path},
          {"group", group_name(c.scene.barrier.fixed)},
          {"source", c.source},
          {"mpm",
           {{"peak_force", num(f.mpm.peak_force)},
            {"rise_time", num(f.mpm.rise_time)},
            {"impact_duration", num(f.mpm.impact_duration)},
            {"final_displacement", num(c.mpm.final_displacement)},
            {"samples", c.cal.time.size()},
            {"run_time_s", num(c.mpm_seconds)}}},
          {"analytical",
           {{"lambda", f.lambda},
            {"tau", f.tau},
            {"sigma_lambda", num(f.sigma_lambda)},
            {"sigma_tau", num(f.sigma_tau)},
            {"correlation", num(f.correlation)},
            {"lambda_range", range_json(f.lambda_range)},
            {"tau_range", range_json(f.tau_range)},
            {"misfit", f.misfit},
            {"grid_lambda", f.grid_lambda},
            {"grid_tau", f.grid_tau},
            {"grid_misfit", f.grid_misfit},
            {"iterations", f.iterations},
            {"converged", f.converged},
            {"stop_reason", f.stop_reason},
            {"residuals", f.residual_count}}},
          {"empirical",
           {{"froude", e.froude},
            {"alpha", e.alpha},
            {"tau", e.tau},
            {"sigma_tau", num(e.sigma_tau)},
            {"tau_range", range_json(e.tau_range)},
            {"misfit", e.misfit},
            {"grid_tau", e.grid_tau},
            {"grid_misfit", e.grid_misfit},
            {"iterations", e.iterations},
            {"converged", e.converged}}}};
}

json group_json(const sweeps::GroupSummary& g) {
  const auto& p = g.power_law;
  return {{"group", group_name(g.fixed)},
          {"cases", g.cases},
          {"n", g.cases.size()},
          {"analytical",
           {{"lambda", stat_json(g.lambda)},
            {"tau", stat_json(g.tau)},
            {"paper", {{"lambda", g.paper.lambda}, {"tau", g.paper.tau}}}}},
          {"empirical",
           {{"a1", num(p.a1)},
            {"a1_ci", range_json(p.a1_ci)},
            {"a2", num(p.a2)},
            {"a2_ci", range_json(p.a2_ci)},
            {"rms_log_residual", num(p.rms_log_residual)},
            {"tau", stat_json(g.empirical_tau)},
            {"paper", {{"a1", g.paper.a1}, {"a2", g.paper.a2}, {"tau", g.paper.empirical_tau}}}}}};
}

json row_json(const Row& r) {
  return {{"case", r.case_name},
          {"method", r.method},
          {"coefficients", r.coefficients},
          {"lambda", num(r.lambda)},
          {"tau", num(r.tau)},
          {"a1", num(r.a1)},
          {"a2", num(r.a2)},
          {"empirical_tau", num(r.empirical_tau)},
          {"peak_force", num(r.peak_force)},
          {"peak_force_rel_error", num(r.peak_error)},
          {"impact_duration", num(r.impact_duration)},
          {"impact_duration_rel_error", num(r.duration_error)},
          {"final_displacement", num(r.final_displacement)},
          {"final_displacement_rel_error", num(r.displacement_error)},
          {"run_time_s", num(r.run_time_s)}};
}

std::string fmt(const char* f, double v) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
std::string pct(double e) {
  if (std::isnan(e)) return "-";
  if (std::isinf(e)) return "inf";
  return fmt("%+.0f%%", 100.0 * e);
}
std::string ci(const sweeps::Range& r) {
  return "[" + fmt("%.3f", r.low) + ", " + fmt("%.3f", r.high) + "]";
}
std::string disp(double x) { return std::isinf(x) ? "never" : fmt("%.3f", x); }
std::string run_time(double s) {
  if (std::isnan(s)) return "-";
  return s < 0.1 ? fmt("%.1f us", s * 1e6) : fmt("%.2f s", s);
}

std::string table(const std::vector<Case>& cases, const std::vector<sweeps::GroupSummary>& groups,
                  const std::vector<Row>& rows, const sweeps::CalibrationOptions& o) {
  std::ostringstream t;
  char line[512];
  t << "Calibration of the closed forms against the MPM (objective " << objective_name(o.objective)
    << ", barrier model " << (o.momentum ? "momentum" : "paper") << ", map " << o.lambda_cells
    << " x " << o.tau_cells << " lambda x tau, then Levenberg-Marquardt)\n";
  t << "Analytical model, per case (sigma: linearised, optimistic; range: misfit within "
    << fmt("%.0f", 100 * o.profile_tolerance) << " % of the minimum, at the map's resolution)\n";
  std::snprintf(line, sizeof line, "%-14s %-5s %-7s %-7s %-16s %-7s %-7s %-16s %-9s %-9s %s\n",
                "case", "group", "lambda", "sigma", "range", "tau", "sigma", "range", "misfit",
                "grid", "LM");
  t << line;
  for (const auto& c : cases) {
    const auto& f = c.fit;
    std::snprintf(
        line, sizeof line, "%-14s %-5s %-7s %-7s %-16s %-7s %-7s %-16s %-9s %-9s %d%s\n",
        c.scene.name.c_str(), group_name(c.scene.barrier.fixed), fmt("%.3f", f.lambda).c_str(),
        fmt("%.3f", f.sigma_lambda).c_str(), ci(f.lambda_range).c_str(), fmt("%.3f", f.tau).c_str(),
        fmt("%.3f", f.sigma_tau).c_str(), ci(f.tau_range).c_str(), fmt("%.4f", f.misfit).c_str(),
        fmt("%.4f", f.grid_misfit).c_str(), f.iterations, f.converged ? "" : " (not converged)");
    t << line;
  }
  t << "\nEmpirical model, per case (alpha_MPM = (F_peak,MPM - F_stat) / (rho v_n^2 h))\n";
  std::snprintf(line, sizeof line, "%-14s %-7s %-7s %-7s %-7s %-16s %-9s %s\n", "case", "Fr",
                "alpha", "tau", "sigma", "range", "misfit", "LM");
  t << line;
  for (const auto& c : cases) {
    const auto& e = c.empirical;
    std::snprintf(line, sizeof line, "%-14s %-7s %-7s %-7s %-7s %-16s %-9s %d%s\n",
                  c.scene.name.c_str(), fmt("%.3f", e.froude).c_str(), fmt("%.3f", e.alpha).c_str(),
                  fmt("%.3f", e.tau).c_str(), fmt("%.3f", e.sigma_tau).c_str(),
                  ci(e.tau_range).c_str(), fmt("%.4f", e.misfit).c_str(), e.iterations,
                  e.converged ? "" : " (not converged)");
    t << line;
  }
  t << "\nGroups (mean and " << fmt("%.0f", 100 * confidence)
    << " % Student-t confidence interval; paper: Cuomo et al. 2022, Di Perna et al. 2022)\n";
  for (const auto& g : groups) {
    std::snprintf(line, sizeof line,
                  "%-5s n=%-2zu lambda %s %s (paper %.2f)   tau %s %s (paper %.2f)\n",
                  group_name(g.fixed), g.cases.size(), fmt("%.3f", g.lambda.mean).c_str(),
                  ci(g.lambda.ci).c_str(), g.paper.lambda, fmt("%.3f", g.tau.mean).c_str(),
                  ci(g.tau.ci).c_str(), g.paper.tau);
    t << line;
    std::snprintf(line, sizeof line,
                  "      empirical a1 %s %s (paper %.3f)   a2 %s %s (paper %.3f)   tau %s %s "
                  "(paper %.2f)\n",
                  fmt("%.3f", g.power_law.a1).c_str(), ci(g.power_law.a1_ci).c_str(), g.paper.a1,
                  fmt("%.3f", g.power_law.a2).c_str(), ci(g.power_law.a2_ci).c_str(), g.paper.a2,
                  fmt("%.3f", g.empirical_tau.mean).c_str(), ci(g.empirical_tau.ci).c_str(),
                  g.paper.empirical_tau);
    t << line;
  }
  t << "\nClosed forms against the MPM (relative errors; calibrated = the group's values; "
       "case fit = the case's own)\n";
  std::snprintf(line, sizeof line, "%-14s %-11s %-12s %-15s %-9s %-6s %-9s %-7s %-7s %s\n", "case",
                "method", "coefficients", "parameters", "peak kN/m", "err", "T2 s", "err",
                "displ m", "err   run time");
  t << line;
  for (const auto& r : rows) {
    std::string params = "-";
    if (r.method == "analytical") params = fmt("%.2f", r.lambda) + "/" + fmt("%.2f", r.tau);
    if (r.method == "empirical")
      params = fmt("%.2f", r.a1) + "/" + fmt("%.2f", r.a2) + "/" + fmt("%.2f", r.empirical_tau);
    std::snprintf(line, sizeof line, "%-14s %-11s %-12s %-15s %-9s %-6s %-9s %-7s %-7s %-6s %s\n",
                  r.case_name.c_str(), r.method.c_str(), r.coefficients.c_str(), params.c_str(),
                  fmt("%.1f", r.peak_force / 1e3).c_str(), pct(r.peak_error).c_str(),
                  fmt("%.2f", r.impact_duration).c_str(), pct(r.duration_error).c_str(),
                  disp(r.final_displacement).c_str(), pct(r.displacement_error).c_str(),
                  run_time(r.run_time_s).c_str());
    t << line;
  }
  t << "parameters: analytical lambda/tau, empirical a1/a2/tau. MPM impact duration: last time "
       "the force is more than 10 % of the peak from its final value (model/mpm_runner.cpp).\n";
  return t.str();
}

// ---------------------------------------------------------------------------------------------
// HDF5 output (C API; atomic like io/hdf5_results.cpp).

using H5 = hdf5::Handle;
using hdf5::check;

void attr(hid_t obj, const std::string& name, double v) {
  hdf5::write_double_attribute(obj, name, v);
}
void attr(hid_t obj, const std::string& name, const std::string& v) {
  hdf5::write_string_attribute(obj, name, v);
}

void dataset(hid_t g, const std::string& name, const std::vector<double>& v,
             std::vector<hsize_t> dims = {}) {
  if (dims.empty()) dims = {v.size()};
  H5 space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
           "dataspace " + name);
  H5 d(H5Dcreate2(g, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
       H5Dclose, "dataset " + name);
  if (!v.empty())
    check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          "dataset " + name);
}

void dataset(hid_t g, const std::string& name, const std::vector<std::string>& v) {
  H5 type = hdf5::vlen_string_type();
  const hsize_t n = v.size();
  H5 space(H5Screate_simple(1, &n, nullptr), H5Sclose, "dataspace " + name);
  H5 d(H5Dcreate2(g, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
       "dataset " + name);
  std::vector<const char*> p;
  for (const auto& s : v) p.push_back(s.c_str());
  if (!p.empty())
    check(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()), "dataset " + name);
}

H5 group(hid_t parent, const std::string& name) {
  return H5(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
            "group " + name);
}

std::string link_name(std::string s) {
  for (char& ch : s)
    if (ch == '/' || ch == '.') ch = '_';
  return s.empty() ? "_" : s;
}

void write_stat(hid_t g, const std::string& p, const sweeps::GroupStatistic& s) {
  attr(g, p + "_mean", s.mean);
  attr(g, p + "_std", s.stddev);
  attr(g, p + "_ci_low", s.ci.low);
  attr(g, p + "_ci_high", s.ci.high);
  attr(g, p + "_n", static_cast<double>(s.n));
}

void write_contents(hid_t file, const std::vector<Case>& cases,
                    const std::vector<sweeps::GroupSummary>& groups, const std::vector<Row>& rows,
                    const sweeps::CalibrationOptions& o, const json& report) {
  attr(file, "objective", std::string(objective_name(o.objective)));
  attr(file, "barrier_model", std::string(o.momentum ? "momentum" : "paper"));
  attr(file, "lambda_cells", static_cast<double>(o.lambda_cells));
  attr(file, "tau_cells", static_cast<double>(o.tau_cells));
  attr(file, "profile_tolerance", o.profile_tolerance);
  attr(file, "confidence", confidence);
  attr(file, "lsi_version", std::string(LSI_VERSION));
  attr(file, "report", report.dump(2));
  {
    H5 cg = group(file, "cases");
    for (const auto& c : cases) {
      H5 g = group(cg, link_name(c.scene.name));
      const auto& f = c.fit;
      const auto& e = c.empirical;
      attr(g, "name", c.scene.name);
      attr(g, "group", std::string(group_name(c.scene.barrier.fixed)));
      attr(g, "source", c.source);
      attr(g, "scene", c.scene.source.dump(2));
      const std::pair<const char*, double> scalars[] = {
          {"lambda", f.lambda},
          {"tau", f.tau},
          {"sigma_lambda", f.sigma_lambda},
          {"sigma_tau", f.sigma_tau},
          {"correlation", f.correlation},
          {"lambda_range_low", f.lambda_range.low},
          {"lambda_range_high", f.lambda_range.high},
          {"tau_range_low", f.tau_range.low},
          {"tau_range_high", f.tau_range.high},
          {"misfit", f.misfit},
          {"grid_lambda", f.grid_lambda},
          {"grid_tau", f.grid_tau},
          {"grid_misfit", f.grid_misfit},
          {"iterations", double(f.iterations)},
          {"converged", f.converged ? 1.0 : 0.0},
          {"residuals", double(f.residual_count)},
          {"paper_lambda", sweeps::paper_values(c.scene.barrier.fixed).lambda},
          {"paper_tau", sweeps::paper_values(c.scene.barrier.fixed).tau},
          {"froude", e.froude},
          {"alpha_mpm", e.alpha},
          {"empirical_tau", e.tau},
          {"empirical_sigma_tau", e.sigma_tau},
          {"empirical_tau_range_low", e.tau_range.low},
          {"empirical_tau_range_high", e.tau_range.high},
          {"empirical_misfit", e.misfit},
          {"empirical_iterations", double(e.iterations)},
          {"empirical_converged", e.converged ? 1.0 : 0.0},
          {"mpm_peak_force", f.mpm.peak_force},
          {"mpm_rise_time", f.mpm.rise_time},
          {"mpm_impact_duration", f.mpm.impact_duration},
          {"mpm_final_displacement", c.mpm.final_displacement},
          {"mpm_run_time_s", c.mpm_seconds}};
      for (const auto& [k, v] : scalars) attr(g, k, v);
      dataset(g, "lambda", f.map.lambda);
      dataset(g, "tau", f.map.tau);
      dataset(g, "misfit_map", f.map.misfit, {f.map.lambda.size(), f.map.tau.size()});
      {
        H5 d(H5Dopen2(g, "misfit_map", H5P_DEFAULT), H5Dclose, "misfit_map");
        attr(d, "dims", std::string("lambda,tau"));
        attr(d, "objective", std::string(objective_name(o.objective)));
        attr(d, "description", std::string("misfit[i, j] at lambda[i], tau[j]"));
      }
      dataset(g, "empirical_tau_axis", e.tau_axis);
      dataset(g, "empirical_misfit", e.misfit_profile);
      dataset(g, "mpm_time", c.cal.time);
      dataset(g, "mpm_force", c.cal.force);
    }
  }
  {
    H5 gg = group(file, "groups");
    for (const auto& gs : groups) {
      H5 g = group(gg, group_name(gs.fixed));
      attr(g, "n", static_cast<double>(gs.cases.size()));
      write_stat(g, "lambda", gs.lambda);
      write_stat(g, "tau", gs.tau);
      write_stat(g, "empirical_tau", gs.empirical_tau);
      attr(g, "a1", gs.power_law.a1);
      attr(g, "a1_ci_low", gs.power_law.a1_ci.low);
      attr(g, "a1_ci_high", gs.power_law.a1_ci.high);
      attr(g, "a2", gs.power_law.a2);
      attr(g, "a2_ci_low", gs.power_law.a2_ci.low);
      attr(g, "a2_ci_high", gs.power_law.a2_ci.high);
      attr(g, "paper_lambda", gs.paper.lambda);
      attr(g, "paper_tau", gs.paper.tau);
      attr(g, "paper_a1", gs.paper.a1);
      attr(g, "paper_a2", gs.paper.a2);
      attr(g, "paper_empirical_tau", gs.paper.empirical_tau);
      dataset(g, "cases", gs.cases);
    }
  }
  H5 cmp = group(file, "comparison");
  std::vector<std::string> cs, ms, cos;
  for (const auto& r : rows) {
    cs.push_back(r.case_name);
    ms.push_back(r.method);
    cos.push_back(r.coefficients);
  }
  dataset(cmp, "case", cs);
  dataset(cmp, "method", ms);
  dataset(cmp, "coefficients", cos);
  auto column = [&](const char* name, double Row::*m) {
    std::vector<double> v;
    for (const auto& r : rows) v.push_back(r.*m);
    dataset(cmp, name, v);
  };
  column("lambda", &Row::lambda);
  column("tau", &Row::tau);
  column("a1", &Row::a1);
  column("a2", &Row::a2);
  column("empirical_tau", &Row::empirical_tau);
  column("peak_force", &Row::peak_force);
  column("peak_force_rel_error", &Row::peak_error);
  column("impact_duration", &Row::impact_duration);
  column("impact_duration_rel_error", &Row::duration_error);
  column("final_displacement", &Row::final_displacement);
  column("final_displacement_rel_error", &Row::displacement_error);
  column("run_time_s", &Row::run_time_s);
}

// Atomic (hdf5::write_atomically): `path` is the old file or the complete new one.
void write_calibration(const std::string& path, const std::vector<Case>& cases,
                       const std::vector<sweeps::GroupSummary>& groups,
                       const std::vector<Row>& rows, const sweeps::CalibrationOptions& o,
                       const json& report) {
  hdf5::write_atomically(path, "lsi calibrate", [&](const std::string& tmp) {
    H5 fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file creation properties");
    check(H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
          "link creation order");
    H5 file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT), H5Fclose,
            "cannot create '" + tmp + "'");
    write_contents(file, cases, groups, rows, o, report);
    check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush '" + tmp + "'");
    file.close("close '" + tmp + "'");
  });
}

// ---------------------------------------------------------------------------------------------

int run_calibrate(const Options& opt) {
  const sweeps::CalibrationOptions co = calibration_options(opt);
  if (!opt.out.empty()) check_output_file("--out", opt.out, opt.scenes);
  // Every scene is read and checked, and the stored runs are read, before any MPM runs; then the
  // runs still to make go side by side.
  std::vector<Case> loaded;
  std::vector<MpmSource> source;
  for (const auto& path : opt.scenes) {
    Case c;
    c.path = path;
    c.scene = with_path(path, [&] { return load_scene(path); });
    // The stored run is read from <results-dir>/<name>.h5: the name must stay inside it.
    if (!opt.results_dir.empty()) check_file_name(path + ": name", c.scene.name);
    for (const auto& other : loaded)
      if (other.scene.name == c.scene.name)
        throw InputError(path + ": name = \"" + c.scene.name +
                         "\": must be unique among the "
                         "scenes (also used by " +
                         other.path + ")");
    source.push_back(stored_mpm(c, opt.results_dir));
    loaded.push_back(std::move(c));
  }
  std::vector<std::size_t> to_run;
  for (std::size_t k = 0; k < loaded.size(); ++k)
    if (source[k] == MpmSource::ToRun) to_run.push_back(k);
  std::vector<const Scene*> scenes_to_run;
  for (const std::size_t k : to_run) scenes_to_run.push_back(&loaded[k].scene);
  run_concurrently(
      to_run.size(),
      [&](std::size_t k) {
        source[to_run[k]] = run_mpm(loaded[to_run[k]]) ? MpmSource::Stored : MpmSource::Skipped;
      },
      campaign_runs_that_fit(to_run.size(), scenes_to_run), "calibrate, the MPM runs");
  std::vector<Case> cases;
  bool skipped = false;
  for (std::size_t k = 0; k < loaded.size(); ++k) {
    Case& c = loaded[k];
    const std::string& path = c.path;
    if (source[k] == MpmSource::Skipped) {
      skipped = true;
      continue;
    }
    c.cal.name = c.scene.name;
    c.cal.inputs = impact_inputs(c.scene);
    c.cal.time = c.mpm.time;
    c.cal.force = c.mpm.force;
    c.cal.peak_force = c.mpm.peak_force;
    c.cal.rise_time = c.mpm.rise_time;
    c.cal.impact_duration = c.mpm.impact_duration;
    try {
      c.fit = sweeps::fit_two_body(c.cal, co);
      c.empirical = sweeps::fit_empirical(c.cal, co);
    } catch (const std::invalid_argument& e) {
      throw InputError(path + ": MPM history: " + e.what());
    }
    cases.push_back(std::move(c));
  }

  std::vector<sweeps::GroupSummary> groups;
  for (bool fixed : {true, false}) {
    std::vector<std::string> names;
    std::vector<sweeps::TwoBodyFit> tb;
    std::vector<sweeps::EmpiricalFit> em;
    for (const auto& c : cases)
      if (c.scene.barrier.fixed == fixed) {
        names.push_back(c.scene.name);
        tb.push_back(c.fit);
        em.push_back(c.empirical);
      }
    if (!names.empty()) groups.push_back(sweeps::summarize_group(fixed, names, tb, em, confidence));
  }
  auto group_of = [&](const Case& c) -> const sweeps::GroupSummary& {
    for (const auto& g : groups)
      if (g.fixed == c.scene.barrier.fixed) return g;
    throw std::logic_error("no group");
  };

  std::vector<Row> rows;
  for (const auto& c : cases) {
    const auto& g = group_of(c);
    // The empirical model calibrated for the group: pooled a1, a2 (a2 = 0 and a1 = the geometric
    // mean of alpha_MPM when the group has too few distinct Froude numbers), mean tau.
    double a1 = g.power_law.a1, a2 = g.power_law.a2;
    if (!std::isfinite(a2)) {
      double s = 0.0;
      int n = 0;
      for (const auto& x : cases)
        if (x.scene.barrier.fixed == c.scene.barrier.fixed) s += std::log(x.empirical.alpha), ++n;
      a1 = std::exp(s / n);
      a2 = 0.0;
    }
    const BarrierModel bm = co.momentum ? BarrierModel::Momentum : BarrierModel::Paper;
    rows.push_back(
        closed_form_row(c, "empirical", "default", with_empirical(c.scene, nan, nan, nan, bm)));
    rows.push_back(closed_form_row(c, "empirical", "calibrated",
                                   with_empirical(c.scene, a1, a2, g.empirical_tau.mean, bm)));
    rows.push_back(
        closed_form_row(c, "analytical", "default", with_analytical(c.scene, nan, nan, bm)));
    rows.push_back(closed_form_row(c, "analytical", "calibrated",
                                   with_analytical(c.scene, g.lambda.mean, g.tau.mean, bm)));
    rows.push_back(closed_form_row(c, "analytical", "case fit",
                                   with_analytical(c.scene, c.fit.lambda, c.fit.tau, bm)));
    Row m;
    m.case_name = c.scene.name;
    m.method = "mpm";
    m.coefficients = "-";
    m.peak_force = c.mpm.peak_force;
    m.impact_duration = c.mpm.impact_duration;
    m.final_displacement = c.mpm.final_displacement;
    m.run_time_s = c.mpm_seconds;
    rows.push_back(m);
  }

  json report = {{"objective", objective_name(co.objective)},
                 {"barrier_model", opt.barrier_model},
                 {"grid", {co.lambda_cells, co.tau_cells}},
                 {"profile_tolerance", co.profile_tolerance},
                 {"cases", json::array()},
                 {"groups", json::array()},
                 {"comparison", json::array()}};
  for (const auto& c : cases) report["cases"].push_back(case_json(c));
  for (const auto& g : groups) report["groups"].push_back(group_json(g));
  for (const auto& r : rows) report["comparison"].push_back(row_json(r));

  if (!opt.out.empty()) write_calibration(opt.out, cases, groups, rows, co, report);
  if (opt.format == "json")
    std::cout << report.dump(2) << "\n";
  else
    std::cout << table(cases, groups, rows, co);
  return skipped ? 3 : 0;
}

}  // namespace

Subcommand add_calibrate_command(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  Subcommand s;
  s.command = app.add_subcommand(
      "calibrate",
      "Fit the analytical model's lambda and tau (and the empirical model's a1, a2, tau) to MPM "
      "force histories; compare every closed form with the MPM (docs/theory/calibration.md)");
  s.command->add_option("scenes", opt->scenes, "Scene JSON files (landslide scenes)")->required();
  s.command->add_option("--results-dir", opt->results_dir,
                        "Use DIR/<scene name>.h5 (its /mpm group) where it exists, as written by "
                        "`lsi compare --out-dir DIR` or `lsi run --out`; otherwise run the MPM");
  s.command->add_option("--objective", opt->objective,
                        "nrms (normalised RMS of F(t), default) or peak-duration (peak force, "
                        "impact duration and rise time)");
  s.command->add_option("--grid", opt->grid,
                        "Misfit map size NxM: N lambda cells in (0, 1], M tau cells in (0, 1) "
                        "(default 41x41)");
  s.command->add_option("--out", opt->out,
                        "Write fits, misfit maps and the comparison to this "
                        "HDF5 file (atomically)");
  s.command->add_option("--format", opt->format, "Report format: table or json");
  s.command->add_option("--barrier-model", opt->barrier_model,
                        "How the closed forms move a free barrier: paper (default) or momentum "
                        "(the momentum-consistent barrier; its lambda and tau are fitted to the "
                        "force it receives)");
  s.run = [opt] { return run_calibrate(*opt); };
  return s;
}

}  // namespace lsi
