// The statistics of a sweep's table (model/sweep_statistics.hpp): each output column described
// from its ok samples.
#include "model/sweep_statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "io/study_parser.hpp"
#include "sweeps/statistics.hpp"

namespace {

lsi::Study two_output_study() {
  const nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "statistics",
    "scene": {
      "name": "s",
      "landslide": {"thickness_m": 1.0, "velocity_m_s": 5, "density_kg_m3": 1800,
                    "shape": {"kind": "front-body-tail", "body_squares": 3}},
      "barrier": {"height_m": 2.0, "base_width_m": 2.0, "top_width_m": 1.0,
                  "face_angle_deg": 80, "density_kg_m3": 2400},
      "methods": {"empirical": {}, "analytical": {}}
    },
    "inputs": [{"path": "/landslide/velocity_m_s", "distribution": "uniform", "min": 5,
                "max": 15}],
    "samples": 4000,
    "seed": 1,
    "methods": ["empirical", "analytical"],
    "outputs": ["peak_force", "final_displacement"],
    "thresholds": [{"output": "peak_force", "above": 2.0e5}]
  })");
  return lsi::parse_study(doc, "");
}

// A results-only table of n rows in an order far from sorted (a multiplicative permutation),
// the samples in `failed` with status 3 and no values; one value of the last column infinite.
lsi::SweepTable table_of(const lsi::Study& study, std::size_t n,
                         const std::vector<std::size_t>& failed) {
  lsi::SweepTable t = lsi::SweepTable::with_columns({}, study.output_columns());
  for (std::size_t i = 0; i < n; ++i) {
    const bool fails = std::find(failed.begin(), failed.end(), i) != failed.end();
    t.index.push_back(i);
    t.status.push_back(fails ? 3 : 0);
    for (std::size_t c = 0; c < t.output_columns.size(); ++c)
      t.outputs[c].push_back(fails ? std::nan("") : 1.0e5 * (c + 1) + 37.0 * ((i * 7919) % n));
  }
  t.outputs.back()[n / 2] = INFINITY;
  return t;
}

// Each column's record is describe() of its ok values in sample order, and its order statistics
// those of the ok values sorted (std::sort, read at the ranks describe() reads): exactly, both
// where every sample is ok and where some failed.
TEST(SweepStatistics, EachColumnDescribesItsOkValues) {
  const lsi::Study study = two_output_study();
  const std::size_t n = 6000;  // above the 4096 values that describe() selects among directly
  ASSERT_EQ(study.output_columns().size(), 4u);
  for (const std::vector<std::size_t>& failed :
       {std::vector<std::size_t>{}, std::vector<std::size_t>{3, 1000, 5999}}) {
    const lsi::SweepTable t = table_of(study, n, failed);
    const nlohmann::json got = lsi::sweep_statistics(study, t);
    EXPECT_EQ(got["samples_ok"], n - failed.size());
    for (std::size_t c = 0; c < t.outputs.size(); ++c) {
      std::vector<double> ok;
      for (std::size_t i = 0; i < n; ++i)
        if (t.status[i] == 0) ok.push_back(t.outputs[c][i]);
      const lsi::sweeps::OutputStatistics s = lsi::sweeps::describe(ok, study.confidence);
      const nlohmann::json& o = got["outputs"][t.output_columns[c]];
      EXPECT_EQ(o["count"], ok.size());
      EXPECT_EQ(o["mean"], lsi::json_number(s.mean)) << c;
      EXPECT_EQ(o["standard_deviation"], lsi::json_number(s.standard_deviation)) << c;
      std::vector<double> sorted = ok;
      std::sort(sorted.begin(), sorted.end());
      EXPECT_EQ(o["min"], lsi::json_number(sorted.front())) << c;
      EXPECT_EQ(o["max"], lsi::json_number(sorted.back())) << c;
      const std::pair<const char*, double> quantiles[] = {
          {"q05", 0.05}, {"q50", 0.5}, {"q95", 0.95}};
      for (const auto& [name, q] : quantiles) {
        EXPECT_EQ(o[name], lsi::json_number(lsi::sweeps::quantile_type7(sorted, q))) << c << name;
        const auto r = lsi::sweeps::order_statistic_ranks(sorted.size(), q, study.confidence);
        ASSERT_GE(r.lower, 1);
        ASSERT_LE(r.upper, static_cast<long long>(sorted.size()));
        const nlohmann::json ci = {lsi::json_number(sorted[std::size_t(r.lower - 1)]),
                                   lsi::json_number(sorted[std::size_t(r.upper - 1)])};
        EXPECT_EQ(o[std::string(name) + "_ci"], ci) << c << name;
      }
    }
  }
}

// Rows [from, from + count) of t (statuses and outputs).
lsi::SweepTable rows_of(const lsi::SweepTable& t, std::size_t from, std::size_t count) {
  lsi::SweepTable r = lsi::SweepTable::with_columns(t.input_paths, t.output_columns);
  const auto at = [&](const auto& v) {
    return std::vector<typename std::decay_t<decltype(v)>::value_type>(
        v.begin() + std::ptrdiff_t(from), v.begin() + std::ptrdiff_t(from + count));
  };
  r.index = at(t.index);
  r.status = at(t.status);
  for (std::size_t c = 0; c < t.outputs.size(); ++c) r.outputs[c] = at(t.outputs[c]);
  return r;
}

// The statistics of rows added a chunk at a time are those of the whole table, bit for bit
// (JSON equality), and the table is asked for only where the values came in order.
TEST(SweepStatistics, RowsAddedAChunkAtATimeGiveTheWholeTablesStatistics) {
  const lsi::Study study = two_output_study();
  // 6000 rows: fewer than the accumulator's first values (described whole); 300000 rows in the
  // order of table_of (a permutation: ranges set from the first values), then ascending (the
  // table read back once).
  struct Case {
    std::size_t n, chunk;
    bool ascending;
    int asked;
  };
  for (const Case k :
       {Case{6000, 700, false, 0}, Case{300000, 40000, false, 0}, Case{300000, 40000, true, 1}}) {
    lsi::SweepTable t = table_of(study, k.n, {3, 1000, 5999});
    if (k.ascending)
      for (std::size_t c = 0; c < t.outputs.size(); ++c)
        for (std::size_t i = 0; i < k.n; ++i)
          if (t.status[i] == 0) t.outputs[c][i] = 10.0 * double(c + 1) + double(i);
    lsi::SweepStatisticsAccumulator a(study, t.output_columns);
    for (std::size_t from = 0; from < k.n; from += k.chunk)
      a.add(rows_of(t, from, std::min(k.chunk, k.n - from)));
    int asked = 0;
    const nlohmann::json got = a.result([&]() -> const lsi::SweepTable& {
      ++asked;
      return t;
    });
    EXPECT_EQ(asked, k.asked) << k.n;
    EXPECT_EQ(got, lsi::sweep_statistics(study, t)) << k.n;
    EXPECT_EQ(got["samples_failed"]["failed"], 3) << got.dump();
  }
}

}  // namespace
