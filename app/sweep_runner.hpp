// Runs a study (model/study.hpp) chunk by chunk and gathers the results into one HDF5 file
// (model/sweep_table.hpp).
//
// Nothing finished is lost. Samples are processed in chunks of study.chunk_samples; each
// finished chunk is written atomically to `<out>.parts/chunk-<k>.h5` before the next starts. A
// run killed at any moment (SIGKILL included) leaves only whole chunk files, and `resume`
// recomputes just the missing chunks: sample i always gets the same inputs (counter-based
// sampling), so the gathered file is the one an uninterrupted run writes (wall times aside).
// When every chunk of the run is done the chunk files are gathered, sorted by sample index, into
// `out` (atomically) and the parts directory is removed. A run stopped by its wall-time limit
// also writes `out` (marked incomplete) and keeps the parts for `resume`.
//
// Sharding: shard i of N runs the chunks k with k mod N = i; merge_sweeps joins the shard files
// into the file a single run writes.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/study.hpp"

namespace lsi {

struct SweepOptions {
  std::string out;      // the result file
  bool resume = false;  // continue the run that left `<out>.parts`
  int shard = 0, shard_count = 1;
  bool progress = true;  // a progress line on standard error, when it is a terminal
};

struct SweepOutcome {
  bool complete = false;   // every planned sample done (or the interval rule met)
  std::string stopped_by;  // why it stopped early ("" if it ran every sample)
  std::uint64_t samples_done = 0, samples_ok = 0, samples_run = 0;  // run: by this invocation
  double wall_seconds = 0.0;
  // Where the time went (s): evaluate (sampling and the methods), write_chunks (chunk files),
  // gather (reading them back and writing `out`), statistics.
  nlohmann::json seconds = nlohmann::json::object();
  nlohmann::json statistics;  // null for a shard of several
};

// Throws InputError for a parts directory that belongs to another study or shard, or one left
// by an earlier run when `resume` is not set; std::runtime_error for I/O failures.
SweepOutcome run_sweep(const Study& study, const SweepOptions& options);

// Joins the result files of shards 0..N-1 of one study into `out` (with statistics), checking
// that they belong to the same study, cover every shard once and are complete.
SweepOutcome merge_sweeps(const std::vector<std::string>& shard_files, const std::string& out);

// Parses "i/N" (0 <= i < N); throws InputError naming the option.
void parse_shard(const std::string& text, int& shard, int& shard_count);

}  // namespace lsi
