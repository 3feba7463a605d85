// The journal of a running sweep; see sweep_journal.hpp.
#include "app/sweep_journal.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "io/hdf5_io.hpp"
#include "model/input_error.hpp"

namespace lsi {

using nlohmann::json;

void write_journal_entry(const std::string& path, SweepHeader header, const SweepJournalEntry& e) {
  json chunks = json::array(), failures = json::array();
  for (const StoredChunk& k : e.chunks)
    chunks.push_back({k.dataset, k.chunk, k.address, k.size, k.column});
  for (std::size_t i = 0; i < e.failure_index.size(); ++i)
    failures.push_back({e.failure_index[i], e.failure_reason[i]});
  header.complete = true;  // the chunk itself
  header.journal = {
      {"format", kJournalFormat},     {"table_file", e.table_file},
      {"chunk_rows", e.chunk_rows},   {"input_chunks", e.whole_input_rows ? "rows" : "columns"},
      {"stored_rows", e.stored_rows}, {"chunks", chunks},
      {"failures", failures}};
  write_sweep_file(path, header, e.pending, nullptr, SweepStorage::Plain);
}

SweepJournalEntry read_journal_entry(const std::string& path, const std::string& fingerprint) {
  SweepFile f = read_sweep_file(path);
  if (f.header.fingerprint != fingerprint) throw InputError(path + ": belongs to another study");
  const json& j = f.header.journal;
  if (!j.is_object())
    throw InputError(path +
                     ": not a journal entry (left by an earlier version of lsi?); delete the "
                     "parts directory to start the sweep again");
  const json format = j.value("format", json(1));
  if (!format.is_number_integer() || format.get<long long>() < 1 ||
      format.get<long long>() > kJournalFormat)
    throw InputError(path + ": journal format " + format.dump() + ": this lsi reads formats 1 to " +
                     std::to_string(kJournalFormat) +
                     " (written by a later version of lsi?); resume with that version, or delete "
                     "the parts directory to start the sweep again");
  SweepJournalEntry e;
  try {
    e.table_file = j.at("table_file").get<std::string>();
    // Entries without it were written with the chunks of 256 KiB, whatever the chunk_samples
    // (SweepTableStream::chunk_rows_for with rows_at_once = 1).
    e.chunk_rows = j.value("chunk_rows", std::uint64_t(0));
    // Formats 1 and 2 chunked the inputs by whole rows, and their chunks have no column.
    if (format.get<long long>() >= 3) {
      const std::string input_chunks = j.at("input_chunks").get<std::string>();
      if (input_chunks != "columns" && input_chunks != "rows")
        throw InputError(path + ": attribute journal: input_chunks \"" + input_chunks +
                         "\" is neither \"columns\" nor \"rows\"");
      e.whole_input_rows = input_chunks == "rows";
    } else {
      e.whole_input_rows = true;
    }
    e.stored_rows = j.at("stored_rows").get<std::uint64_t>();
    for (const auto& k : j.at("chunks"))
      e.chunks.push_back({k.at(0).get<std::uint64_t>(), k.at(1).get<std::uint64_t>(),
                          k.at(2).get<std::uint64_t>(), k.at(3).get<std::uint64_t>(),
                          k.size() > 4 ? k.at(4).get<std::uint64_t>() : 0});
    for (const auto& k : j.at("failures")) {
      e.failure_index.push_back(k.at(0).get<std::uint64_t>());
      e.failure_reason.push_back(k.at(1).get<std::string>());
    }
  } catch (const json::exception& x) {
    throw InputError(path + ": attribute journal: " + x.what());
  }
  if (e.table_file.empty() || e.table_file.find('/') != std::string::npos)
    throw InputError(path + ": attribute journal: table_file \"" + e.table_file +
                     "\" is not a file name");
  e.pending = std::move(f.table);
  return e;
}

SweepJournal::SweepJournal(std::string table_path, SweepHeader header)
    : table_path_(std::move(table_path)), header_(std::move(header)) {}

SweepJournal::~SweepJournal() {
  try {
    flush();
  } catch (...) {  // the chunk held runs again on --resume
  }
}

void SweepJournal::add(std::string entry_path, SweepJournalEntry entry) {
  flush();
  written_ = std::async(std::launch::async, [table = table_path_, header = header_,
                                             path = std::move(entry_path), e = std::move(entry)] {
    hdf5::fsync_file(table);  // the chunks on disk before the entry names them
    write_journal_entry(path, header, e);
  });
}

void SweepJournal::flush() {
  if (written_.valid()) written_.get();
}

}  // namespace lsi
