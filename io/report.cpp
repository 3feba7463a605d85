#include "io/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace lsi {
namespace {

// JSON has no infinity or NaN: infinity (a barrier that never stops) becomes null; NaN (not
// given by this method) leaves the key out.
void put(nlohmann::json& j, const std::string& key, double v) {
  if (std::isnan(v)) return;
  j[key] = std::isinf(v) ? nlohmann::json(nullptr) : nlohmann::json(v);
}

std::string fmt(double v, const char* format = "%.3g") {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return "never stops";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// A safety factor: "inf" where no load of the history can make the barrier slide or tip.
std::string fmt_safety(double v) { return std::isinf(v) ? "inf" : fmt(v, "%.2f"); }

std::string pad(const std::string& s, size_t width) {
  return s.size() >= width ? s + " " : s + std::string(width - s.size(), ' ');
}

double scalar_or_nan(const std::optional<double>& v) { return v.value_or(std::nan("")); }
double end_time_or_nan(const MethodResult& r) { return r.run ? r.run->end_time : std::nan(""); }

// The final displacement as a table cell: the number where it is one; ">=" the displacement at
// the end where the run was cut short while the barrier still slid; "unstable".
std::string displacement_cell(const MethodResult& r) {
  switch (r.end_state) {
    case EndState::EndTimeBarrierSliding:
    case EndState::BarrierLeftDomain:
      return ">=" + fmt(scalar_or_nan(r.scalars.displacement_at_end), "%.3f");
    case EndState::Unstable:
      return "unstable";
    default:
      return fmt(r.final_displacement, "%.3f");
  }
}

// What a table must say about how a run ended, or "" (at rest, or not a run).
std::string end_note(const MethodResult& r) {
  const std::string t = fmt(end_time_or_nan(r), "%.3g");
  const std::string d = fmt(scalar_or_nan(r.scalars.displacement_at_end), "%.3g");
  switch (r.end_state) {
    case EndState::EndTimeBarrierSliding:
      return "the barrier was still sliding at t = " + t + " s (>= " + d +
             " m): the run reached its end time (final displacement not known)";
    case EndState::BarrierLeftDomain:
      return "the barrier was still sliding at t = " + t + " s (>= " + d +
             " m) when it reached the downstream end of the modelled domain (final "
             "displacement not known)";
    case EndState::EndTimeLandslideMoving:
      return "the landslide was still moving at t = " + t +
             " s, the end time (the barrier at rest, displaced " + d + " m so far)";
    case EndState::Unstable:
      return "stopped unstable at t = " + t + " s: " + r.status;
    default:
      return "";
  }
}

}  // namespace

nlohmann::json summary_json(const std::vector<MethodResult>& results) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& r : results) {
    nlohmann::json m = nlohmann::json::object();
    put(m, "peak_force", r.peak_force);
    put(m, "rise_time", r.rise_time);
    put(m, "impact_duration", r.impact_duration);
    put(m, "final_displacement", r.final_displacement);
    for (const auto& [k, v] : named_scalars(r)) put(m, k, v);
    if (r.end_state != EndState::None) m["end_state"] = end_state_token(r.end_state);
    if (!r.status.empty()) m["status"] = r.status;
    if (!r.barrier_model.empty()) m["barrier_model"] = r.barrier_model;
    j[r.method] = m;
  }
  return j;
}

std::string summary_table(const Scene& scene, const std::vector<MethodResult>& results) {
  std::ostringstream o;
  o << "scene " << scene.name << ": landslide " << fmt(scene.landslide.mass_kg_per_m(), "%.0f")
    << " kg/m at " << fmt(scene.landslide.velocity_m_s) << " m/s; barrier "
    << fmt(scene.barrier.mass(), "%.0f") << " kg/m, "
    << (scene.barrier.fixed ? "fixed" : "free on its base") << ", face "
    << fmt(scene.barrier.face_angle_deg) << " deg\n";
  o << pad("method", 12) << pad("peak force", 13) << pad("rise time", 11)
    << pad("impact duration", 17) << "final displacement\n";
  o << pad("", 12) << pad("[kN/m]", 13) << pad("[s]", 11) << pad("[s]", 17) << "[m]\n";
  for (const auto& r : results) {
    o << pad(r.method, 12) << pad(fmt(r.peak_force / 1e3, "%.1f"), 13)
      << pad(fmt(r.rise_time, "%.3f"), 11) << pad(fmt(r.impact_duration, "%.3f"), 17)
      << displacement_cell(r) << "\n";
  }
  for (const auto& r : results) {
    const std::string note = end_note(r);
    if (!note.empty()) o << r.method << ": " << note << "\n";
  }
  // The MPM's volumes (the closed forms have none): what went over the crest, and how much of
  // that is the grid contact's leak into the barrier (docs/theory/two_phase.md).
  for (const auto& r : results) {
    const auto& over = r.scalars.overtopped_volume_m2;
    const auto& kept = r.scalars.retained_volume_m2;
    if (!over || !kept) continue;
    const double total = *over + *kept;
    o << r.method << ": overtopped " << fmt(*over, "%.2f") << " m^2/m ("
      << fmt(total > 0.0 ? 100.0 * *over / total : 0.0, "%.1f") << " % of the landslide";
    const auto& leak = r.scalars.overtopped_inside_barrier_m2;
    if (leak && *leak > 0.0)
      o << "; " << fmt(*leak, "%.2f") << " of it inside the barrier, the contact's leak";
    o << "), retained " << fmt(*kept, "%.2f") << " m^2/m\n";
  }
  return o.str();
}

