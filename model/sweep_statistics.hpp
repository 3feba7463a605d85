// Statistics of a sweep's outputs (sweeps/statistics.hpp) as JSON, for the result file, the
// command's JSON output and its table; and the confidence-interval stopping rule.
//
// Only samples with status ok enter the statistics (the same sample set for every method, so
// that the methods are compared on the same samples); the effective count is reported beside
// the planned one. Infinite values (a barrier that never stops) are kept: they count in the
// quantiles and exceedance probabilities, and make the mean infinite. Non-finite numbers are
// written as the strings "inf" / "-inf" (JSON has no infinity).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "model/study.hpp"
#include "model/sweep_table.hpp"

namespace lsi {

nlohmann::json sweep_statistics(const Study& study, const SweepTable& table);

// A double as JSON: finite values as numbers, the others as "inf", "-inf" or "nan".
nlohmann::json json_number(double v);

// The human-readable summary of sweep_statistics' JSON.
std::string sweep_statistics_table(const nlohmann::json& statistics);

// Whether the study's interval rule (study.stop) is met by these values of its output (the ok
// samples so far, in index order); `why` gets the one-line reason when it is.
bool interval_rule_met(const Study& study, const std::vector<double>& values, std::string& why);

}  // namespace lsi
