// What `lsi sweep`, `lsi merge` and `lsi-mpi` print when a sweep ends: the statistics table (and
// the MPM at quantiles) and one line on the file, or all of it as JSON.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "app/sweep_runner.hpp"

namespace lsi {

// `where`: how the samples ran, e.g. "" or "on 2 ranks" (text and JSON `ranks` when > 0).
nlohmann::json sweep_outcome_json(const SweepOutcome& o, const std::string& out, int ranks = 0);
std::string sweep_outcome_text(const SweepOutcome& o, const std::string& out, int ranks = 0);

}  // namespace lsi
