// A sweep result file whose table is written as its rows arrive: each whole chunk of rows of the
// /samples datasets is compressed once (shuffle + deflate, on several threads, as HDF5's filter
// pipeline would) and written straight into the file; the rows that do not fill a chunk yet wait
// in memory. Where each compressed chunk lies (byte address and size) is returned, so that a run
// killed part-way can copy the chunks, still compressed, into a new file and go on
// (app/sweep_runner.cpp keeps that journal). finish() adds what depends on the whole run (the
// last, partial chunk, attributes, failures, statistics): the file is then the one
// write_sweep_file writes (io/sweep_file.hpp), the same datasets, types and attributes.
#pragma once
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/compressed_chunks.hpp"
#include "io/hdf5_io.hpp"
#include "io/sweep_file.hpp"
#include "io/sweep_file_layout.hpp"
#include "io/written_chunk_address.hpp"
#include "model/sweep_table.hpp"

namespace lsi {

// One compressed chunk of a /samples dataset in a file: the dataset (its place in
// sweep_layout::sample_datasets), the chunk's index along the rows, its bytes' address and size,
// and its first column (the inputs' chunks of one column each; 0 for the others).
struct StoredChunk {
  std::uint64_t dataset, chunk, address, size, column = 0;
};

class SweepTableStream {
 public:
  // Chunk rows for a table of these columns and `rows` rows whose rows arrive `rows_at_once` at
  // a time (a sweep's chunk_samples): the largest power of two whose widest row (the inputs)
  // fits 256 KiB, doubled while it is below `rows_at_once` and the chunk fits 1 MiB; at most
  // `rows`. Larger chunks cost less to compress and index (each byte plane's code and block
  // header is made once per chunk); the cap keeps a chunk within HDF5's default chunk cache, and
  // `rows_at_once` bounds the rows that wait in memory for a chunk to fill (a sweep's journal
  // writes them again with every entry).
  static std::uint64_t chunk_rows_for(std::size_t inputs, std::uint64_t rows,
                                      std::uint64_t rows_at_once);

  // Creates `path` (truncating it) with the /samples datasets of a table of `rows` rows (at
  // most; finish() may end it shorter), in chunks of `chunk_rows` rows. A chunk of the inputs
  // holds one of their columns (`whole_input_rows` false: each column's bytes compress as its
  // numbers allow) or whole rows, as tables of earlier versions of lsi did, which a resumed run
  // goes on with.
  SweepTableStream(const std::string& path, std::vector<std::string> input_paths,
                   std::vector<std::string> output_columns, std::uint64_t rows,
                   std::uint64_t chunk_rows, bool whole_input_rows = false);

  // Appends rows (failures are the caller's): the chunks they complete are compressed and
  // written; returns where they lie.
  std::vector<StoredChunk> append(const SweepTable& rows);
  // Copies chunks, still compressed, from the file `from`, where `chunks` lie; returns where they
  // lie now. Throws std::runtime_error naming `from` when it lacks their bytes.
  std::vector<StoredChunk> adopt(const std::string& from, const std::vector<StoredChunk>& chunks);
  // After adopt: the rows in whole chunks, and those after them (waiting in memory).
  void restore(std::uint64_t stored_rows, SweepTable pending);

  std::uint64_t stored_rows() const { return stored_rows_; }
  bool whole_input_rows() const { return whole_input_rows_; }
  const SweepTable& pending() const { return pending_; }
  std::uint64_t rows() const { return stored_rows_ + pending_.rows(); }
  const std::string& path() const { return path_; }

  // The rows in whole chunks, read back (inflated by HDF5).
  SweepTable read_stored() const;

  // Ends the file with rows() rows: the pending rows as the last chunk, the header, failures and
  // statistics (may be null); flushes and closes it.
  void finish(const SweepHeader& header, const std::vector<std::uint64_t>& failure_index,
              const std::vector<std::string>& failure_reason, const nlohmann::json* statistics);

 private:
  std::vector<StoredChunk> write_chunks(const SweepTable& source, std::uint64_t rows);
  // Writes one compressed chunk where k says (dataset, chunk) and sets k's address and size to
  // where the file put it.
  void write_chunk(StoredChunk& k, const void* bytes, std::size_t size);

  std::string path_;
  std::vector<std::string> input_paths_, output_columns_;
  std::vector<sweep_layout::SampleDataset> layout_;
  hdf5::Handle file_;
  std::vector<hdf5::Handle> datasets_;
  std::uint64_t planned_rows_, chunk_rows_, stored_rows_ = 0;
  bool whole_input_rows_;
  std::unique_ptr<hdf5::ChunkCompression> compression_;  // every dataset has the same filters
  SweepTable pending_;
  std::vector<double> row_major_inputs_;  // whole input rows: write_chunks' buffer, kept
  std::unique_ptr<hdf5::WrittenChunkAddress> addresses_;  // where each chunk went
};

}  // namespace lsi
