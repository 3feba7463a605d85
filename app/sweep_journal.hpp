// The journal of a running sweep: after each chunk, `<out>.parts/chunk-<k>.h5` records what the
// chunk added to the result being written (`<out>.parts/table-<g>.h5`, io/sweep_table_stream.hpp):
// where its compressed chunks lie in that file, its failures, and the rows not yet in a whole
// compressed chunk. A run killed part-way is resumed from these records: the compressed chunks
// are copied into a new table file and the run goes on (app/sweep_runner.cpp).
#pragma once
#include <cstdint>
#include <future>
#include <string>
#include <vector>

#include "io/sweep_file.hpp"
#include "io/sweep_table_stream.hpp"

namespace lsi {

struct SweepJournalEntry {
  std::string table_file;                    // the table file's name in the parts directory
  std::vector<StoredChunk> chunks;           // the compressed chunks the chunk completed there
  std::uint64_t chunk_rows = 0;              // the table's rows per compressed chunk
  bool whole_input_rows = false;             // the inputs' chunks hold whole rows (formats 1, 2)
  std::uint64_t stored_rows = 0;             // rows in whole compressed chunks after the chunk
  SweepTable pending;                        // the rows after those (not compressed yet)
  std::vector<std::uint64_t> failure_index;  // the chunk's failed samples ...
  std::vector<std::string> failure_reason;   // ... and why
};

// The layout of an entry's `journal` attribute, written as its "format". Format 1 (entries
// without the key) may lack chunk_rows; format 2 always has it. Formats 1 and 2 journal tables
// whose inputs' chunks hold whole rows; format 3 records how the inputs are chunked
// ("input_chunks": "columns" or "rows") and each chunk's column. A reader refuses a format newer
// than its own: a newer lsi may record what this one would not know to follow (the table's
// chunk rows and its inputs' chunks were such records), and resuming would then write a wrong
// table.
constexpr int kJournalFormat = 3;

// Writes the entry atomically, with the sweep's header (its fingerprint identifies the study).
void write_journal_entry(const std::string& path, SweepHeader header,
                         const SweepJournalEntry& entry);
// Reads an entry; throws InputError naming the file when it belongs to another study, is not a
// journal entry (a parts directory of an earlier version of lsi) or has a format other than 1 to
// kJournalFormat (a later version's).
SweepJournalEntry read_journal_entry(const std::string& path, const std::string& fingerprint);

// Journals a run's chunks: after a chunk, a thread of its own fsyncs the table file and then
// writes the chunk's entry, while the caller goes on (describes the chunk's rows, evaluates the
// next chunk); the caller calls `flush` before it uses HDF5 again (the next chunk's rows into the
// table file). The entries stay in chunk order and each names bytes already on disk. A chunk is
// journalled one fsync after its rows were written, whatever the next chunk takes: a kill then
// loses the chunks not yet journalled, the one whose fsync was under way at most.
class SweepJournal {
 public:
  SweepJournal(std::string table_path, SweepHeader header);
  SweepJournal(const SweepJournal&) = delete;
  SweepJournal& operator=(const SweepJournal&) = delete;
  // Waits for the entry under way (an error leaves the chunk to run again on --resume).
  ~SweepJournal();

  // The chunk whose rows the table file has just taken: its entry, for `entry_path`. Waits for
  // the entry under way first, then starts this one's fsync and entry.
  void add(std::string entry_path, SweepJournalEntry entry);
  // Waits for the entry under way, if any (its fsync's or writing's failure is thrown here).
  void flush();

 private:
  std::string table_path_;
  SweepHeader header_;
  std::future<void> written_;
};

}  // namespace lsi
