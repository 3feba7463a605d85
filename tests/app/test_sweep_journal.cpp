// The sweep's journal (app/sweep_journal.hpp): each entry held while the table file's fsync runs,
// written in chunk order only after that fsync returned, and none lost at the end of a run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "app/sweep_journal.hpp"

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

TEST(SweepJournal, HoldsEachEntryUntilFlushOrTheNextAddInChunkOrder) {
  const fs::path dir = fresh_dir("order");
  lsi::SweepJournal journal(table_file(dir).string(), header());
  const fs::path first = dir / "chunk-0.h5", second = dir / "chunk-1.h5";
  journal.add(first.string(), entry(0));
  EXPECT_FALSE(fs::exists(first)) << "held until its fsync is waited for";
  journal.add(second.string(), entry(1));
  ASSERT_TRUE(fs::exists(first));
  EXPECT_FALSE(fs::exists(second));
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
  journal.flush();  // nothing held: nothing written again
  EXPECT_EQ(lsi::read_journal_entry(second.string(), "journal-test").stored_rows, 2000u);
}

TEST(SweepJournal, TheEntryHeldIsWrittenWhenTheJournalEnds) {
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