namespace {
const DesignCheck* check_of(const std::vector<DesignCheck>& checks, const std::string& method) {
  for (const auto& c : checks)
    if (c.method == method) return &c;
  return nullptr;
}

nlohmann::json check_json(const DesignCheck& c) {
  if (!c.skipped.empty()) return {{"skipped", c.skipped}};
  nlohmann::json j = {{"barrier",
                       {{"height", c.barrier.height_m},
                        {"base_width", c.barrier.base_width_m},
                        {"top_width", c.barrier.top_width_m},
                        {"mass", c.barrier.mass()}}},
                      {"within_tolerance", c.within},
                      {"end_state", end_state_token(c.mpm.end_state)}};
  put(j, "final_displacement", c.mpm.final_displacement);
  put(j, "displacement_at_end", scalar_or_nan(c.mpm.scalars.displacement_at_end));
  put(j, "peak_force", c.mpm.peak_force);
  put(j, "min_sliding_safety", scalar_or_nan(c.mpm.scalars.min_sliding_safety));
  put(j, "min_overturning_safety", scalar_or_nan(c.mpm.scalars.min_overturning_safety));
  put(j, "overturning_resultant_height", scalar_or_nan(c.mpm.scalars.overturning_resultant_height));
  put(j, "solver_seconds", (c.mpm.run ? c.mpm.run->solver_seconds : std::nan("")));
  return j;
}
}  // namespace

nlohmann::json design_json(const std::vector<MassDesign>& designs, double max_displacement_m,
                           const std::vector<DesignCheck>& checks) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& d : designs) {
    nlohmann::json m = {{"status", d.status}, {"max_displacement", max_displacement_m}};
    put(m, "barrier_mass", d.mass_kg_per_m);
    put(m, "final_displacement", d.displacement_m);
    m["geometries"] = nlohmann::json::array();
    for (const auto& g : d.geometries) {
      nlohmann::json gj = {
          {"height", g.height_m}, {"base_width", g.base_width_m}, {"top_width", g.top_width_m}};
      put(gj, "min_overturning_safety", g.min_overturning_safety);
      m["geometries"].push_back(gj);
    }
    if (const DesignCheck* c = check_of(checks, d.method)) m["mpm_check"] = check_json(*c);
    j[d.method] = m;
  }
  return j;
}

std::string design_table(const Scene& scene, const std::vector<MassDesign>& designs,
                         double max_displacement_m, const std::vector<DesignCheck>& checks) {
  std::ostringstream o;
  o << "scene " << scene.name
    << ": minimum barrier mass for a final displacement <= " << fmt(max_displacement_m)
    << " m (current barrier: " << fmt(scene.barrier.mass(), "%.0f") << " kg/m)\n";
  for (const auto& d : designs) {
    o << "  " << pad(d.method, 11);
    if (d.status == "found") {
      o << fmt(d.mass_kg_per_m, "%.0f") << " kg/m (displacement " << fmt(d.displacement_m, "%.3f")
        << " m)\n";
      for (const auto& g : d.geometries)
        o << "      H = " << fmt(g.height_m, "%.2f") << " m, B = " << fmt(g.base_width_m, "%.2f")
          << " m, b = " << fmt(g.top_width_m, "%.2f") << " m; overturning safety factor "
          << fmt_safety(g.min_overturning_safety) << "\n";
      if (const DesignCheck* c = check_of(checks, d.method); c && !c->skipped.empty()) {
        o << "      MPM check not run: " << c->skipped << "\n";
      } else if (c) {
        const std::string note = end_note(c->mpm);
        o << "      MPM check (H = " << fmt(c->barrier.height_m, "%.2f")
          << " m, B = " << fmt(c->barrier.base_width_m, "%.2f")
          << " m, b = " << fmt(c->barrier.top_width_m, "%.2f") << " m): displacement "
          << displacement_cell(c->mpm) << " m against " << fmt(max_displacement_m)
          << " m: " << (c->within ? "within" : "NOT within")
          << " the tolerance; safety under the MPM's loads: sliding "
          << fmt_safety(scalar_or_nan(c->mpm.scalars.min_sliding_safety)) << ", overturning "
          << fmt_safety(scalar_or_nan(c->mpm.scalars.min_overturning_safety)) << " (resultant at "
          << fmt(scalar_or_nan(c->mpm.scalars.overturning_resultant_height), "%.2f") << " m)"
          << (note.empty() ? "" : "; " + note) << "\n";
      }
    } else {
      o << d.status << "\n";
    }
  }
  return o.str();
}

