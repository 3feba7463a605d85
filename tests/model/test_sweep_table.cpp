// The per-sample table of a sweep (model/sweep_table.hpp): whole rows appended and sorted by
// sample index, a duplicate refused, and the statistics' table of statuses and outputs alone.
#include "model/sweep_table.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace {

// Rows of samples `first`, `first` + 1, ...: status 0 but sample 2 (failed), inputs and outputs
// that name their sample.
lsi::SweepTable rows(std::uint64_t first, std::size_t count) {
  lsi::SweepTable t =
      lsi::SweepTable::with_columns({"/landslide/thickness_m"}, {"analytical/peak_force"});
  for (std::uint64_t i = first; i < first + count; ++i) {
    t.index.push_back(i);
    t.status.push_back(i == 2 ? 3 : 0);
    t.wall_time.push_back(0.5f);
    t.inputs[0].push_back(10.0 + double(i));
    t.outputs[0].push_back(100.0 + double(i));
    if (i == 2) {
      t.failure_index.push_back(i);
      t.failure_reason.push_back("failed");
    }
  }
  return t;
}

}  // namespace

TEST(SweepTable, WholeRowsAppendAndSortBySampleIndex) {
  lsi::SweepTable t =
      lsi::SweepTable::with_columns({"/landslide/thickness_m"}, {"analytical/peak_force"});
  t.append(rows(4, 3));
  t.append(rows(0, 4));
  ASSERT_EQ(t.rows(), 7u);
  t.sort_by_index();
  for (std::uint64_t i = 0; i < 7; ++i) {
    EXPECT_EQ(t.index[i], i);
    EXPECT_EQ(t.inputs[0][i], 10.0 + double(i));
    EXPECT_EQ(t.outputs[0][i], 100.0 + double(i));
    EXPECT_EQ(t.status[i], i == 2 ? 3 : 0);
  }
  t.append(rows(5, 1));
  EXPECT_THROW(t.sort_by_index(), std::runtime_error) << "sample 5 twice";
}

TEST(SweepTable, ResultsAloneKeepStatusesOutputsAndFailuresInTheOrderAppended) {
  lsi::SweepTable t =
      lsi::SweepTable::with_columns({"/landslide/thickness_m"}, {"analytical/peak_force"});
  t.append_results(rows(0, 3));
  t.append_results(rows(3, 2));
  ASSERT_EQ(t.rows(), 5u) << "a row per status";
  EXPECT_TRUE(t.index.empty());
  EXPECT_TRUE(t.wall_time.empty());
  EXPECT_TRUE(t.inputs[0].empty());
  t.sort_by_index();  // nothing to sort by: the order appended
  ASSERT_EQ(t.outputs[0].size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(t.outputs[0][i], 100.0 + double(i));
  EXPECT_EQ(t.status[2], 3);
  ASSERT_EQ(t.failure_index.size(), 1u);
  EXPECT_EQ(t.failure_index[0], 2u);
}

TEST(SweepTable, ResultsAloneReserveOnlyTheColumnsTheyFill) {
  lsi::SweepTable t =
      lsi::SweepTable::with_columns({"/landslide/thickness_m"}, {"analytical/peak_force"});
  t.reserve_results(1000);
  EXPECT_GE(t.status.capacity(), 1000u);
  EXPECT_GE(t.outputs[0].capacity(), 1000u);
  EXPECT_EQ(t.index.capacity(), 0u) << "the index stays empty";
  EXPECT_EQ(t.wall_time.capacity(), 0u);
  EXPECT_EQ(t.inputs[0].capacity(), 0u);
  t.reserve(1000);  // whole rows: every column
  EXPECT_GE(t.index.capacity(), 1000u);
  EXPECT_GE(t.wall_time.capacity(), 1000u);
  EXPECT_GE(t.inputs[0].capacity(), 1000u);
}
