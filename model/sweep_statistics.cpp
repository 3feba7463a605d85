#include "model/sweep_statistics.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>

#include "model/host_threads.hpp"
#include "sweeps/statistics.hpp"

namespace lsi {
namespace {

using nlohmann::json;

double as_double(const json& v) {
  if (v.is_number()) return v.get<double>();
  const std::string s = v.get<std::string>();
  if (s == "inf") return INFINITY;
  if (s == "-inf") return -INFINITY;
  return NAN;
}

json interval(const sweeps::Interval& i) {
  return json::array({json_number(i.low), json_number(i.high)});
}

const char* design_name(sweeps::Design d) {
  switch (d) {
    case sweeps::Design::MonteCarlo:
      return "monte-carlo";
    case sweeps::Design::LatinHypercube:
      return "latin-hypercube";
    case sweeps::Design::Sobol:
      return "sobol";
    case sweeps::Design::Grid:
      return "grid";
    case sweeps::Design::Points:
      return "points";
  }
  return "?";
}

}  // namespace

json json_number(double v) {
  if (std::isfinite(v)) return v;
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

SweepStatisticsAccumulator::SweepStatisticsAccumulator(
    const Study& study, const std::vector<std::string>& output_columns)
    : study_(study), columns_(output_columns), threshold_of_(output_columns.size()) {
  column_.reserve(columns_.size());
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const std::string& column = columns_[c];
    const std::string method = column.substr(0, column.find('/'));
    const std::string output = column.substr(column.find('/') + 1);
    std::vector<double> above;
    for (std::size_t t = 0; t < study.thresholds.size(); ++t) {
      const StudyThreshold& th = study.thresholds[t];
      if (th.output != output || (!th.method.empty() && th.method != method)) continue;
      threshold_of_[c].push_back(t);
      above.push_back(th.above);
    }
    column_.emplace_back(std::move(above), study.confidence);
  }
}

void SweepStatisticsAccumulator::add(const SweepTable& rows) {
  const std::size_t n = rows.rows();
  const auto is_ok = [&](std::size_t i) {
    return rows.status[i] == static_cast<std::int8_t>(SampleStatus::ok);
  };
  std::size_t ok_count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (is_ok(i))
      ++ok_count;
    else
      ++failed_[describe(static_cast<SampleStatus>(rows.status[i]))];
  }
  rows_ += n;
  ok_ += ok_count;
  const bool all_ok = ok_count == n;
  std::vector<std::size_t> ok;  // the rows of the ok samples, where some failed
  if (!all_ok) {
    ok.reserve(ok_count);
    for (std::size_t i = 0; i < n; ++i)
      if (is_ok(i)) ok.push_back(i);
  }
  // Each column on its own (its ok values in sample order), the columns in parallel.
  const std::size_t columns = columns_.size();
  std::atomic<std::size_t> next{0};
  on_host_threads(std::min(columns, host_thread_count()), [&](std::size_t) {
    std::vector<double> copy;  // the column's ok values, where some failed
    for (std::size_t c; (c = next.fetch_add(1)) < columns;) {
      const std::vector<double>& all = rows.outputs[c];
      if (all_ok) {
        column_[c].add(all.data(), n);
        continue;
      }
      copy.clear();
      for (std::size_t i : ok) copy.push_back(all[i]);
      column_[c].add(copy.data(), copy.size());
    }
  });
}

json SweepStatisticsAccumulator::result(const std::function<const SweepTable&()>& whole_table) {
  const Study& study = study_;
  json j;
  j["design"] = design_name(study.design);
  j["samples_planned"] = study.samples;
  j["samples_done"] = rows_;
  j["samples_ok"] = ok_;
  j["samples_failed"] = failed_;
  j["confidence"] = study.confidence;
  if (study.design != sweeps::Design::MonteCarlo)
    j["note"] =
        "confidence intervals assume independent samples; for Latin-hypercube, Sobol "
        "and grid designs and for given points they are indicative only";
  const std::size_t columns = columns_.size();
  // The whole table, read once, where a column's kept values miss one of its ranks.
  const SweepTable* table = nullptr;
  for (std::size_t c = 0; c < columns && table == nullptr; ++c)
    if (column_[c].invalid_count() == 0 && column_[c].needs_column()) table = &whole_table();
  std::vector<json> column_stats(columns);
  std::vector<json> column_exceed(columns, json::array());
  std::vector<std::exception_ptr> column_error(columns);
  auto describe_column = [&](std::size_t c, sweeps::OrderScratch& scratch) {
    const std::string& column = columns_[c];
    sweeps::ColumnAccumulator& a = column_[c];
    json& o = column_stats[c];
    o["count"] = a.count();
    if (a.count() == 0 || a.invalid_count() > 0) {
      // An ok sample always has a value; a NaN here would be a bug, reported rather than hidden.
      if (a.invalid_count() > 0)
        o["error"] = std::to_string(a.invalid_count()) + " ok samples have no value";
      return;
    }
    for (std::size_t k = 0; k < threshold_of_[c].size(); ++k) {
      const sweeps::ExceedanceEstimate e = a.exceedance(k);
      column_exceed[c].push_back({{"column", column},
                                  {"above", study.thresholds[threshold_of_[c][k]].above},
                                  {"count_above", e.exceed_count},
                                  {"count", e.count},
                                  {"probability", json_number(e.probability)},
                                  {"ci", interval(e.ci)}});
    }
    const auto ok_values = [&]() {
      std::vector<double> v;
      v.reserve(a.count());
      for (std::size_t i = 0; i < table->rows(); ++i)
        if (table->status[i] == static_cast<std::int8_t>(SampleStatus::ok))
          v.push_back(table->outputs[c][i]);
      return v;
    };
    const sweeps::OutputStatistics s = a.describe(ok_values, scratch);
    o["infinite_count"] = s.infinite_count;
    o["mean"] = json_number(s.mean);
    o["mean_ci"] = interval(s.mean_ci);
    o["standard_deviation"] = json_number(s.standard_deviation);
    o["min"] = json_number(s.min);
    o["max"] = json_number(s.max);
    o["q05"] = json_number(s.q05);
    o["q05_ci"] = interval(s.q05_ci);
    o["q50"] = json_number(s.q50);
    o["q50_ci"] = interval(s.q50_ci);
    o["q95"] = json_number(s.q95);
    o["q95_ci"] = interval(s.q95_ci);
  };
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    sweeps::OrderScratch scratch;
    for (std::size_t c; (c = next.fetch_add(1)) < columns;) {
      try {
        describe_column(c, scratch);
      } catch (...) {
        column_error[c] = std::current_exception();
      }
    }
  };
  on_host_threads(std::min(columns, host_thread_count()), [&](std::size_t) { worker(); });
  json outputs = json::object();
  json exceed = json::array();
  for (std::size_t c = 0; c < columns; ++c) {
    if (column_error[c]) std::rethrow_exception(column_error[c]);
    outputs[columns_[c]] = std::move(column_stats[c]);
    for (auto& e : column_exceed[c]) exceed.push_back(std::move(e));
  }
  j["outputs"] = outputs;
  j["exceedance"] = exceed;
  return j;
}

