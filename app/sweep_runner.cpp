// The sweep runner; see sweep_runner.hpp.
#include "app/sweep_runner.hpp"

#include <unistd.h>

#include <Kokkos_Core.hpp>
#include <hdf5.h>
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <limits>
#include <optional>

#include "io/json_fields.hpp"
#include "model/concurrent_runs.hpp"
#include "model/mpm_footprint.hpp"
#include "model/mpm_impact.hpp"
#include "io/text_file.hpp"
#include "model/mpm_runner.hpp"
#include "model/progress.hpp"
#include "model/resource_estimate.hpp"
#include "app/sweep_quantile_mpm.hpp"
#include "model/sweep_statistics.hpp"
#include "model/sweep_table.hpp"
#include "sweeps/closed_form_sweep.hpp"
#include "sweeps/huge_pages.hpp"
#include "sweeps/sampler.hpp"
#include "io/resolved_scene.hpp"
#include "io/scene_parser.hpp"
#include "io/study_parser.hpp"
#include "io/sweep_file.hpp"
#include "io/sweep_table_stream.hpp"
#include "io/hdf5_io.hpp"
#include "io/output_paths.hpp"
#include "app/sweep_journal.hpp"

namespace lsi {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string chunk_file(const fs::path& parts, std::uint64_t k) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "chunk-%012llu.h5", static_cast<unsigned long long>(k));
  return (parts / buf).string();
}

// Evaluates chunks of a study in three steps: the closed forms of a chunk's samples in one kernel
// on the default execution space (closed_forms), the chunk's MPM samples, each on its own
// (run_mpm: safe to call for several samples at once), and the rows the MPM and the range check
// fill in sample order (finish).
class ChunkEvaluator {
 public:
  using Exec = Kokkos::DefaultExecutionSpace;
  using Mem = Exec::memory_space;
  using Matrix = Kokkos::View<double**, Kokkos::LayoutLeft, Mem>;

  // One MPM sample's run: its four summaries, and how it ended where it did not end well.
  struct MpmSample {
    double summaries[sweeps::closed_form_output_count] = {NAN, NAN, NAN, NAN};
    SampleStatus status = SampleStatus::ok;
    std::string reason;
    double seconds = 0.0;
  };

