// The sweep's journal (app/sweep_journal.hpp): each entry written on the journal's thread after
// the table file's fsync returned, in chunk order (the next add waits for it), none lost at the
// end of a run and none written after a failed fsync; each entry written with its format, and an
// entry of a format the reader does not know refused; each chunk's column and the inputs'
// chunking recorded, older formats read as whole input rows.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "app/sweep_journal.hpp"
#include "io/sweep_file.hpp"
#include "model/input_error.hpp"

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("lsi_test_sweep_journal_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

lsi::SweepHeader header() {
  lsi::SweepHeader h;
  h.fingerprint = "journal-test";
  h.study = {{"name", "journal-test"}};
  return h;
}

// An entry that says which chunk it is by its stored rows.
lsi::SweepJournalEntry entry(std::uint64_t chunk) {
  lsi::SweepJournalEntry e;
  e.table_file = "table-0.h5";
  e.chunk_rows = 4096;
  e.stored_rows = 1000 * (chunk + 1);
  e.pending = lsi::SweepTable::with_columns({"/landslide/thickness"}, {"analytical/peak_force"});
  e.pending.index = {e.stored_rows};
  e.pending.status = {0};
  e.pending.wall_time = {0.0f};
  e.pending.inputs = {{1.5}};
  e.pending.outputs = {{2.5}};
  return e;
}

fs::path table_file(const fs::path& dir) {
  const fs::path t = dir / "table-0.h5";
  std::ofstream(t) << "the table's bytes";
  return t;
}

}  // namespace

TEST(SweepJournal, WritesEachEntryBeforeTheNextAddOrFlushReturnsInChunkOrder) {
  const fs::path dir = fresh_dir("order");
  lsi::SweepJournal journal(table_file(dir).string(), header());
  const fs::path first = dir / "chunk-0.h5", second = dir / "chunk-1.h5";
  journal.add(first.string(), entry(0));
  journal.add(second.string(), entry(1));
  ASSERT_TRUE(fs::exists(first)) << "the next add waits for the entry under way";
  journal.flush();
  ASSERT_TRUE(fs::exists(second));
  const lsi::SweepJournalEntry a = lsi::read_journal_entry(first.string(), "journal-test");
  const lsi::SweepJournalEntry b = lsi::read_journal_entry(second.string(), "journal-test");
  EXPECT_EQ(a.stored_rows, 1000u);
  EXPECT_EQ(b.stored_rows, 2000u);
  EXPECT_EQ(b.chunk_rows, 4096u);
  ASSERT_EQ(b.pending.rows(), 1u);
  EXPECT_EQ(b.pending.index[0], 2000u);
  EXPECT_EQ(b.pending.outputs[0][0], 2.5);
  journal.flush();  // nothing under way: nothing written again
  EXPECT_EQ(lsi::read_journal_entry(second.string(), "journal-test").stored_rows, 2000u);
}

TEST(SweepJournal, TheEntryUnderWayIsWrittenWhenTheJournalEnds) {
  const fs::path dir = fresh_dir("end");
  const fs::path only = dir / "chunk-0.h5";
  {
    lsi::SweepJournal journal(table_file(dir).string(), header());
    journal.add(only.string(), entry(0));
  }
  ASSERT_TRUE(fs::exists(only));
  EXPECT_EQ(lsi::read_journal_entry(only.string(), "journal-test").stored_rows, 1000u);
}

TEST(SweepJournal, AFailedFsyncIsThrownAndItsEntryNeverWritten) {
  const fs::path dir = fresh_dir("fsync");
  const fs::path missing = dir / "no-table.h5", first = dir / "chunk-0.h5";
  lsi::SweepJournal journal(missing.string(), header());
  journal.add(first.string(), entry(0));
  try {
    journal.flush();
    FAIL() << "the fsync of a missing table file cannot succeed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fsync"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(first)) << "an entry must never name bytes not known to be on disk";
}

// An entry's journal attribute as a given format would write it (`format` null: left out, as
// entries of format 1 were written).
static void write_entry_of_format(const fs::path& path, const nlohmann::json& format) {
  lsi::SweepHeader h = header();
  h.complete = true;
  h.journal = {{"table_file", "table-0.h5"},
               {"stored_rows", 1000},
               {"chunks", nlohmann::json::array()},
               {"failures", nlohmann::json::array()}};
  if (!format.is_null()) h.journal["format"] = format;
  lsi::write_sweep_file(path.string(), h, entry(0).pending, nullptr, lsi::SweepStorage::Plain);
}

