// The per-sample table of a sweep and its HDF5 files: the chunk files a running sweep writes as
// work finishes (app/sweep_runner.hpp) and the result file they are gathered into.
//
// HDF5 layout (chunk files and result files alike):
//   /                     attributes: kind = "lsi sweep", study (the study JSON with its scene
//                         inlined), fingerprint, lsi_version, git_revision, planned_samples,
//                         chunk_samples, shard ("i/N"), samples_done, complete (0/1),
//                         stopped_by ("" or why the sweep stopped before planned_samples),
//                         wall_seconds (of the run that wrote the file)
//   /samples/index        uint64 [n]  sample index (rows sorted by it)
//   /samples/status       int8 [n]    0 ok, 1 invalid input, 2 MPM unstable, 3 failed
//   /samples/wall_time    float32 [n] s; closed forms: their chunk's time shared per sample
//   /samples/inputs       float64 [n x inputs]; attribute `paths`: JSON array of the inputs'
//                         scene paths, in column order
//   /samples/<method>/<output>  float64 [n], attribute units; NaN where status != 0
//   /failures/index       uint64 [f]  the samples with status != 0 ...
//   /failures/reason      string [f]  ... and why (one line, as `lsi run` would print it)
//   /statistics           result files only: attribute `json` (model/sweep_statistics.hpp)
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "model/sweep_table.hpp"

namespace lsi {

struct SweepHeader {
  nlohmann::json study;
  std::string fingerprint;
  std::uint64_t planned_samples = 0;
  std::uint64_t chunk_samples = 0;
  int shard = 0, shard_count = 1;
  bool complete = false;
  std::string stopped_by;
  double wall_seconds = 0.0;
};

// Writes atomically (io/hdf5_io.hpp). `statistics` (may be null) goes to /statistics.
void write_sweep_file(const std::string& path, const SweepHeader& header, const SweepTable& table,
                      const nlohmann::json* statistics = nullptr);

struct SweepFile {
  SweepHeader header;
  SweepTable table;
  nlohmann::json statistics;  // null if the file has none
};
// Throws std::runtime_error naming the path and what is wrong (not a sweep file, unreadable...).
SweepFile read_sweep_file(const std::string& path);

}  // namespace lsi