  // A chunk's rows on their way through the three steps; kept (and reused) from chunk to chunk.
  struct Chunk {
    std::uint64_t k = 0;
    SweepTable table;
    // Per row: the scene field the kernel's range check rejected, or -1 (`bad`, on the host).
    Kokkos::View<int*, Mem> invalid_store;
    decltype(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(),
                                                 std::declval<Kokkos::View<int*, Mem>>())) bad;
    bool any_invalid = false;
    std::vector<std::uint64_t> mpm_rows;  // the rows whose MPM runs, in order
    std::vector<MpmSample> runs;          // their runs
  };

  explicit ChunkEvaluator(const Study& s) : study_(s), sweep_(s.sampler<Mem>()) {
    sweep_.base = s.base_values;
    for (std::size_t d = 0; d < s.inputs.size(); ++d) sweep_.target[d] = s.inputs[d].field;
    sweep_.empirical = s.runs("empirical");
    sweep_.analytical = s.runs("analytical");
    // Result columns and where each comes from.
    for (const auto& m : s.methods)
      for (const auto& o : s.outputs) {
        int out = 0;
        while (sweeps::closed_form_output_name[out] != o) ++out;
        const int column = m == "empirical"    ? out
                           : m == "analytical" ? sweeps::closed_form_output_count + out
                                               : -1;
        source_.push_back({m, out, column});
      }
    for (const auto& in : s.inputs) paths_.push_back(in.path);
  }

  // A chunk with the study's columns, for closed_forms to fill.
  Chunk new_chunk() const {
    Chunk c;
    c.table = SweepTable::with_columns(paths_, study_.output_columns());
    return c;
  }

  // Chunk k's closed forms (and its inputs, index and range check) into c; the MPM columns NaN,
  // c.mpm_rows the rows whose MPM is to run (run_mpm), the rest of the rows final.
  void closed_forms(std::uint64_t k, Chunk& c) {
    const std::uint64_t first = k * study_.chunk_samples;
    const std::uint64_t count = std::min(study_.chunk_samples, study_.samples - first);
    const int dims = static_cast<int>(study_.inputs.size());
    const int columns = 2 * sweeps::closed_form_output_count;
    c.k = k;
    // On the host the kernel runs a block of samples at a time, each block's working columns
    // (its inputs, the models' inputs and outputs: a few MB) reused by the next, so that the
    // only memory a chunk touches for the first time is its table's; on a device, the chunk in
    // one launch and one copy back. A sample's values do not depend on the block it is drawn in
    // (counter-based sampling; the batched models give each sample the scalar models' bits).
    const std::uint64_t block = on_host ? std::min(count, kBlockSamples) : count;
    if (input_store_.extent(0) < block) {
      // Allocated once, for the longest block, without filling them (the kernel writes every
      // value it reads back), on huge pages where they are host memory (sweeps/huge_pages.hpp).
      input_store_ =
          Matrix(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sweep inputs"), block, dims);
      output_store_ =
          Matrix(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sweep outputs"), block, columns);
      sweeps::advise_huge_pages(input_store_);
      sweeps::advise_huge_pages(output_store_);
    }
    if (c.invalid_store.extent(0) < count) {
      c.invalid_store = Kokkos::View<int*, Mem>(
          Kokkos::view_alloc(Kokkos::WithoutInitializing, "sweep invalid field"), count);
      sweeps::advise_huge_pages(c.invalid_store);
    }

    // Columns kept from chunk to chunk: resized, not allocated anew, and every row overwritten.
    SweepTable& t = c.table;
    t.reserve(count);  // on huge pages, before the first chunk's columns are written
    t.failure_index.clear();
    t.failure_reason.clear();
    t.index.resize(count);
    t.status.assign(count, static_cast<std::int8_t>(SampleStatus::ok));
    for (int d = 0; d < dims; ++d) t.inputs[d].resize(count);
    for (auto& col : t.outputs) col.resize(count);
    double kernel_seconds = 0.0;
    for (std::uint64_t offset = 0; offset < count; offset += block) {
      const std::uint64_t m = std::min(block, count - offset);
      // A shorter block (the last) takes the front of the buffers, as views of its own extents.
      const Matrix inputs(input_store_.data(), m, dims);
      const Matrix outputs(output_store_.data(), m, columns);
      const Kokkos::View<int*, Mem> invalid(c.invalid_store.data() + offset, m);
      const auto t0 = Clock::now();
      sweeps::evaluate_closed_form_chunk(Exec(), sweep_, first + offset, inputs, outputs, invalid,
                                         columns_);
      Exec().fence();
      const auto in = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), inputs);
      const auto out = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), outputs);
      kernel_seconds += seconds_since(t0);
      copy_block(t, first, offset, m, in, out);
    }
    const Kokkos::View<int*, Mem> invalid(c.invalid_store.data(), count);
    c.bad = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), invalid);
    t.wall_time.assign(count, static_cast<float>(kernel_seconds / double(count)));
    c.any_invalid = false;
    for (std::uint64_t i = 0; i < count && !c.any_invalid; ++i) c.any_invalid = c.bad(i) >= 0;
    c.mpm_rows.clear();
    if (study_.runs("mpm"))
      for (std::uint64_t i = 0; i < count; ++i)
        if (c.bad(i) < 0) c.mpm_rows.push_back(i);
    c.runs.assign(c.mpm_rows.size(), MpmSample{});
  }

  // Runs the MPM of c's r-th MPM row (c.mpm_rows[r]) into c.runs[r]; safe to call for several
  // rows (of one chunk or several) at once.
  void run_mpm(Chunk& c, std::size_t r) const {
    const std::vector<double> x = mpm_inputs(c, r);
    c.runs[r] = run_mpm_sample(c.table.index[c.mpm_rows[r]], x.data());
  }

  // The memory MPM run r of chunk c takes (host_run_bytes of its sample's scene); 0 where the
  // sample's scene is invalid (its run reports why).
  double mpm_run_bytes(const Chunk& c, std::size_t r) const {
    try {
      return scene_run_bytes(parse_scene(sample_scene_document(study_, mpm_inputs(c, r).data())));
    } catch (const InputError&) {
      return 0.0;  // an invalid sample: its run reports why
    }
  }

  // The sample number (from 1) of MPM run r of chunk c.
  std::uint64_t mpm_sample_number(const Chunk& c, std::size_t r) const {
    return c.table.index[c.mpm_rows[r]] + 1;
  }

  // c's rows complete once its MPM rows have run: the MPM columns and the failures, in row order.
  void finish(Chunk& c) const {
    if (!c.any_invalid && c.mpm_rows.empty()) return;  // the common case: nothing per sample
    SweepTable& t = c.table;
    const int dims = static_cast<int>(study_.inputs.size());
    std::vector<double> x(dims);
    std::size_t next_run = 0;
    for (std::uint64_t i = 0; i < t.rows(); ++i) {
      if (c.bad(i) < 0) {
        if (next_run < c.mpm_rows.size() && c.mpm_rows[next_run] == i)
          take_mpm_sample(t, i, c.runs[next_run++]);
        continue;
      }
      for (int d = 0; d < dims; ++d) x[d] = t.inputs[d][i];
      std::string reason = invalid_sample_reason(study_, x.data());
      if (reason.empty())  // the kernel's range check and the scene parser disagree: a bug
        reason = std::string("rejected by the sweep's range check at ") +
                 sweeps::scene_field_pointer[c.bad(i)] + " but accepted by the scene parser";
      fail_sample(t, i, SampleStatus::invalid_input, reason);
    }
  }

 private:
  struct Source {
    std::string method;
    int output;
    int kernel_column;  // the column of the kernel's outputs, or -1 (an MPM column)
  };

  static constexpr bool on_host = Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
  // Samples in a block on the host: its working columns, about 200 bytes a sample, a few MB.
  static constexpr std::uint64_t kBlockSamples = 16384;

  // A block's rows [offset, offset + m) of the chunk's table from the kernel's columns (`in`,
  // `out`, host views of the block), by the host's threads a column each (a copy of contiguous
  // values; the rows' index generated); the MPM columns NaN (filled later).
  template <class HostMatrix>
  void copy_block(SweepTable& t, std::uint64_t first, std::uint64_t offset, std::uint64_t m,
                  const HostMatrix& in, const HostMatrix& out) const {
    struct Copy {
      double* to;
      const double* from;
    };
    Copy copies[sweeps::ClosedFormSweep<Mem>::max_inputs + 3 * sweeps::closed_form_output_count];
    std::size_t n = 0;
    for (std::size_t d = 0; d < t.inputs.size(); ++d)
      copies[n++] = {t.inputs[d].data() + offset, in.data() + d * in.stride(1)};
    for (std::size_t c = 0; c < source_.size(); ++c) {
      const int o = source_[c].kernel_column;
      copies[n++] = {t.outputs[c].data() + offset,
                     o < 0 ? nullptr : out.data() + o * out.stride(1)};
    }
    std::uint64_t* const index = t.index.data() + offset;
    const std::uint64_t start = first + offset;
    Kokkos::parallel_for(
        "lsi::sweep_chunk_table",
        Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, static_cast<std::int64_t>(n + 1)),
        [&](const std::int64_t c) {
          if (c == static_cast<std::int64_t>(n)) {
            for (std::uint64_t i = 0; i < m; ++i) index[i] = start + i;
          } else if (copies[c].from != nullptr) {
            std::copy(copies[c].from, copies[c].from + m, copies[c].to);
          } else {
            std::fill(copies[c].to, copies[c].to + m, NAN);
          }
        });
    Kokkos::DefaultHostExecutionSpace().fence();  // `copies` is captured by reference
  }

  static void fail_sample(SweepTable& t, std::uint64_t i, SampleStatus s, const std::string& why) {
    t.status[i] = static_cast<std::int8_t>(s);
    t.failure_index.push_back(t.index[i]);
    t.failure_reason.push_back(why);
  }

  // The inputs of MPM run r of chunk c.
  std::vector<double> mpm_inputs(const Chunk& c, std::size_t r) const {
    const std::size_t dims = study_.inputs.size();
    std::vector<double> x(dims);
    for (std::size_t d = 0; d < dims; ++d) x[d] = c.table.inputs[d][c.mpm_rows[r]];
    return x;
  }

  // Runs sample `index` (its inputs x); safe to call for several samples at once.
  MpmSample run_mpm_sample(std::uint64_t index, const double* x) const {
    MpmSample r;
    const auto t0 = Clock::now();
    try {
      const Scene scene = parse_scene(sample_scene_document(study_, x));
      MpmCase c = impact_case(scene);
      // The run's progress line names the sample: "mpm <scene> (sample k of n)".
      c.name +=
          " (sample " + std::to_string(index + 1) + " of " + std::to_string(study_.samples) + ")";
      const MpmOutcome o = run_mpm_case(c);
      const double v[sweeps::closed_form_output_count] = {o.result.peak_force, o.result.rise_time,
                                                          o.result.impact_duration,
                                                          o.result.final_displacement};
      std::copy(v, v + sweeps::closed_form_output_count, r.summaries);
      if (!o.finished()) {
        r.status = SampleStatus::unstable;
        r.reason = "the MPM run stopped: " + o.status();
      } else if (!has_final_displacement(o.result.end_state)) {
        r.status = SampleStatus::truncated;
        r.reason =
            "the barrier was still sliding at t = " + json_fields::format_number(o.run().end_time) +
            " s (>= " + json_fields::format_number(o.result.scalars.displacement_at_end.value()) +
            " m): " + end_state_token(o.result.end_state);
      }
    } catch (const InputError& e) {
      r.status = SampleStatus::invalid_input;
      r.reason = e.what();
    } catch (const std::exception& e) {
      r.status = SampleStatus::failed;
      r.reason = e.what();
    }
    r.seconds = seconds_since(t0);
    return r;
  }

  void take_mpm_sample(SweepTable& t, std::uint64_t i, const MpmSample& r) const {
    for (std::size_t c = 0; c < source_.size(); ++c)
      if (source_[c].method == "mpm") t.outputs[c][i] = r.summaries[source_[c].output];
    if (r.status != SampleStatus::ok) fail_sample(t, i, r.status, r.reason);
    t.wall_time[i] += static_cast<float>(r.seconds);
  }

  const Study& study_;
  sweeps::ClosedFormSweep<Mem> sweep_;
  std::vector<Source> source_;
  std::vector<std::string> paths_;
  Matrix input_store_, output_store_;
  sweeps::ClosedFormChunkColumns<Mem> columns_;  // the models' inputs, batched
};

