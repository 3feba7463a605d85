// HDF5 result files: one file per scene run, one group per design method.
//
// Layout written by write_results (read back by read_results and app/lsi_plot.py):
//   /                       attributes: scene (the scene JSON, indent 2), lsi_version, git_revision
//   /<method>               one group per MethodResult, in the order given (link creation order
//                           is tracked); attributes: peak_force, rise_time, impact_duration,
//                           final_displacement (double; +inf allowed; left out where it is not
//                           given, e.g. a run cut short while the barrier still slid), every
//                           further scalar (model/result_scalars.hpp: named_scalars), `units` (string listing the units of the four
//                           scalars), and for runs `end_state` (string: at_rest,
//                           end_time_landslide_moving, end_time_barrier_sliding,
//                           barrier_left_domain, unstable) and `status` (string)
//   /<method>/<history>     1D double datasets time, force, force_horizontal, force_vertical,
//                           landslide_kinetic_energy, barrier_velocity, barrier_displacement;
//                           only the non-empty ones; each with string attributes units, description
// Strings are variable-length UTF-8 scalars (h5py reads them as str).
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/method_result.hpp"

namespace lsi {

// Writes atomically: everything goes to `<path>.tmp.<pid>` in the same directory, which is closed,
// fsync'ed and renamed onto `path`; `path` is either the old file or the complete new one, never a
// partial one. Missing parent directories are created.
// Throws std::invalid_argument (nothing written) for an invalid result: a non-empty history whose
// length differs from `time` (the message names the dataset), an empty/duplicate method name or one
// containing '/'.
// Throws std::runtime_error (message: path + what failed) for any I/O or HDF5 failure; the
// temporary file is removed and an existing file at `path` is left untouched.
// `extra`, if set, is called with the open file's id (an hid_t) after the method groups are written
// and before the file is closed and renamed, to add further objects (e.g. MPM particle snapshots,
// io/mpm_snapshots.hpp); an exception from it fails the whole write as above.
void write_results(const std::string& path, const nlohmann::json& scene,
                   const std::vector<MethodResult>& results,
                   const std::function<void(long long file_id)>& extra = {});

struct StoredResults {
  nlohmann::json scene;
  std::vector<MethodResult> results;  // in the order they were written (name order if untracked)
  std::string lsi_version;
};

// Reads back everything write_results writes. Every group under the root is one method (the group
// name is MethodResult::method); missing datasets give empty vectors, the double attributes other
// than the four standard scalars are set by name (set_named_scalar; a name this version does not
// know is left out). Throws std::runtime_error (path + what failed).
StoredResults read_results(const std::string& path);

}  // namespace lsi
