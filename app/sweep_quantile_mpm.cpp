#include "app/sweep_quantile_mpm.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "model/concurrent_runs.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "model/sweep_statistics.hpp"
#include "sweeps/statistics.hpp"
#include "io/scene_parser.hpp"
#include "io/study_parser.hpp"

namespace lsi {
namespace {

using nlohmann::json;

int column_index(const SweepTable& t, const std::string& name) {
  for (std::size_t c = 0; c < t.output_columns.size(); ++c)
    if (t.output_columns[c] == name) return static_cast<int>(c);
  return -1;
}

}  // namespace

json mpm_at_quantiles(const Study& study, const SweepTable& t) {
  if (!study.mpm_at_quantiles) return nullptr;
  const StudyQuantileMpm& q = *study.mpm_at_quantiles;
  const int col = column_index(t, q.method + "/" + q.output);
  std::vector<std::size_t> ok;
  std::vector<double> values;
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (t.status[i] == static_cast<std::int8_t>(SampleStatus::ok)) {
      ok.push_back(i);
      values.push_back(t.outputs[col][i]);
    }
  json out = json::array();
  if (values.empty()) return out;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  // The samples nearest each quantile, then their MPM runs side by side
  // (model/concurrent_runs.hpp), each into its own entry.
  std::vector<std::vector<double>> xs;
  std::vector<std::size_t> rows;
  for (double p : q.quantiles) {
    const double target = sweeps::quantile_type7(sorted, p);
    std::size_t best = 0;
    for (std::size_t k = 1; k < values.size(); ++k)
      if (std::fabs(values[k] - target) < std::fabs(values[best] - target)) best = k;
    const std::size_t row = ok[best];
    json e = {{"quantile", p},
              {"quantile_value", json_number(target)},
              {"column", q.method + "/" + q.output},
              {"sample", t.index[row]}};
    std::vector<double> x;
    json inputs = json::object();
    for (std::size_t d = 0; d < t.input_paths.size(); ++d) {
      x.push_back(t.inputs[d][row]);
      inputs[t.input_paths[d]] = t.inputs[d][row];
    }
    e["inputs"] = inputs;
    json closed = json::object();
    for (std::size_t c = 0; c < t.output_columns.size(); ++c)
      if (t.output_columns[c].rfind("mpm/", 0) != 0)
        closed[t.output_columns[c]] = json_number(t.outputs[c][row]);
    e["closed_form"] = closed;
    out.push_back(e);
    xs.push_back(std::move(x));
    rows.push_back(row);
  }
  run_concurrently(xs.size(), [&](std::size_t k) {
    json& e = out[k];
    const std::size_t row = rows[k];
    const auto t0 = std::chrono::steady_clock::now();
    try {
      const MpmOutcome o =
          run_mpm_case(impact_case(parse_scene(sample_scene_document(study, xs[k].data()))));
      e["mpm_status"] = o.status();
      e["mpm_end_state"] = end_state_token(o.result.end_state);  // at_rest, or how it was cut short
      json mpm = json::object(), errors = json::object();
      for (const auto& output : study.outputs)
        mpm[output] = json_number(scalar_by_name(o.result, output));
      if (o.finished()) {
        for (std::size_t c = 0; c < t.output_columns.size(); ++c) {
          const std::string& name = t.output_columns[c];
          if (name.rfind("mpm/", 0) == 0) continue;
          const double m = scalar_by_name(o.result, name.substr(name.find('/') + 1));
          const double v = t.outputs[c][row];
          errors[name] = (std::isfinite(m) && m != 0.0 && std::isfinite(v))
                             ? json_number((v - m) / m)
                             : json(nullptr);
        }
      }
      e["mpm"] = mpm;
      e["relative_error"] = errors;
    } catch (const std::exception& ex) {
      e["mpm_status"] = std::string("failed: ") + ex.what();
    }
    e["mpm_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
  return out;
}

std::string mpm_at_quantiles_table(const json& j) {
  std::string s;
  if (!j.is_array() || j.empty()) return s;
  char buf[512];
  s += "MPM at quantiles of " + j[0]["column"].get<std::string>() + ":\n";
  for (const auto& e : j) {
    std::snprintf(buf, sizeof buf, "  q = %.3g (sample %llu, %.1f s): %s\n",
                  e["quantile"].get<double>(), e["sample"].get<unsigned long long>(),
                  e["mpm_seconds"].get<double>(), e["mpm_status"].get<std::string>().c_str());
    s += buf;
    if (!e.contains("relative_error")) continue;
    for (const auto& [name, err] : e["relative_error"].items()) {
      const std::string output = name.substr(name.find('/') + 1);
      const json& cf = e["closed_form"][name];
      const json& m = e["mpm"][output];
      if (!cf.is_number() || !m.is_number() || !err.is_number()) {
        s += "    " + name + ": " + cf.dump() + " vs MPM " + m.dump() + "\n";
        continue;
      }
      std::snprintf(buf, sizeof buf, "    %-30s %12.5g vs MPM %12.5g  (%+.1f %%)\n", name.c_str(),
                    cf.get<double>(), m.get<double>(), 100 * err.get<double>());
      s += buf;
    }
  }
  return s;
}

}  // namespace lsi