// What the sweep does after a chunk is committed: go on, finish the runs already under way (a
// wall-time stop: the chunks whose runs have all started are committed, the later ones dropped)
// or drop every chunk started (the interval rule was met: a sequential run would not have run
// them).
enum class AfterChunk { go_on, finish_started, drop_started };

// How many MPM samples of a study run at once: one per thread (model/concurrent_runs.hpp) for a
// study of several samples, each on a thread of its own however few are left, so that a
// sample's numbers are the same in a resumed, a sharded and an uninterrupted run; a study of one
// sample runs it with every thread. At most as many as fit in the memory side by side, each
// counted at the base scene's footprint (campaign_runs_that_fit, model/mpm_footprint.hpp): large
// scenes run fewer at once, or one after the other with every thread. A sample larger than the
// base scene waits for memory as it starts (evaluate_in_order).
int sweep_runs_at_once(const Study& s) {
  return s.runs("mpm") ? campaign_runs_that_fit(static_cast<std::size_t>(s.samples), {&s.base}) : 1;
}

// Rows a run holds at most in chunks started but not yet committed (evaluate_in_order).
std::uint64_t rows_in_flight(const Study& s, int runs_at_once) {
  return runs_at_once > 1 ? 4 * std::uint64_t(runs_at_once) + s.chunk_samples : s.chunk_samples;
}