namespace {
const MethodResult* find(const std::vector<MethodResult>& rs, const std::string& m) {
  for (const auto& r : rs)
    if (r.method == m) return &r;
  return nullptr;
}
const MassDesign* find(const std::vector<MassDesign>& ds, const std::string& m) {
  for (const auto& d : ds)
    if (d.method == m) return &d;
  return nullptr;
}
}  // namespace

namespace {
// An MPM value with its error bar where a convergence study gave one (`<key>_spread`,
// `<key>_converged`: io/convergence_file.hpp): "value+-spread", "*" when not converged.
std::string with_spread(const MethodResult& r, const std::string& key, const std::string& value,
                        double scale, const char* format) {
  if (!r.convergence || value == "-") return value;
  const auto bar = r.convergence->outputs.find(key);
  if (bar == r.convergence->outputs.end()) return value;
  return value + "+-" + fmt(bar->second.spread / scale, format) +
         (bar->second.converged ? "" : "*");
}

bool has_spreads(const std::vector<ComparisonRow>& rows) {
  for (const auto& row : rows)
    for (const auto& r : row.results)
      if (r.convergence && r.convergence->outputs.count("peak_force")) return true;
  return false;
}

struct MpmColumn {
  const char* key;
  const char* head;
  double scale;
  const char* format;
};
// The MPM outputs with error bars, in the order of the convergence study.
constexpr MpmColumn kMpmColumns[] = {
    {"peak_force", "peak [kN/m]", 1e3, "%.1f"},
    {"peak_force_windowed", "peak, window [kN/m]", 1e3, "%.1f"},
    {"impulse", "impulse [kN s/m]", 1e3, "%.1f"},
    {"impact_duration", "duration [s]", 1, "%.2f"},
    {"final_displacement", "displacement [m]", 1, "%.3f"},
    {"overtopped_volume_m2", "overtopped [m^2]", 1, "%.2f"},
    {"retained_volume_m2", "retained [m^2]", 1, "%.2f"},
    {"face_pore_pressure_max_pa", "face pore p. [kPa]", 1e3, "%.0f"},
};

}  // namespace

