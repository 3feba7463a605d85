// The journal of a running sweep: after each chunk, `<out>.parts/chunk-<k>.h5` records what the
// chunk added to the result being written (`<out>.parts/table-<g>.h5`, io/sweep_table_stream.hpp):
// where its compressed chunks lie in that file, its failures, and the rows not yet in a whole
// compressed chunk. A run killed part-way is resumed from these records: the compressed chunks
// are copied into a new table file and the run goes on (app/sweep_runner.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/sweep_file.hpp"
#include "io/sweep_table_stream.hpp"

namespace lsi {

struct SweepJournalEntry {
  std::string table_file;                    // the table file's name in the parts directory
  std::vector<StoredChunk> chunks;           // the compressed chunks the chunk completed there
  std::uint64_t chunk_rows = 0;              // the table's rows per compressed chunk
  std::uint64_t stored_rows = 0;             // rows in whole compressed chunks after the chunk
  SweepTable pending;                        // the rows after those (not compressed yet)
  std::vector<std::uint64_t> failure_index;  // the chunk's failed samples ...
  std::vector<std::string> failure_reason;   // ... and why
};

// Writes the entry atomically, with the sweep's header (its fingerprint identifies the study).
void write_journal_entry(const std::string& path, SweepHeader header,
                         const SweepJournalEntry& entry);
// Reads an entry; throws InputError naming the file when it belongs to another study or is not a
// journal entry (a parts directory of an earlier version of lsi).
SweepJournalEntry read_journal_entry(const std::string& path, const std::string& fingerprint);

}  // namespace lsi