// Evaluates chunks ks (in order) and hands each, complete, to commit(k, rows) in order. The MPM
// samples run side by side, `runs` at once (sweep_runs_at_once), across chunk boundaries: each
// thread takes the next sample, evaluating the next chunk's closed forms when none is waiting,
// so that a slow sample holds back the commits, not the other threads. Chunks are started while
// fewer than rows_in_flight rows wait for their commit: at most that many finished runs are lost
// to a kill. With one run at a time, one chunk after the other on the calling thread.
void evaluate_in_order(ChunkEvaluator& evaluator, const Study& study, const int runs,
                       const std::vector<std::uint64_t>& ks,
                       const std::function<AfterChunk(std::uint64_t, const SweepTable&)>& commit) {
  // A chunk, how many of its MPM runs have not finished and how many have not started.
  struct Slot {
    ChunkEvaluator::Chunk chunk;
    std::size_t runs_left = 0, runs_waiting = 0;
    std::vector<double> run_bytes;  // each MPM run's memory (ChunkEvaluator::mpm_run_bytes)
  };
  // The memory the runs under way may take together (memory_for_runs of what is available when
  // the sweep starts); 0: no bound known, or one run at a time. A sampled
  // input may make a sample's scene larger than the base scene that `runs` was counted at: a
  // run that does not fit beside the runs under way waits until they end (one larger than its
  // share, memory_for_runs / runs, is named in a note as its chunk starts).
  const double memory_for_runs = runs > 1 ? lsi::memory_for_runs(available_memory_bytes()) : 0.0;
  double memory_in_runs = 0.0;
  const std::uint64_t most_rows = rows_in_flight(study, runs) - study.chunk_samples;
  std::mutex lock;
  std::condition_variable changed;
  std::vector<std::unique_ptr<Slot>> slots;  // every chunk's storage, reused
  std::vector<Slot*> free_slots;
  std::deque<Slot*> started;                               // in order, not yet committed
  std::deque<std::pair<Slot*, std::size_t>> waiting_runs;  // (chunk, its MPM run)
  std::size_t next = 0, running = 0;
  std::size_t to_commit = 0;  // after finish_started: the chunks of `started` still committed
  std::uint64_t started_rows = 0;
  bool committing = false, failed = false;
  AfterChunk after = AfterChunk::go_on;
  // Commits the complete chunks at the front of `started`, one thread at a time, the lock
  // released while the commit writes (the chunk still counted in started_rows).
  auto commit_ready = [&](std::unique_lock<std::mutex>& l) {
    while (!failed && !committing && !started.empty() && started.front()->runs_left == 0) {
      Slot* c = started.front();
      started.pop_front();
      if (after == AfterChunk::finish_started && to_commit == 0) after = AfterChunk::drop_started;
      if (after != AfterChunk::drop_started) {
        if (after == AfterChunk::finish_started) --to_commit;
        committing = true;
        l.unlock();
        evaluator.finish(c->chunk);
        const AfterChunk a = commit(c->chunk.k, c->chunk.table);
        l.lock();
        committing = false;
        if (a == AfterChunk::drop_started) {
          after = a;
        } else if (a == AfterChunk::finish_started && after == AfterChunk::go_on) {
          // No run starts any more: the chunks before the first with a run not yet started are
          // committed once their runs end, the others dropped.
          after = a;
          to_commit = 0;
          while (to_commit < started.size() && started[to_commit]->runs_waiting == 0) ++to_commit;
        }
        if (after != AfterChunk::go_on) waiting_runs.clear();
      }
      started_rows -= c->chunk.table.rows();
      free_slots.push_back(c);
    }
    changed.notify_all();
  };
  auto worker = [&](std::size_t) {
    std::unique_lock<std::mutex> l(lock);
    try {
      while (!failed) {
        bool run_fits = !waiting_runs.empty();
        if (run_fits && running > 0 && memory_for_runs > 0.0) {
          const auto [c, r] = waiting_runs.front();
          run_fits = memory_in_runs + c->run_bytes[r] <= memory_for_runs;
        }
        if (run_fits) {
          const auto [c, r] = waiting_runs.front();
          waiting_runs.pop_front();
          --c->runs_waiting;
          ++running;
          const double bytes = c->run_bytes[r];
          memory_in_runs += bytes;
          l.unlock();
          evaluator.run_mpm(c->chunk, r);
          l.lock();
          memory_in_runs -= bytes;
          --running;
          --c->runs_left;
          commit_ready(l);
        } else if (after == AfterChunk::go_on && next < ks.size() &&
                   (started.empty() || started_rows < most_rows)) {
          if (free_slots.empty()) {
            slots.push_back(std::make_unique<Slot>(Slot{evaluator.new_chunk(), 0, 0, {}}));
            free_slots.push_back(slots.back().get());
          }
          Slot* c = free_slots.back();
          free_slots.pop_back();
          // The closed forms under the lock: one chunk at a time (the evaluator's buffers).
          evaluator.closed_forms(ks[next++], c->chunk);
          c->runs_left = c->runs_waiting = c->chunk.mpm_rows.size();
          c->run_bytes.assign(c->runs_left, 0.0);
          if (memory_for_runs > 0.0)
            for (std::size_t r = 0; r < c->runs_left; ++r) {
              c->run_bytes[r] = evaluator.mpm_run_bytes(c->chunk, r);
              if (c->run_bytes[r] > memory_for_runs / runs)  // larger than its share
                std::fprintf(
                    stderr,
                    "lsi: note: sample %llu needs %s for its MPM run, more than its "
                    "share of half the memory (%s of %s): it runs beside fewer runs, "
                    "alone if need be\n",
                    static_cast<unsigned long long>(evaluator.mpm_sample_number(c->chunk, r)),
                    format_bytes(c->run_bytes[r]).c_str(),
                    format_bytes(memory_for_runs / runs).c_str(),
                    format_bytes(memory_for_runs).c_str());
            }
          for (std::size_t r = 0; r < c->runs_left; ++r) waiting_runs.emplace_back(c, r);
          started.push_back(c);
          started_rows += c->chunk.table.rows();
          commit_ready(l);
        } else if (running == 0 && !committing) {
          return;  // nothing to run, to start or to commit
        } else {
          changed.wait(l);
        }
      }
    } catch (...) {
      if (!l.owns_lock()) l.lock();
      failed = true;
      changed.notify_all();
      throw;
    }
  };
  run_concurrently(static_cast<std::size_t>(runs), worker, runs);
}

// The column of the interval rule among the table's outputs (or -1).
int rule_column(const Study& s, const SweepTable& t) {
  if (!s.stop.has_interval_rule) return -1;
  const std::string name = s.stop.method + "/" + s.stop.output;
  for (std::size_t c = 0; c < t.output_columns.size(); ++c)
    if (t.output_columns[c] == name) return static_cast<int>(c);
  return -1;
}

void collect_rule_values(const Study& s, const SweepTable& t, std::vector<double>& values) {
  const int c = rule_column(s, t);
  if (c < 0) return;
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (t.status[i] == static_cast<std::int8_t>(SampleStatus::ok))
      values.push_back(t.outputs[c][i]);
}

SweepHeader header_of(const Study& s, int shard, int shard_count) {
  SweepHeader h;
  h.study = s.source;
  h.scene_resolved = resolved_scene_json(s.base);
  h.fingerprint = s.fingerprint;
  h.planned_samples = s.samples;
  h.chunk_samples = s.chunk_samples;
  h.shard = shard;
  h.shard_count = shard_count;
  return h;
}

