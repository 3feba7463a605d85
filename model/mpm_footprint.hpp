// What an MPM case will take before it is built: its points, grid nodes, the memory of its state,
// of its histories and snapshots if it runs to end_time_s, and its number of steps bounded by the
// first step's size. A case whose memory cannot fit on this machine is refused up front, naming
// the setting that makes it so (check_mpm_fits), instead of failing late in an allocation.
#pragma once
#include <vector>

#include "model/mpm_case.hpp"
#include "model/scene.hpp"

namespace lsi {

struct MpmFootprint {
  double points = 0.0;           // estimated from the bodies' areas and the points per cell
  double nodes = 0.0;            // grid nodes
  double state_bytes = 0.0;      // points and grid (both phases), with the scatter's buffers
  double history_bytes = 0.0;    // the histories, one output per output_interval_s to end_time_s
  double snapshot_bytes = 0.0;   // the snapshots kept to the end of the run
  double first_time_step = 0.0;  // s: the Courant limit at the initial speed and wave speed
  double max_steps = 0.0;        // end_time_s / first_time_step (an upper estimate: points that
                                 // expand or speed up shorten the step; an impact run ends at rest)
};

MpmFootprint estimate_footprint(const MpmCase& c);

// Throws InputError when the footprint exceeds the memory available (resource_estimate.hpp):
// on methods.mpm.cell_size_m when the state alone does not fit, else on snapshot_interval_s or
// end_time_s / output_interval_s, with the numbers and the smallest change that fits.
void check_mpm_fits(const MpmCase& c);

// The memory a run of the footprint's case takes where the campaign runs (the host's): its state
// where that lives on the host, its histories and its snapshots.
double host_run_bytes(const MpmFootprint& f);

// host_run_bytes of the footprint of a scene's MPM case; 0 where the case cannot be built (the
// scene's run reports why).
double scene_run_bytes(const Scene& s);

// The runs at once for a campaign of `tasks` MPM runs of `scenes` (run_concurrently's
// runs_at_once): as many as threads and tasks allow (concurrent_runs), at most as many as fit in
// the memory side by side, each counted at the largest scene's footprint (runs_that_fit). A
// scene whose case cannot be built is left out (its task reports the error).
int campaign_runs_that_fit(std::size_t tasks, const std::vector<const Scene*>& scenes);

}  // namespace lsi
