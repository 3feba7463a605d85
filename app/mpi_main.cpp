// `lsi-mpi`: the shards of one sweep on the ranks of an MPI job (docs/guide/mpi.md).
//
//   mpirun -np N -x OMP_NUM_THREADS=T lsi-mpi STUDY --out F [--resume] [--format table|json]
//
// Rank r runs shard r/N of the study (app/sweep_runner.hpp) into `F.rank<r>-of-<N>.h5`, its
// chunks in `F.rank<r>-of-<N>.h5.parts` as `lsi sweep --shard r/N` would; `--resume` is passed
// to every rank, so a killed MPI job resumes where each rank stopped. When every rank is done,
// rank 0 merges the shard files into F (merge_sweeps: the file an unsharded `lsi sweep` writes,
// wall times aside), prints the summary as `lsi sweep` does and removes the shard files. The
// ranks need a shared file system for F (rank 0 reads every shard file).
//
// Exit codes as for `lsi`: 0 success, 2 invalid input, 1 any other failure. The ranks agree on
// the outcome of each phase (load the study, run the shard, merge) with a collective before the
// next one, and all exit with the worst code; rank 0 prints each distinct error message once. A
// rank whose shard fails does not stop the others: they finish their shards (kept for --resume).
// Shards stopped by the study's wall-time limit are not merged: the run reports "incomplete"
// (exit 0, as `lsi sweep` does) and `--resume` continues it.
//
// Threads: each rank runs Kokkos with OpenMP and takes OMP_NUM_THREADS from its environment
// (`mpirun -x OMP_NUM_THREADS=...` forwards it to every rank; with N ranks on C cores use C/N).
#include <CLI/CLI.hpp>
// The C API only: OpenMPI's and MPICH's mpi.h otherwise declare the (deprecated) C++ bindings,
// which need a library CMake's MPI::MPI_C does not link.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/openmp_wait_policy.hpp"
#include "io/provenance.hpp"
#include "model/scene.hpp"
#include "model/study.hpp"
#include "app/subcommand.hpp"
#include "app/sweep_runner.hpp"
#include "app/sweep_report.hpp"
#include "model/sweep_table.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time
#include "io/study_parser.hpp"
#include "io/sweep_file.hpp"

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// What one phase came to on this rank: an exit code (0, 1, 2) and, if not 0, the message.
struct Status {
  int code = 0;
  std::string message;
};

template <class F>
Status guarded(F&& f) {
  try {
    f();
    return {};
  } catch (const lsi::InputError& e) {
    return {2, std::string("error: ") + e.what()};
  } catch (const std::exception& e) {
    return {1, std::string("failed: ") + e.what()};
  }
}

// Collective: the worst exit code of the ranks. Rank 0 prints each distinct message once, in the
// order of the first rank that reported it, naming the ranks unless every rank reported it.
int agree(const Status& s, int rank, int size) {
  int worst = 0;
  MPI_Allreduce(&s.code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (worst == 0) return 0;
  const int len = s.code == 0 ? 0 : static_cast<int>(s.message.size());
  std::vector<int> lens(rank == 0 ? size : 0), displs(rank == 0 ? size : 0);
  MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      displs[r] = total;
      total += lens[r];
    }
    all.resize(total);
  }
  MPI_Gatherv(s.message.data(), len, MPI_CHAR, all.data(), lens.data(), displs.data(), MPI_CHAR, 0,
              MPI_COMM_WORLD);
  if (rank == 0) {
    std::vector<std::pair<std::string, std::vector<int>>> distinct;
    for (int r = 0; r < size; ++r) {
      if (lens[r] == 0) continue;
      const std::string m = all.substr(displs[r], lens[r]);
      auto it =
          std::find_if(distinct.begin(), distinct.end(), [&](auto& d) { return d.first == m; });
      if (it == distinct.end())
        distinct.push_back({m, {r}});
      else
        it->second.push_back(r);
    }
    for (const auto& [m, ranks] : distinct) {
      std::string who;
      if (static_cast<int>(ranks.size()) != size) {
        who = ranks.size() == 1 ? "rank " : "ranks ";
        for (std::size_t k = 0; k < ranks.size(); ++k)
          who += (k ? "," : "") + std::to_string(ranks[k]);
        who += ": ";
      }
      std::cerr << "lsi-mpi: " << who << m << "\n";
    }
    std::cerr.flush();
  }
  return worst;
}