// Checks the rows of shard files against their study before they are merged: every sample index
// within the study and in a chunk of the shard that holds it, a known status, and the inputs
// bitwise those the study's sampler draws for the index (sampling is counter-based, so a row's
// inputs are a function of its index). A file edited or damaged since it was written fails here
// with the first row that differs. Throws InputError.
void check_shard_rows(const Study& study, const std::string& file, const SweepHeader& h,
                      const SweepTable& t) {
  auto fail = [&](std::size_t row, const std::string& why) {
    throw InputError(file + ": row " + std::to_string(row) + " (sample " +
                     std::to_string(t.index[row]) + ") " + why +
                     ": the file was changed or damaged after it was written; run the shard "
                     "again");
  };
  if (t.input_paths.size() != study.inputs.size())
    throw InputError(file + ": " + std::to_string(t.input_paths.size()) +
                     " input columns, the study has " + std::to_string(study.inputs.size()));
  for (std::size_t d = 0; d < study.inputs.size(); ++d)
    if (t.input_paths[d] != study.inputs[d].path)
      throw InputError(file + ": input column " + std::to_string(d) + " is " + t.input_paths[d] +
                       ", the study's is " + study.inputs[d].path);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const std::uint64_t k = t.index[i];
    if (k >= study.samples)
      fail(i, "lies beyond the study's " + std::to_string(study.samples) + " samples");
    if ((k / study.chunk_samples) % std::uint64_t(h.shard_count) != std::uint64_t(h.shard))
      fail(i, "belongs to another shard than " + std::to_string(h.shard) + "/" +
                  std::to_string(h.shard_count));
    if (t.status[i] < 0 || t.status[i] > static_cast<std::int8_t>(SampleStatus::truncated))
      fail(i, "has an unknown status " + std::to_string(int(t.status[i])));
  }
  ensure_kokkos();
  const auto sampler = study.sampler<Kokkos::HostSpace>();
  const int dims = static_cast<int>(study.inputs.size());
  std::int64_t first_bad = std::numeric_limits<std::int64_t>::max();
  Kokkos::parallel_reduce(
      "lsi::check_shard_rows",
      Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0,
                                                             static_cast<std::int64_t>(t.rows())),
      [&](const std::int64_t i, std::int64_t& bad) {
        double x[sweeps::Sampler<Kokkos::HostSpace>::max_dimensions];
        sampler.sample(t.index[i], x);
        for (int d = 0; d < dims; ++d)
          if (!(x[d] == t.inputs[d][i]) && i < bad) bad = i;
      },
      Kokkos::Min<std::int64_t>(first_bad));
  if (first_bad != std::numeric_limits<std::int64_t>::max()) {
    const std::size_t i = static_cast<std::size_t>(first_bad);
    double x[sweeps::Sampler<Kokkos::HostSpace>::max_dimensions];
    sampler.sample(t.index[i], x);
    int d = 0;
    while (x[d] == t.inputs[d][i]) ++d;
    fail(i, "has " + study.inputs[d].path + " = " + json_fields::format_number(t.inputs[d][i]) +
                " where the study's sampler draws " + json_fields::format_number(x[d]));
  }
}

// Refuses, before anything is written, a run whose rows cannot be held in memory or whose files
// cannot fit beside `out` (the result's table, and its copy when the run stops early: at most
// twice the table). In memory: the rows of the chunks under way (rows_in_flight) and a chunk's
// rows again (the kernel's on a device; on the host its blocks take a few MB, so that this
// bounds it from above), and the values the statistics keep (sweeps/column_accumulator.hpp: the
// first values of each output column and a few per cent of the rest; 4 % is counted). The whole
// table is held instead (twice, plus a column) where the MPM runs again at the quantiles, and
// once more beside the chunks where the statistics may read it back (designs whose samples do
// not come in random order).
void check_sweep_fits(const Study& s, const SweepOptions& opt, const int runs_at_once) {
  const std::uint64_t chunks = (s.samples + s.chunk_samples - 1) / s.chunk_samples;
  const std::uint64_t n = static_cast<std::uint64_t>(opt.shard_count);
  const std::uint64_t shard = static_cast<std::uint64_t>(opt.shard);
  const std::uint64_t my_chunks = shard < chunks ? (chunks - shard + n - 1) / n : 0;
  double rows = double(my_chunks) * double(s.chunk_samples);
  if (chunks > 0 && (chunks - 1) % n == shard) rows -= double(chunks * s.chunk_samples - s.samples);
  // index (8), status (1), wall time (4), one double per input and per output column.
  const double row_bytes = 13.0 + 8.0 * double(s.inputs.size() + s.output_columns().size());
  const double table = rows * row_bytes;
  const double columns = double(s.output_columns().size());
  const bool describe_here = opt.shard_count == 1;
  const bool keep_rows = describe_here && s.mpm_at_quantiles.has_value();
  const bool may_read_back =
      describe_here && (s.design == sweeps::Design::Grid || s.design == sweeps::Design::Points);
  const double in_flight = double(rows_in_flight(s, runs_at_once));
  const double chunk =
      (std::min(rows, in_flight) + std::min(rows, double(s.chunk_samples))) * row_bytes;
  double memory = chunk;
  std::string what = "a chunk's rows (" + json_fields::format_number(row_bytes) + " bytes each)";
  if (keep_rows) {
    memory = 2.0 * table + 8.0 * rows;
    what = "the sweep table (" + json_fields::format_number(rows) + " rows of " +
           json_fields::format_number(row_bytes) + " bytes, held twice)";
  } else if (describe_here) {
    memory += 8.0 * columns * (double(sweeps::stats::kShiftValues) + 0.04 * rows);
    what += " and the statistics' values";
    if (may_read_back) {
      memory += table;
      what += " and the table, read back for the quantiles of a " +
              std::string(s.design == sweeps::Design::Grid ? "grid" : "points") + " design";
    }
  }
  const std::string value = json_fields::format_number(double(s.samples));
  const std::string remedy = opt.shard_count > 1
                                 ? "more shards (--shard i/N) or fewer samples"
                                 : "fewer samples, or shards (--shard i/N) on several machines";
  require_fits("samples", value, what, memory, available_memory_bytes(), "memory", remedy);
  require_fits("samples", value, "the result file and its copy at a stop", 2.0 * table,
               free_disk_bytes(opt.out), "disk where --out goes", remedy + ", or another --out");
}

}  // namespace

void parse_shard(const std::string& text, int& shard, int& shard_count) {
  int i = -1, n = -1;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &tail) != 2 || n < 1 || i < 0 || i >= n)
    throw InputError("--shard " + text + ": must be i/N with 0 <= i < N (e.g. 0/4)");
  shard = i;
  shard_count = n;
}