json sweep_statistics(const Study& study, const SweepTable& table) {
  SweepStatisticsAccumulator a(study, table.output_columns);
  a.add(table);
  return a.result([&]() -> const SweepTable& { return table; });
}

std::string sweep_statistics_table(const json& s) {
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s design: %llu of %llu samples done, %llu ok",
                s.value("design", "?").c_str(), s.value("samples_done", 0ull),
                s.value("samples_planned", 0ull), s.value("samples_ok", 0ull));
  out += buf;
  const json failed = s.value("samples_failed", json::object());
  const json outputs = s.value("outputs", json::object());
  const json exceedance = s.value("exceedance", json::array());
  for (const auto& [why, count] : failed.items())
    out += ", " + std::to_string(count.get<unsigned long long>()) + " " + why;
  out += "\n";
  std::snprintf(buf, sizeof buf, "%-30s %12s %21s %12s %12s %12s %12s\n", "output", "mean",
                "mean CI", "sd", "q05", "q50", "q95");
  out += buf;
  for (const auto& [column, o] : outputs.items()) {
    if (o.contains("error") || !o.contains("mean")) {
      out += column + ": " + o.value("error", std::string("no ok samples")) + "\n";
      continue;
    }
    const auto ci = o["mean_ci"];
    std::snprintf(buf, sizeof buf, "%-30s %12.5g [%9.4g, %9.4g] %12.5g %12.5g %12.5g %12.5g\n",
                  column.c_str(), as_double(o["mean"]), as_double(ci[0]), as_double(ci[1]),
                  as_double(o["standard_deviation"]), as_double(o["q05"]), as_double(o["q50"]),
                  as_double(o["q95"]));
    out += buf;
    if (o.value("infinite_count", 0ull) > 0)
      out += "  (" + std::to_string(o["infinite_count"].get<unsigned long long>()) +
             " samples infinite: the barrier never stops)\n";
  }
  for (const auto& e : exceedance) {
    std::snprintf(buf, sizeof buf, "P(%s > %g) = %.5g  [%.4g, %.4g]  (%llu of %llu)\n",
                  e["column"].get<std::string>().c_str(), e["above"].get<double>(),
                  as_double(e["probability"]), as_double(e["ci"][0]), as_double(e["ci"][1]),
                  e["count_above"].get<unsigned long long>(), e["count"].get<unsigned long long>());
    out += buf;
  }
  const double conf = s.value("confidence", 0.95);
  std::snprintf(buf, sizeof buf, "intervals at %.3g %% confidence%s\n", 100 * conf,
                s.contains("note") ? " (indicative only for this design)" : "");
  out += buf;
  return out;
}

bool interval_rule_met(const Study& study, const std::vector<double>& values, std::string& why) {
  const StudyStop& r = study.stop;
  if (!r.has_interval_rule || values.size() < r.min_samples) return false;
  char buf[256];
  if (r.statistic == "mean") {
    for (double v : values)
      if (!std::isfinite(v)) return false;  // an infinite mean has no interval
    const sweeps::OutputStatistics s = sweeps::describe(values, study.confidence);
    const double half = 0.5 * (s.mean_ci.high - s.mean_ci.low);
    if (!(half <= r.relative_half_width * std::fabs(s.mean))) return false;
    std::snprintf(buf, sizeof buf,
                  "confidence interval: mean of %s/%s = %.6g +- %.3g (<= %.3g %% of the mean) "
                  "after %zu ok samples",
                  r.method.c_str(), r.output.c_str(), s.mean, half, 100 * r.relative_half_width,
                  values.size());
  } else {
    const sweeps::ExceedanceEstimate e = sweeps::exceedance(values, r.threshold, study.confidence);
    const double half = 0.5 * (e.ci.high - e.ci.low);
    if (!(half <= r.half_width)) return false;
    std::snprintf(
        buf, sizeof buf,
        "confidence interval: P(%s/%s > %g) = %.6g +- %.3g (<= %.3g) after %zu ok samples",
        r.method.c_str(), r.output.c_str(), r.threshold, e.probability, half, r.half_width,
        values.size());
  }
  why = buf;
  return true;
}

}  // namespace lsi