std::string shard_file(const std::string& out, int rank, int size) {
  return out + ".rank" + std::to_string(rank) + "-of-" + std::to_string(size) + ".h5";
}

// The summary `lsi sweep` prints, plus the number of ranks.
void report(const lsi::SweepOutcome& o, const std::string& out, const std::string& format,
            int ranks) {
  if (format == "json")
    std::cout << lsi::sweep_outcome_json(o, out, ranks).dump(2) << "\n";
  else
    std::cout << lsi::sweep_outcome_text(o, out, ranks);
  std::cout.flush();
}

struct Args {
  std::string study, out, format = "table";
  bool resume = false;
};

int run(const CLI::App& app, const Args& args, int rank, int size) {
  const auto t0 = Clock::now();
  const auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };

  // 1. Every rank loads the study (a bad study stops the job before any work).
  lsi::Study study;
  Status s = guarded([&] {
    if (args.format != "table" && args.format != "json")
      throw lsi::InputError("--format " + args.format + ": allowed: table, json");
    lsi::reject_empty_values(app);
    if (args.out.empty()) throw lsi::InputError("--out: required (the HDF5 result file)");
    study = lsi::load_study(args.study);
  });
  if (int code = agree(s, rank, size)) return code;

  // A resumed job whose merge already happened (killed while removing the shard files): the
  // result is F; report it.
  int finished = 0;
  lsi::SweepOutcome done;
  if (rank == 0 && args.resume && fs::exists(args.out)) {
    s = guarded([&] {
      const lsi::SweepFile f = lsi::read_sweep_file(args.out);
      if (f.header.fingerprint != study.fingerprint)
        throw lsi::InputError(args.out + ": written by another study (fingerprint " +
                              f.header.fingerprint + ", this study " + study.fingerprint + ")");
      if (f.header.complete && f.header.shard_count == 1) {
        finished = 1;
        done.complete = true;
        done.stopped_by = f.header.stopped_by;
        done.samples_done = f.table.rows();
        done.statistics = f.statistics;
        if (f.statistics.is_object()) done.samples_ok = f.statistics.value("samples_ok", 0ull);
      }
    });
  }
  if (int code = agree(s, rank, size)) return code;
  MPI_Bcast(&finished, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (finished) {
    if (rank == 0) {
      for (int r = 0; r < size; ++r) {
        std::error_code ec;
        fs::remove(shard_file(args.out, r, size), ec);
      }
      done.wall_seconds = since(t0);
      report(done, args.out, args.format, size);
    }
    return 0;
  }

  // 2. Rank r runs shard r/N.
  lsi::SweepOutcome mine;
  s = guarded([&] {
    lsi::SweepOptions o;
    o.out = shard_file(args.out, rank, size);
    o.resume = args.resume;
    o.shard = rank;
    o.shard_count = size;
    o.progress = false;  // N ranks on one standard error would interleave
    mine = lsi::run_sweep(study, o);
  });
  MPI_Barrier(MPI_COMM_WORLD);
  if (int code = agree(s, rank, size)) return code;

  unsigned long long run_here = mine.samples_run, run_total = 0, done_here = mine.samples_done,
                     done_total = 0;
  int complete_here = mine.complete ? 1 : 0, all_complete = 0;
  double shard_s = mine.wall_seconds, slowest_shard_s = 0.0;
  MPI_Allreduce(&run_here, &run_total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&done_here, &done_total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&complete_here, &all_complete, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&shard_s, &slowest_shard_s, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const int stopped_rank = complete_here ? size : rank;
  int first_stopped = size;
  MPI_Allreduce(&stopped_rank, &first_stopped, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);

  if (!all_complete) {
    // Stopped by the wall-time limit: nothing to merge yet; the shard files and their parts stay.
    std::string why = mine.stopped_by;
    int n = static_cast<int>(why.size());
    MPI_Bcast(&n, 1, MPI_INT, first_stopped, MPI_COMM_WORLD);
    why.resize(n);
    MPI_Bcast(why.data(), n, MPI_CHAR, first_stopped, MPI_COMM_WORLD);
    if (rank == 0) {
      lsi::SweepOutcome o;
      o.stopped_by = why + " (the shard files " + shard_file(args.out, 0, size) +
                     " ... are kept; lsi-mpi --resume with the same number of ranks continues)";
      o.samples_done = done_total;
      o.samples_run = run_total;
      o.wall_seconds = since(t0);
      o.seconds = {{"shards", slowest_shard_s}};
      report(o, args.out, args.format, size);
    }
    return 0;
  }

  // 3. Rank 0 merges; the shard files go only once F is in place.
  int code = 0;
  if (rank == 0) {
    const auto tm = Clock::now();
    lsi::SweepOutcome merged;
    s = guarded([&] {
      std::vector<std::string> files;
      for (int r = 0; r < size; ++r) files.push_back(shard_file(args.out, r, size));
      merged = lsi::merge_sweeps(files, args.out);
      for (const auto& f : files) fs::remove(f);
    });
    code = s.code;
    if (code) {
      std::cerr << "lsi-mpi: " << s.message << "\n";
    } else {
      merged.samples_run = run_total;
      merged.wall_seconds = since(t0);
      merged.seconds = {{"shards", slowest_shard_s}, {"merge", since(tm)}};
      report(merged, args.out, args.format, size);
    }
  }
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef __linux__
  // OpenMP threads that spin briefly, then sleep (app/openmp_wait_policy.hpp: unlimited
  // spinning was 10-40 times slower on a shared 2-core machine). libgomp reads the variables when
  // it loads, before main, so setting them here only takes effect through a restart. Restarting
  // is safe before MPI_Init (it is what `mpirun ... env VAR=value lsi-mpi` does; the process
  // keeps its id and its environment) and not after it, so it happens here, first. `mpirun -x
  // OMP_WAIT_POLICY=passive` sets it for every rank without the restart.
  // The executable is named by its own path, not /proc/self/exe, so that ps and top show the
  // ranks as lsi-mpi.
  if (lsi::set_openmp_wait_defaults()) {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    lsi::restart_program(ec ? "/proc/self/exe" : self.c_str(), argv);  // returns on failure only
  }
#endif
  MPI_Init(&argc, &argv);
  lsi::set_command_line(argc, argv);  // stored in the result files
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);

  CLI::App app{
      "lsi-mpi: run the shards of a sweep (lsi sweep) on the ranks of an MPI job and merge "
      "them into one result file. Usage: mpirun -np N -x OMP_NUM_THREADS=T lsi-mpi STUDY "
      "--out F (docs/guide/mpi.md)"};
  app.set_version_flag("--version",
                       std::string("lsi-mpi ") + LSI_VERSION + " (" + LSI_GIT_REVISION + ")");
  Args args;
  app.add_option("study", args.study,
                 "Study JSON file (docs/reference/scene_schema.md, \"Study files\")")
      ->required();
  app.add_option("--out", args.out,
                 "Merged HDF5 result file; rank r writes F.rank<r>-of-<N>.h5 "
                 "(and its .parts) first")
      ->required();
  app.add_flag("--resume", args.resume,
               "Continue an interrupted job (the same study, --out and "
               "number of ranks)");
  app.add_option("--format", args.format, "Summary format: table or json");

  int code = 0;
  try {
    app.parse(argc, argv);
    code = run(app, args, rank, size);
  } catch (const CLI::ParseError& e) {
    // Every rank parses the same command line: all stop here, rank 0 prints.
    const bool help = dynamic_cast<const CLI::CallForHelp*>(&e) ||
                      dynamic_cast<const CLI::CallForAllHelp*>(&e) ||
                      dynamic_cast<const CLI::CallForVersion*>(&e);
    if (rank == 0) app.exit(e);
    code = help ? 0 : 2;
  }
  MPI_Finalize();
  return code;
}