SweepOutcome run_sweep(const Study& study, const SweepOptions& opt) {
  const auto t0 = Clock::now();
  if (opt.out.empty()) throw InputError("--out: required (the HDF5 result file)");
  if (opt.shard_count > 1 && study.stop.has_interval_rule)
    throw InputError(
        "stop.interval: a sharded run cannot stop on a confidence interval (each "
        "shard sees only its samples); run unsharded or drop the rule");
  // Shards take whole chunks in turn: with fewer chunks than shards some would have no work.
  const std::uint64_t chunk_count = (study.samples + study.chunk_samples - 1) / study.chunk_samples;
  if (std::uint64_t(opt.shard_count) > chunk_count) {
    const std::uint64_t most = (study.samples + opt.shard_count - 1) / opt.shard_count;
    throw InputError("chunk_samples = " + std::to_string(study.chunk_samples) + ": the study's " +
                     std::to_string(study.samples) + " samples make " +
                     std::to_string(chunk_count) + " chunk(s), fewer than the " +
                     std::to_string(opt.shard_count) +
                     " shards (or MPI ranks), which take whole chunks: some would have no work; "
                     "set chunk_samples <= " +
                     std::to_string(most) + " in the study, or use at most " +
                     std::to_string(chunk_count) + " shard(s)");
  }
  // How many MPM samples run at once, for the memory check and the run.
  const int runs_at_once = sweep_runs_at_once(study);
  const fs::path parts = opt.out + ".parts";
  const fs::path marker = parts / "sweep.json";
  const json identity = {
      {"fingerprint", study.fingerprint}, {"shard", opt.shard}, {"shard_count", opt.shard_count}};
  SweepOutcome outcome;
  // A finished run renames its parts directory before removing it; a kill during the removal
  // leaves this, which is never needed again.
  const fs::path removed_parts = parts.string() + ".removing";
  if (fs::exists(removed_parts)) fs::remove_all(removed_parts);
  // Resuming a run that already finished reports what it wrote.
  auto finished_run = [&]() -> std::optional<SweepOutcome> {
    if (!opt.resume || !fs::exists(opt.out)) return std::nullopt;
    const SweepFile done = read_sweep_file(opt.out);
    if (done.header.fingerprint != study.fingerprint)
      throw InputError(opt.out + ": written by another study (fingerprint " +
                       done.header.fingerprint + ", this study " + study.fingerprint + ")");
    if (!done.header.complete || done.header.shard != opt.shard ||
        done.header.shard_count != opt.shard_count)
      return std::nullopt;
    SweepOutcome o;
    o.complete = true;
    o.stopped_by = done.header.stopped_by;
    o.samples_done = done.table.rows();
    o.statistics = done.statistics;
    if (done.statistics.is_object()) o.samples_ok = done.statistics.value("samples_ok", 0ull);
    return o;
  };

  if (fs::exists(parts)) {
    if (!opt.resume)
      throw InputError(parts.string() +
                       ": an earlier run of this sweep did not finish; "
                       "--resume continues it (or delete the directory to start again)");
    json found;
    try {
      std::ifstream f(marker);
      found = json::parse(f);
    } catch (const std::exception&) {
      // A finished run killed while it removed its parts (the marker may be gone first).
      if (auto done = finished_run()) {
        fs::remove_all(parts);
        return *done;
      }
      throw InputError(parts.string() + ": not a sweep's parts directory (no readable sweep.json)");
    }
    if (found != identity)
      throw InputError(parts.string() + ": left by another study or shard (" + found.dump() +
                       "; this run: " + identity.dump() + ")");
  } else {
    if (auto done = finished_run()) return *done;
    check_sweep_fits(study, opt, runs_at_once);
    fs::create_directories(parts);
    write_text_atomically(marker, identity.dump() + "\n");
  }
  // Leftovers of a killed run: temporary files are never complete.
  for (const auto& e : fs::directory_iterator(parts))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(e.path());

  const std::uint64_t chunks = (study.samples + study.chunk_samples - 1) / study.chunk_samples;
  std::vector<std::uint64_t> mine;
  for (std::uint64_t k = opt.shard; k < chunks; k += opt.shard_count) mine.push_back(k);
  std::uint64_t my_samples = 0, done_samples = 0;
  auto rows_of_chunk = [&](std::uint64_t k) {
    return std::min(study.chunk_samples, study.samples - k * study.chunk_samples);
  };
  for (std::uint64_t k : mine) my_samples += rows_of_chunk(k);

  // The result's table is written as the chunks finish, into a table file in the parts
  // directory, new for each invocation: a resumed run copies into it the compressed chunks its
  // predecessors journalled (the chunks done: in order, so the journal's first entries), then
  // goes on. The table file becomes `out` when the run is complete.
  std::vector<std::string> paths;
  for (const auto& in : study.inputs) paths.push_back(in.path);
  std::vector<bool> done(mine.size(), false);
  std::vector<SweepJournalEntry> earlier;
  for (std::size_t m = 0; m < mine.size(); ++m) {
    const std::string f = chunk_file(parts, mine[m]);
    if (!fs::exists(f)) break;
    earlier.push_back(read_journal_entry(f, study.fingerprint));
    done[m] = true;
    done_samples += rows_of_chunk(mine[m]);
  }
  for (std::size_t m = earlier.size(); m < mine.size(); ++m)  // after a gap: run again
    fs::remove(chunk_file(parts, mine[m]));
  int generation = 0;
  std::vector<fs::path> old_tables;
  for (const auto& e : fs::directory_iterator(parts)) {
    int g = -1;
    char tail = 0;
    if (std::sscanf(e.path().filename().c_str(), "table-%d.h%c", &g, &tail) == 2 && g >= 0) {
      generation = std::max(generation, g + 1);
      old_tables.push_back(e.path());
    }
  }
  const std::string table_name = "table-" + std::to_string(generation) + ".h5";
  // A resumed run goes on with the chunk rows and the inputs' chunks its predecessors journalled
  // (entries that do not say were written with the rule's chunks for rows arriving one at a
  // time).
  std::uint64_t chunk_rows =
      SweepTableStream::chunk_rows_for(paths.size(), my_samples, study.chunk_samples);
  bool whole_input_rows = false;
  if (!earlier.empty()) {
    for (auto& e : earlier)
      if (e.chunk_rows == 0)
        e.chunk_rows = SweepTableStream::chunk_rows_for(paths.size(), my_samples, 1);
    chunk_rows = earlier.front().chunk_rows;
    whole_input_rows = earlier.front().whole_input_rows;
    auto chunks_of = [](const SweepJournalEntry& e) {
      return std::to_string(e.chunk_rows) + " rows" +
             (e.whole_input_rows ? " (the inputs' whole rows)" : " (the inputs' columns)");
    };
    for (std::size_t m = 0; m < earlier.size(); ++m)
      if (earlier[m].chunk_rows != chunk_rows || earlier[m].whole_input_rows != whole_input_rows)
        throw InputError(chunk_file(parts, mine[m]) + ": journals chunks of " +
                         chunks_of(earlier[m]) + ", " + chunk_file(parts, mine[0]) + " of " +
                         chunks_of(earlier.front()) +
                         "; delete the parts directory to start the sweep again");
  }
  SweepTableStream table((parts / table_name).string(), paths, study.output_columns(), my_samples,
                         chunk_rows, whole_input_rows);
  const SweepHeader chunk_header = header_of(study, opt.shard, opt.shard_count);
  std::vector<StoredChunk> stored;  // every compressed chunk of the table, where it lies
  // The rows go into the statistics as they finish (model/sweep_statistics.hpp), and are not
  // kept; only where the MPM runs again at the quantiles (study.mpm_at_quantiles), which needs
  // their inputs, are they kept whole. A shard has no statistics (merge describes the shards'
  // rows together).
  const bool describe_here = opt.shard_count == 1;
  const bool keep_rows = describe_here && study.mpm_at_quantiles.has_value();
  SweepTable all = SweepTable::with_columns(paths, study.output_columns());  // keep_rows only
  std::optional<SweepStatisticsAccumulator> accumulator;
  if (describe_here && !keep_rows) accumulator.emplace(study, study.output_columns());
  std::vector<std::uint64_t> failure_index;
  std::vector<std::string> failure_reason;
  std::uint64_t rows_done = 0, rows_ok = 0;
  auto gather = [&](const SweepTable& rows) {
    if (keep_rows)
      all.append(rows);
    else if (accumulator)
      accumulator->add(rows);
    failure_index.insert(failure_index.end(), rows.failure_index.begin(), rows.failure_index.end());
    failure_reason.insert(failure_reason.end(), rows.failure_reason.begin(),
                          rows.failure_reason.end());
    rows_done += rows.rows();
    for (const std::int8_t s : rows.status) rows_ok += s == std::int8_t(SampleStatus::ok);
  };
  std::vector<double> rule_values;  // the values the interval rule has seen so far
  if (!earlier.empty()) {
    for (auto& e : earlier) {
      e.chunks = table.adopt((parts / e.table_file).string(), e.chunks);
      e.table_file = table_name;
      e.chunk_rows = chunk_rows;
      e.whole_input_rows = whole_input_rows;
      stored.insert(stored.end(), e.chunks.begin(), e.chunks.end());
      failure_index.insert(failure_index.end(), e.failure_index.begin(), e.failure_index.end());
      failure_reason.insert(failure_reason.end(), e.failure_reason.begin(), e.failure_reason.end());
    }
    table.restore(earlier.back().stored_rows, earlier.back().pending);
    hdf5::fsync_file(table.path());
    for (std::size_t m = 0; m < earlier.size(); ++m)
      write_journal_entry(chunk_file(parts, mine[m]), chunk_header, earlier[m]);
    SweepTable rows = table.read_stored();
    rows.append(table.pending());
    rows.failure_index.clear();
    rows.failure_reason.clear();
    gather(rows);
    collect_rule_values(study, rows, rule_values);
    earlier.clear();
  }
  for (const auto& t : old_tables) fs::remove(t);
  if (keep_rows) all.reserve(my_samples);

  ensure_kokkos();
  ChunkEvaluator evaluator(study);
  SampleProgress progress("sweep " + study.name, my_samples, opt.progress);
  std::string stopped_by;
  bool rule_met = false;
  std::uint64_t run_here = 0;
  double evaluate_s = 0.0, write_s = 0.0, gather_s = 0.0;
  // Each chunk's entry is written on the journal's thread once the table file's fsync has
  // returned, while the chunk's rows are described and the next chunk is evaluated; the journal
  // is waited for before the table file takes the next rows (HDF5 from one thread at a time).
  SweepJournal journal(table.path(), chunk_header);
  std::vector<std::uint64_t> to_do;
  std::size_t m = 0;  // the next chunk to commit, in `mine`
  while (m < mine.size() && done[m]) ++m;
  for (std::size_t i = m; i < mine.size(); ++i) to_do.push_back(mine[i]);
  bool out_of_time = false;
  double commit_s = 0.0;
  const auto pipeline_start = Clock::now();
  evaluate_in_order(evaluator, study, runs_at_once, to_do,
                    [&](std::uint64_t k, const SweepTable& t) {
                      const auto tc = Clock::now();
                      auto ts = tc;
                      journal.flush();
                      SweepJournalEntry entry;
                      entry.table_file = table_name;
                      entry.chunk_rows = chunk_rows;
                      entry.whole_input_rows = whole_input_rows;
                      entry.chunks = table.append(t);
                      entry.stored_rows = table.stored_rows();
                      entry.pending = table.pending();
                      entry.failure_index = t.failure_index;
                      entry.failure_reason = t.failure_reason;
                      stored.insert(stored.end(), entry.chunks.begin(), entry.chunks.end());
                      journal.add(chunk_file(parts, k), std::move(entry));
                      write_s += seconds_since(ts);
                      done[m++] = true;  // chunks come in order: k is mine[m]
                      done_samples += t.rows();
                      run_here += t.rows();
                      progress.update(done_samples, run_here);
                      collect_rule_values(study, t, rule_values);
                      ts = Clock::now();
                      gather(t);
                      gather_s += seconds_since(ts);
                      std::string why;
                      AfterChunk after = AfterChunk::go_on;
                      if (interval_rule_met(study, rule_values, why)) {
                        rule_met = true;
                        stopped_by = why;
                        after = AfterChunk::drop_started;
                      } else if (seconds_since(t0) > study.stop.wall_time_s) {
                        out_of_time = true;
                        after = AfterChunk::finish_started;
                      }
                      commit_s += seconds_since(tc);
                      return after;
                    });
  evaluate_s = seconds_since(pipeline_start) - commit_s;
  if (out_of_time && !rule_met && std::find(done.begin(), done.end(), false) != done.end())
    stopped_by = "wall time: stop.wall_time_s = " + json(study.stop.wall_time_s).dump() +
                 " s reached; --resume continues";

  auto ts = Clock::now();
  journal.flush();
  write_s += seconds_since(ts);
  progress.finishing("writing the result file");
  ts = Clock::now();
  all.sort_by_index();
  // The interval rule ends the sweep where it was met: later chunks (none in a sequential run)
  // would not be part of the answer.
  const bool complete = rule_met || std::find(done.begin(), done.end(), false) == done.end();

  SweepHeader h = header_of(study, opt.shard, opt.shard_count);
  h.complete = complete;
  h.stopped_by = stopped_by;
  h.wall_seconds = seconds_since(t0);
  outcome.complete = complete;
  outcome.stopped_by = stopped_by;
  outcome.samples_done = rows_done;
  outcome.samples_run = run_here;
  outcome.samples_ok = rows_ok;
  gather_s += seconds_since(ts);
  ts = Clock::now();
  // The table file's rows, read back only where a column's quantiles need all its values.
  std::optional<SweepTable> whole;
  const auto whole_table = [&]() -> const SweepTable& {
    whole = table.read_stored();
    whole->append(table.pending());
    return *whole;
  };
  if (keep_rows)
    outcome.statistics = sweep_statistics(study, all);
  else if (accumulator)
    outcome.statistics = accumulator->result(whole_table);
  whole.reset();
  const double statistics_s = seconds_since(ts);
  ts = Clock::now();
  if (opt.shard_count == 1 && complete && study.mpm_at_quantiles)
    outcome.statistics["mpm_at_quantiles"] = mpm_at_quantiles(study, all);
  const double quantile_mpm_s = seconds_since(ts);
  ts = Clock::now();
  const nlohmann::json* statistics = outcome.statistics.is_null() ? nullptr : &outcome.statistics;
  if (complete) {
    // The table file, finished, becomes `out`; the parts are renamed before their removal: a
    // kill during the removal leaves no parts to resume.
    if (const std::string why = unsafe_output_reason(opt.out); !why.empty())
      throw std::runtime_error("lsi sweep: cannot write '" + opt.out + "': " + why);
    table.finish(h, failure_index, failure_reason, statistics);
    hdf5::fsync_file(table.path());
    if (std::rename(table.path().c_str(), opt.out.c_str()) != 0)
      throw std::runtime_error("lsi sweep: cannot rename '" + table.path() + "' onto '" + opt.out +
                               "': " + std::strerror(errno));
    hdf5::fsync_directory(fs::absolute(opt.out).parent_path());
    fs::rename(parts, removed_parts);
    fs::remove_all(removed_parts);
  } else {
    // Stopped before the end: `out` holds the rows so far, copied (still compressed) from the
    // table file, which the journal keeps for --resume.
    hdf5::write_atomically(opt.out, "lsi sweep", [&](const std::string& tmp) {
      SweepTableStream copy(tmp, paths, study.output_columns(), table.rows(), chunk_rows,
                            whole_input_rows);
      copy.adopt(table.path(), stored);
      copy.restore(table.stored_rows(), table.pending());
      copy.finish(h, failure_index, failure_reason, statistics);
    });
  }
  gather_s += seconds_since(ts);
  outcome.seconds = {{"evaluate", evaluate_s},
                     {"write_chunks", write_s},
                     {"gather", gather_s},
                     {"statistics", statistics_s},
                     {"mpm_at_quantiles", quantile_mpm_s}};
  outcome.wall_seconds = seconds_since(t0);
  return outcome;
}

