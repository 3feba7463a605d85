#include "app/sweep_report.hpp"

#include <sstream>

#include "app/sweep_quantile_mpm.hpp"
#include "model/sweep_statistics.hpp"

namespace lsi {

nlohmann::json sweep_outcome_json(const SweepOutcome& o, const std::string& out, int ranks) {
  nlohmann::json j = {{"out", out},
                      {"complete", o.complete},
                      {"stopped_by", o.stopped_by},
                      {"samples_done", o.samples_done},
                      {"samples_ok", o.samples_ok},
                      {"samples_run", o.samples_run},
                      {"wall_seconds", o.wall_seconds},
                      {"seconds", o.seconds},
                      {"statistics", o.statistics}};
  if (ranks > 0) j["ranks"] = ranks;
  return j;
}

std::string sweep_outcome_text(const SweepOutcome& o, const std::string& out, int ranks) {
  std::ostringstream s;
  if (o.statistics.is_object()) {
    s << sweep_statistics_table(o.statistics);
    if (o.statistics.contains("mpm_at_quantiles"))
      s << mpm_at_quantiles_table(o.statistics["mpm_at_quantiles"]);
  }
  s << (o.complete ? "complete" : "incomplete") << ": " << o.samples_done << " samples in " << out
    << " (" << o.samples_run << " run now";
  if (ranks > 0) s << " on " << ranks << (ranks == 1 ? " rank" : " ranks");
  s << ", " << o.wall_seconds << " s)";
  if (!o.stopped_by.empty()) s << "; stopped by " << o.stopped_by;
  s << "\n";
  return s.str();
}

}  // namespace lsi
