// Statistics of a sweep's outputs (sweeps/statistics.hpp) as JSON, for the result file, the
// command's JSON output and its table; and the confidence-interval stopping rule.
//
// Only samples with status ok enter the statistics (the same sample set for every method, so
// that the methods are compared on the same samples); the effective count is reported beside
// the planned one. Infinite values (a barrier that never stops) are kept: they count in the
// quantiles and exceedance probabilities, and make the mean infinite. Non-finite numbers are
// written as the strings "inf" / "-inf" (JSON has no infinity).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/study.hpp"
#include "model/sweep_table.hpp"
#include "sweeps/column_accumulator.hpp"

namespace lsi {

// The statistics of the rows of a sweep's table (all of them: sample order).
nlohmann::json sweep_statistics(const Study& study, const SweepTable& table);

// The same, of rows added a chunk at a time in sample order, without the rows kept
// (sweeps/column_accumulator.hpp): what sweep_statistics() gives for all of them, bit for bit.
class SweepStatisticsAccumulator {
 public:
  SweepStatisticsAccumulator(const Study& study, const std::vector<std::string>& output_columns);
  // The next rows (their statuses and outputs are read).
  void add(const SweepTable& rows);
  // The statistics of the rows added. whole_table() gives them all, in sample order (called at
  // most once, where a column's values did not arrive in random order: a grid walked in order).
  nlohmann::json result(const std::function<const SweepTable&()>& whole_table);

 private:
  const Study& study_;
  std::vector<std::string> columns_;
  std::vector<sweeps::ColumnAccumulator> column_;
  std::vector<std::vector<std::size_t>> threshold_of_;  // per column: the study's thresholds
  std::size_t rows_ = 0, ok_ = 0;
  std::map<std::string, std::size_t> failed_;
};

// A double as JSON: finite values as numbers, the others as "inf", "-inf" or "nan".
nlohmann::json json_number(double v);

// The human-readable summary of sweep_statistics' JSON.
std::string sweep_statistics_table(const nlohmann::json& statistics);

// Whether the study's interval rule (study.stop) is met by these values of its output (the ok
// samples so far, in index order); `why` gets the one-line reason when it is.
bool interval_rule_met(const Study& study, const std::vector<double>& values, std::string& why);

}  // namespace lsi
