// HDF5 result files: one file per scene run, one group per design method.
//
// Layout written by write_results (read back by read_results and app/lsi_plot.py; documented for
// users in docs/reference/results.md):
//   /                       attributes: scene (the scene JSON as read, indent 2), scene_resolved
//                           (the scene as run, every default filled in; where given),
//                           lsi_version, git_revision, command_line, argv (io/provenance.hpp)
//   /<method>               one group per MethodResult, in the order given (link creation order
//                           is tracked); string attributes end_state (runs: at_rest,
//                           end_time_landslide_moving, end_time_barrier_sliding,
//                           barrier_left_domain, unstable), status, barrier_model
//   /<method>/<history>     1D double datasets time, force, ..., barrier_displacement
//                           (history_fields) and the result's further series; only the non-empty
//                           ones; each with string attributes units and description. `time` is a
//                           dimension scale attached to every other history of the group.
//   /<method>/scalars/<name>  one 0-d dataset per scalar (described_scalars): float64, int64
//                           for counts, the boolean enum of hdf5_io.hpp for flags; each with
//                           units and description. A scalar a method does not give is left out.
//   Deprecated, still written for one release: the scalars also as float64 attributes of
//   /<method> under the same names, and the attribute `units` listing the four summaries' units.
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
// `scene_resolved`, if not null, is the scene as run (io/resolved_scene.hpp).
void write_results(const std::string& path, const nlohmann::json& scene,
                   const std::vector<MethodResult>& results,
                   const std::function<void(long long file_id)>& extra = {},
                   const nlohmann::json& scene_resolved = nullptr);

struct StoredResults {
  nlohmann::json scene;
  nlohmann::json scene_resolved;      // null where the file has none
  std::vector<MethodResult> results;  // in the order they were written (name order if untracked)
  std::string lsi_version;
  std::string git_revision;
  std::vector<std::string> argv;  // the command line's words; empty where not recorded
};

// Reads back everything write_results writes. Every group under the root is one method (the group
// name is MethodResult::method); missing datasets give empty vectors; the scalars come from
// /<method>/scalars, or in files without it (earlier versions) from the group's double
// attributes; those other than the four summaries are set by name (set_named_scalar; a name this
// version does not know is left out). Throws std::runtime_error (path + what failed).
StoredResults read_results(const std::string& path);

}  // namespace lsi
