// The statistics of a sweep's table (model/sweep_statistics.hpp): sweep_statistics_sorting, which
// may sort the table's output columns in place, gives sweep_statistics' record exactly, and
// touches the table only where every sample is ok.
#include "model/sweep_statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "io/study_parser.hpp"

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

TEST(SweepStatistics, SortingInPlaceGivesTheSameRecordAndSortsOnlyWhereAllAreOk) {
  const lsi::Study study = two_output_study();
  const std::size_t n = 4000;
  ASSERT_EQ(study.output_columns().size(), 4u);
  // Every sample ok: the same record (both describe the same values in sorted order), and each
  // output column left sorted: the sorted permutation of what it held.
  {
    const lsi::SweepTable original = table_of(study, n, {});
    lsi::SweepTable sorted = original;
    const nlohmann::json want = lsi::sweep_statistics(study, original);
    const nlohmann::json got = lsi::sweep_statistics_sorting(study, sorted);
    EXPECT_EQ(got, want);
    EXPECT_EQ(got["samples_ok"], n);
    for (std::size_t c = 0; c < original.outputs.size(); ++c) {
      EXPECT_TRUE(std::is_sorted(sorted.outputs[c].begin(), sorted.outputs[c].end())) << c;
      std::vector<double> expected = original.outputs[c];
      std::sort(expected.begin(), expected.end());
      EXPECT_EQ(sorted.outputs[c], expected) << c;
    }
    EXPECT_EQ(sorted.index, original.index);
    EXPECT_EQ(sorted.status, original.status);
  }
  // Some failed: the same record, and the table untouched (the ok values are copied out).
  {
    const lsi::SweepTable original = table_of(study, n, {3, 1000, 3999});
    lsi::SweepTable kept = original;
    const nlohmann::json want = lsi::sweep_statistics(study, original);
    const nlohmann::json got = lsi::sweep_statistics_sorting(study, kept);
    EXPECT_EQ(got, want);
    EXPECT_EQ(got["samples_ok"], n - 3);
    for (std::size_t c = 0; c < original.outputs.size(); ++c)
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_TRUE(kept.outputs[c][i] == original.outputs[c][i] ||
                    (std::isnan(kept.outputs[c][i]) && std::isnan(original.outputs[c][i])))
            << c << " " << i;
  }
}

}  // namespace