SweepOutcome merge_sweeps(const std::vector<std::string>& files, const std::string& out) {
  const auto t0 = Clock::now();
  if (files.empty()) throw InputError("merge: no shard files given");
  std::vector<SweepFile> shards;
  for (const auto& f : files) {
    std::error_code ec;
    if (!fs::exists(f, ec)) throw InputError(f + ": shard file not found");
    if (!fs::is_regular_file(f, ec))
      throw InputError(f + ": not a regular file (a shard result file of lsi sweep --shard i/N)");
    if (H5Fis_hdf5(f.c_str()) <= 0)
      throw InputError(f + ": not an HDF5 file (a shard result file of lsi sweep --shard i/N)");
    shards.push_back(read_sweep_file(f));
  }
  const SweepHeader& h0 = shards.front().header;
  std::vector<bool> seen(h0.shard_count, false);
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const SweepHeader& h = shards[k].header;
    if (h.fingerprint != h0.fingerprint)
      throw InputError(files[k] + ": another study than " + files[0] + " (fingerprint " +
                       h.fingerprint + " vs " + h0.fingerprint + ")");
    if (h.shard_count != h0.shard_count)
      throw InputError(files[k] + ": shard " + std::to_string(h.shard) + "/" +
                       std::to_string(h.shard_count) + ", but " + files[0] + " is of " +
                       std::to_string(h0.shard_count) + " shards");
    if (seen[h.shard])
      throw InputError(files[k] + ": shard " + std::to_string(h.shard) + " given twice");
    if (!h.complete)
      throw InputError(files[k] + ": shard " + std::to_string(h.shard) +
                       " is not complete (resume it first: lsi sweep ... --shard " +
                       std::to_string(h.shard) + "/" + std::to_string(h.shard_count) +
                       " --resume)");
    seen[h.shard] = true;
  }
  for (int s = 0; s < h0.shard_count; ++s)
    if (!seen[s])
      throw InputError("merge: shard " + std::to_string(s) + "/" + std::to_string(h0.shard_count) +
                       " is missing");
  SweepTable all = shards.front().table;
  for (std::size_t k = 1; k < shards.size(); ++k) all.append(shards[k].table);
  all.sort_by_index();
  const Study study = parse_study(h0.study, "");
  if (study.fingerprint != h0.fingerprint)
    throw std::runtime_error("merge: the stored study does not reproduce its fingerprint (" +
                             study.fingerprint + " vs " + h0.fingerprint + ")");
  for (std::size_t k = 0; k < shards.size(); ++k)
    check_shard_rows(study, files[k], shards[k].header, shards[k].table);
  if (all.rows() != study.samples)  // each row is in its shard, none twice: a row is missing
    throw InputError("merge: the shards hold " + std::to_string(all.rows()) +
                     " samples, the study " + std::to_string(study.samples) +
                     ": a shard file lost rows after it was written");
  SweepOutcome outcome;
  SweepHeader h = header_of(study, 0, 1);
  h.complete = true;
  for (const auto& s : shards) h.wall_seconds = std::max(h.wall_seconds, s.header.wall_seconds);
  outcome.complete = true;
  outcome.samples_done = all.rows();
  for (auto s : all.status) outcome.samples_ok += s == static_cast<std::int8_t>(SampleStatus::ok);
  outcome.statistics = sweep_statistics(study, all);
  if (study.mpm_at_quantiles) outcome.statistics["mpm_at_quantiles"] = mpm_at_quantiles(study, all);
  write_sweep_file(out, h, all, &outcome.statistics);
  outcome.wall_seconds = seconds_since(t0);
  return outcome;
}

}  // namespace lsi