std::string comparison_table(const std::vector<ComparisonRow>& rows, double max_displacement_m) {
  // Columns: E = empirical, A = analytical, M = MPM (when any row ran it).
  bool mpm = false;
  for (const auto& row : rows) mpm = mpm || find(row.results, "mpm");
  const bool bars = has_spreads(rows);
  std::vector<const char*> methods = {"empirical", "analytical"};
  if (mpm) methods.push_back("mpm");
  const size_t w = 9, wm = bars ? 17 : 9;
  size_t case_w = 8;
  for (const auto& row : rows) case_w = std::max(case_w, row.scene.size() + 1);
  const std::string heads = pad("E", w) + pad("A", w) + (mpm ? pad("M", wm) : "");
  const size_t group = 2 * w + (mpm ? wm : 0) + 2;
  auto width = [&](const char* m) { return std::string(m) == "mpm" ? wm : w; };
  std::ostringstream o;
  o << "Comparison of the design methods (E: empirical, A: analytical" << (mpm ? ", M: MPM" : "")
    << "); forces normal to the face\n";
  std::vector<std::string> checked;  // methods whose designs the MPM checked, in table order
  for (const char* m : {"empirical", "analytical"})
    for (const auto& row : rows)
      if (check_of(row.checks, m)) {
        checked.push_back(m);
        break;
      }
  o << pad("case", case_w) << pad("peak force [kN/m]", group) << pad("impact period [s]", group)
    << pad("final displ. [m]", group) << "mass for " << fmt(max_displacement_m) << " m [t/m]"
    << (checked.empty() ? "" : "   M displ. at that mass [m]") << "\n";
  o << pad("", case_w) << pad(heads, group) << pad(heads, group) << pad(heads, group)
    << "E        A        ";
  for (const auto& m : checked) o << pad(m == "empirical" ? "E's" : "A's", 10);
  o << "\n";
  for (const auto& row : rows) {
    auto cols = [&](const std::string& key, const char* format, double scale) {
      std::string out;
      for (const char* m : methods) {
        const MethodResult* r = find(row.results, m);
        std::string cell = r ? fmt(scalar_by_name(*r, key) / scale, format) : "-";
        if (r && key == "final_displacement") cell = displacement_cell(*r);
        if (r) cell = with_spread(*r, key, cell, scale, format);
        out += pad(cell, width(m));
      }
      return pad(out, group);
    };
    o << pad(row.scene, case_w) << cols("peak_force", "%.1f", 1e3)
      << cols("impact_duration", "%.2f", 1) << cols("final_displacement", "%.3f", 1);
    for (const char* m : {"empirical", "analytical"}) {
      const MassDesign* d = find(row.designs, m);
      o << pad(!d                              ? "-"
               : d->status == "found"          ? fmt(d->mass_kg_per_m / 1e3, "%.1f")
               : d->status == "any mass works" ? "any"
                                               : "none",
               9);
    }
    for (const auto& m : checked) {
      const DesignCheck* c = check_of(row.checks, m);
      o << pad(c && c->skipped.empty() ? displacement_cell(c->mpm) : "-", 10);
    }
    o << "\n";
  }
  // How each closed form moved the barrier (the barrier model of its results).
  auto model_of = [&](const char* m) {
    std::string model;
    for (const auto& row : rows)
      if (const MethodResult* r = find(row.results, m); r && !r->barrier_model.empty())
        model = model.empty() || model == r->barrier_model ? r->barrier_model : "mixed";
    return model;
  };
  auto described = [](const std::string& model, const char* paper) {
    return model == "momentum" ? std::string(
                                     "the barrier pushed by the flow at their relative "
                                     "velocity (momentum-consistent)")
           : model == "mixed" ? std::string("paper and momentum-consistent, by scene")
                              : std::string(paper);
  };
  o << "E displacement: "
    << described(model_of("empirical"),
                 "rigid-block sliding under the empirical (fixed-barrier) pulse")
    << "; A: " << described(model_of("analytical"), "the two-body model")
    << "; M: the MPM (docs/theory/mpm.md). \"any\": no mass exceeds the tolerance (docs/theory/models.md).\n";
  if (!checked.empty())
    o << "M displ. at that mass: the MPM on the barrier of that minimum mass (the scene's height, "
         "top width and face angle; the base width from the mass).\n";
  for (const auto& row : rows)
    for (const auto& r : row.results) {
      const std::string note = end_note(r);
      if (!note.empty()) o << row.scene << " " << r.method << ": " << note << "\n";
    }
  if (bars) {
    double cells = 0, courant = 0;
    for (const auto& row : rows)
      if (const MethodResult* r = find(row.results, "mpm"); r && r->convergence) {
        cells = r->convergence->finer_cells;
        courant = r->convergence->finer_courant;
      }
    o << "\nMPM outputs +- their spread in the convergence study (the larger change to "
      << fmt(cells, "%.0f") << " cells through the thickness or to Courant " << fmt(courant)
      << "; * not converged: the spread above 10 % of the value and above the output's floor)\n";
    o << pad("case", case_w);
    for (const auto& c : kMpmColumns) o << pad(c.head, 20);
    o << "\n";
    for (const auto& row : rows) {
      const MethodResult* r = find(row.results, "mpm");
      if (!r) continue;
      o << pad(row.scene, case_w);
      for (const auto& c : kMpmColumns) {
        std::string cell = fmt(scalar_by_name(*r, c.key) / c.scale, c.format);
        if (std::string(c.key) == "final_displacement") cell = displacement_cell(*r);
        o << pad(with_spread(*r, c.key, cell, c.scale, c.format), 20);
      }
      o << "\n";
    }
  }
  if (mpm) {
    o << "MPM run time per case [s]:";
    for (const auto& row : rows) {
      const MethodResult* r = find(row.results, "mpm");
      double seconds = std::nan("");
      if (r && r->run) seconds = r->run->solver_seconds;
      o << " " << row.scene << " " << fmt(seconds, "%.3g");
    }
    o << "\n";
  }
  return o.str();
}

nlohmann::json comparison_json(const std::vector<ComparisonRow>& rows, double max_displacement_m) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& row : rows) {
    j[row.scene] = {{"results", summary_json(row.results)},
                    {"design", design_json(row.designs, max_displacement_m, row.checks)}};
  }
  return j;
}

}  // namespace lsi
