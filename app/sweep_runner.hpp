// Runs a study (model/study.hpp) chunk by chunk and gathers the results into one HDF5 file
// (model/sweep_table.hpp).
//
// Samples are processed in chunks of study.chunk_samples, the MPM samples side by side across
// chunks (one a thread, model/concurrent_runs.hpp) while the chunks are committed in order.
//
// Nothing finished is lost. The result's table is written as the chunks finish, each chunk of
// its datasets compressed once, into `<out>.parts/table-<g>.h5` (io/sweep_table_stream.hpp);
// after each chunk `<out>.parts/chunk-<k>.h5` journals what it added (app/sweep_journal.hpp). A
// run killed at any moment (SIGKILL included) leaves whole journal entries (and loses its MPM
// runs finished beyond the first chunk not yet complete: at most four a thread), and `resume`
// copies the compressed chunks they name into a new table file and recomputes just the missing
// chunks: sample i always gets the same inputs (counter-based sampling) and its MPM the same
// threads, so the file is the one an uninterrupted run writes (wall times aside). When every
// chunk of the run is done the table file, finished with the statistics, is renamed onto `out`
// and the parts directory is removed. A run stopped by its wall-time limit starts no more MPM
// runs, commits the chunks of the runs under way, writes `out` (marked incomplete, a copy of the
// table so far) and keeps the parts for `resume`.
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
  // Where the time went (s): evaluate (sampling and the methods), write_chunks (compressing and
  // writing the table's chunks, the journal), gather (joining the rows for the statistics,
  // finishing `out`), statistics.
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