TEST(SweepJournal, WritesItsFormatAndRefusesAFormatItDoesNotKnow) {
  const fs::path dir = fresh_dir("format");
  const fs::path written = dir / "chunk-0.h5";
  {
    lsi::SweepJournal journal(table_file(dir).string(), header());
    journal.add(written.string(), entry(0));
  }
  EXPECT_EQ(lsi::read_sweep_file(written.string()).header.journal.at("format"),
            lsi::kJournalFormat);
  // Format 1 (no key): read, its chunk rows left to the caller's rule for such entries.
  const fs::path older = dir / "chunk-1.h5";
  write_entry_of_format(older, nullptr);
  const lsi::SweepJournalEntry e = lsi::read_journal_entry(older.string(), "journal-test");
  EXPECT_EQ(e.stored_rows, 1000u);
  EXPECT_EQ(e.chunk_rows, 0u);
  // A later format, or one that is no format at all: refused, naming the file and the value.
  for (const nlohmann::json& bad :
       {nlohmann::json(lsi::kJournalFormat + 1), nlohmann::json(0), nlohmann::json("2")}) {
    const fs::path later = dir / "chunk-2.h5";
    write_entry_of_format(later, bad);
    try {
      lsi::read_journal_entry(later.string(), "journal-test");
      FAIL() << "format " << bad.dump() << " read";
    } catch (const lsi::InputError& x) {
      const std::string what = x.what();
      EXPECT_NE(what.find(later.string()), std::string::npos) << what;
      EXPECT_NE(what.find("journal format " + bad.dump()), std::string::npos) << what;
      EXPECT_NE(what.find("reads formats 1 to " + std::to_string(lsi::kJournalFormat)),
                std::string::npos)
          << what;
    }
  }
}

// An entry whose journal attribute is `journal` as it stands.
static void write_entry_with_journal(const fs::path& path, const nlohmann::json& journal) {
  lsi::SweepHeader h = header();
  h.complete = true;
  h.journal = journal;
  lsi::write_sweep_file(path.string(), h, entry(0).pending, nullptr, lsi::SweepStorage::Plain);
}

TEST(SweepJournal, RecordsEachChunksColumnAndReadsOlderFormatsAsWholeInputRows) {
  const fs::path dir = fresh_dir("input_chunks");
  // Written and read back: each chunk's column, and how the inputs are chunked.
  for (const bool whole_rows : {false, true}) {
    const fs::path written = dir / (whole_rows ? "chunk-rows.h5" : "chunk-columns.h5");
    lsi::SweepJournalEntry e = entry(0);
    e.whole_input_rows = whole_rows;
    e.chunks = {{3, 2, 4096, 512, whole_rows ? 0u : 4u}, {4, 2, 8192, 256, 0}};
    {
      lsi::SweepJournal journal(table_file(dir).string(), header());
      journal.add(written.string(), e);
    }
    const lsi::SweepJournalEntry back = lsi::read_journal_entry(written.string(), "journal-test");
    EXPECT_EQ(back.whole_input_rows, whole_rows);
    ASSERT_EQ(back.chunks.size(), 2u);
    EXPECT_EQ(back.chunks[0].dataset, 3u);
    EXPECT_EQ(back.chunks[0].chunk, 2u);
    EXPECT_EQ(back.chunks[0].address, 4096u);
    EXPECT_EQ(back.chunks[0].size, 512u);
    EXPECT_EQ(back.chunks[0].column, whole_rows ? 0u : 4u);
    EXPECT_EQ(back.chunks[1].column, 0u);
  }
  // Format 2 knew whole input rows alone, and its chunks no column.
  const fs::path older = dir / "chunk-2.h5";
  write_entry_with_journal(older, {{"format", 2},
                                   {"table_file", "table-0.h5"},
                                   {"chunk_rows", 4096},
                                   {"stored_rows", 1000},
                                   {"chunks", {{3, 1, 4096, 512}}},
                                   {"failures", nlohmann::json::array()}});
  const lsi::SweepJournalEntry e = lsi::read_journal_entry(older.string(), "journal-test");
  EXPECT_TRUE(e.whole_input_rows);
  ASSERT_EQ(e.chunks.size(), 1u);
  EXPECT_EQ(e.chunks[0].column, 0u);
  // Format 3 names its inputs' chunks: a name it does not know is refused, named.
  const fs::path odd = dir / "chunk-3.h5";
  write_entry_with_journal(odd, {{"format", 3},
                                 {"table_file", "table-0.h5"},
                                 {"chunk_rows", 4096},
                                 {"input_chunks", "diagonal"},
                                 {"stored_rows", 1000},
                                 {"chunks", nlohmann::json::array()},
                                 {"failures", nlohmann::json::array()}});
  try {
    lsi::read_journal_entry(odd.string(), "journal-test");
    FAIL() << "input_chunks \"diagonal\" read";
  } catch (const lsi::InputError& x) {
    const std::string what = x.what();
    EXPECT_NE(what.find(odd.string()), std::string::npos) << what;
    EXPECT_NE(what.find("input_chunks \"diagonal\""), std::string::npos) << what;
  }
}
