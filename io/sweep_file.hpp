// The per-sample table of a sweep and its HDF5 files: the chunk files a running sweep writes as
// work finishes (app/sweep_runner.hpp) and the result file they are gathered into. Documented
// for users in docs/reference/results.md.
//
// HDF5 layout (chunk files and result files alike); every dataset has the string attributes
// `units` ("1" for a pure number or a count, "" for text) and `description`:
//   /                     attributes: kind = "lsi sweep", study (the study JSON with its scene
//                         inlined), scene_resolved (the study's scene with every default filled
//                         in, io/resolved_scene.hpp), fingerprint, lsi_version, git_revision,
//                         command_line, argv (io/provenance.hpp), planned_samples,
//                         chunk_samples, samples_done (int64), shard ("i/N"), complete
//                         (boolean, hdf5_io.hpp), stopped_by ("" or why the sweep stopped before
//                         planned_samples), wall_seconds (of the run that wrote the file)
//   /samples/index        uint64 [n]  sample index (rows sorted by it)
//   /samples/status       int8 [n]    0 ok, 1 invalid input, 2 MPM unstable, 3 failed, 4 cut short
//   /samples/wall_time    float32 [n] s; closed forms: their chunk's time shared per sample
//   /samples/inputs       float64 [n x inputs]; attributes `paths` (JSON array of the inputs'
//                         scene paths, in column order) and `units` (an array of strings, one
//                         per column: the units of the scene key)
//   /samples/<method>/<output>  float64 [n]; NaN where status != 0
//   /failures/index       uint64 [f]  the samples with status != 0 ...
//   /failures/reason      string [f]  ... and why (one line, as `lsi run` would print it)
//   /statistics           result files only: attribute `json` (model/sweep_statistics.hpp) and
//                         the same as datasets (statistics_datasets in sweep_file.cpp)
// Chunk files of a running sweep hold the rows of the result not yet in its whole compressed
// chunks, and the root attribute `journal` (JSON: what the chunk added to the result).
// The /samples datasets of result files are chunked and compressed (shuffle + deflate).
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "model/sweep_table.hpp"

namespace lsi {

struct SweepHeader {
  nlohmann::json study;
  nlohmann::json scene_resolved;  // null: not stored
  std::string fingerprint;
  std::uint64_t planned_samples = 0;
  std::uint64_t chunk_samples = 0;
  int shard = 0, shard_count = 1;
  bool complete = false;
  std::string stopped_by;
  double wall_seconds = 0.0;
  // Chunk files of a running sweep only: what the chunk added to the result being written
  // (app/sweep_runner.cpp); null: not stored.
  nlohmann::json journal;
};

// How the /samples datasets are stored: compressed (result files) or plain (the chunk files of a
// running sweep, written once and read once: compressing them would only cost time).
enum class SweepStorage { Compressed, Plain };

// Writes atomically (io/hdf5_io.hpp). `statistics` (may be null) goes to /statistics.
void write_sweep_file(const std::string& path, const SweepHeader& header, const SweepTable& table,
                      const nlohmann::json* statistics = nullptr,
                      SweepStorage storage = SweepStorage::Compressed);

struct SweepFile {
  SweepHeader header;
  SweepTable table;
  nlohmann::json statistics;  // null if the file has none
};
// Throws std::runtime_error naming the path and what is wrong (not a sweep file, unreadable...).
SweepFile read_sweep_file(const std::string& path);

}  // namespace lsi
