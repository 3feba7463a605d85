// `lsi` under a careless user, a full disk, a scheduler's signals and impossible sizes
// (docs/vv/robustness.md, "What lsi guarantees"): one line and a clear exit code, never a crash, a
// lost input, a stale temporary file or a number that is not one.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "io/sweep_file.hpp"
#include "model/concurrent_runs.hpp"
#include "model/mpm_footprint.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "model/scene.hpp"
#include "support/run_command.hpp"
#include "support/temp_files.hpp"
#include "io/scene_parser.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;
const fs::path source_dir = LSI_SOURCE_DIR;
const std::string lsi_exe = LSI_EXE;

using Outcome = lsi::testing::CommandOutcome;  // out: stdout and stderr together

Outcome run(const std::string& args) { return lsi::testing::run_lsi(lsi_exe, args); }
// The command under bash, e.g. with resource limits set first.
Outcome run_in_bash(const std::string& setup, const std::string& args) {
  return lsi::testing::run_command("bash -c '" + setup + "; exec " + lsi_exe + " " + args +
                                   "' 2>&1");
}

fs::path temp_dir() { return lsi::testing::process_temp_dir("lsi_robustness_test"); }
fs::path write_json(const std::string& name, const json& j) {
  return lsi::testing::write_text(temp_dir() / name, j.dump(2));
}

json read_json(const fs::path& p) {
  std::ifstream f(p);
  return json::parse(f);
}

json minimal_scene() { return read_json(source_dir / "scenes/examples/minimal.json"); }

// A study of scenes/former-reference/L1-B1.json with `extra` merged in.
fs::path write_study(const std::string& name, const json& extra) {
  json s = read_json(source_dir / "scenes/studies/L1-B1-monte-carlo.json");
  s["name"] = name;
  s["scene"] = (source_dir / "scenes/former-reference/L1-B1.json").string();
  s["samples"] = 2000;
  if (!extra.is_null()) s.merge_patch(extra);  // `{}` is a null json: nothing to merge
  return write_json(name + ".json", s);
}

std::size_t lines(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

// Files in `dir` whose name starts with `prefix`.
std::vector<std::string> files_starting(const fs::path& dir, const std::string& prefix) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().filename().string().rfind(prefix, 0) == 0) out.push_back(e.path().filename());
  return out;
}

// A pid that no process has: a child that has exited and been reaped.
pid_t dead_pid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  waitpid(pid, nullptr, 0);
  return pid;
}

// A small tmpfs at `dir` (root with the right to mount), unmounted by the destructor; `ok` is
// false where mounting is not allowed (then the test is skipped).
struct SmallTmpfs {
  fs::path dir;
  bool ok = false;
  SmallTmpfs(const fs::path& d, const std::string& size) : dir(d) {
    fs::create_directories(dir);
    ok = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
  }
  ~SmallTmpfs() {
    if (ok) ::umount(dir.c_str());
  }
};

// A full disk: the write fails, lsi exits 1 with one line naming the file and the reason,
// removes its temporary and leaves no file. (HDF5's own exit handler used to crash on the file
// whose close had failed: SIGSEGV, exit 139.) The file-size limit (ulimit -f, with SIGXFSZ
// ignored) fails the write the way a full disk does, without privileges.
TEST(CliRobustness, AFullDiskEndsInOneLineAndExitOneWithoutATemporary) {
  const fs::path dir = temp_dir() / "disk-full";
  fs::create_directories(dir);
  const fs::path out = dir / "x.h5";
  const Outcome r = run_in_bash("trap \"\" XFSZ; ulimit -f 4",
                                "run " + (source_dir / "scenes/reference/L1-B1.json").string() +
                                    " --methods empirical,analytical --out " + out.string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1u) << r.out;
  EXPECT_NE(r.out.find("cannot write '" + out.string() + "'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("File too large"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(files_starting(dir, "x.h5.tmp.").empty());
}

TEST(CliRobustness, AFullTmpfsEndsInOneLineAndExitOne) {
  SmallTmpfs disk(temp_dir() / "small-tmpfs", "12k");
  if (!disk.ok) GTEST_SKIP() << "mounting a tmpfs is not allowed here";
  const fs::path out = disk.dir / "x.h5";
  const Outcome r = run("run " + (source_dir / "scenes/reference/L1-B1.json").string() +
                        " --methods empirical,analytical --out " + out.string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1u) << r.out;
  EXPECT_NE(r.out.find("No space left on device"), std::string::npos) << r.out;
  EXPECT_TRUE(files_starting(disk.dir, "x.h5").empty());
}

// A finished sweep killed while it removed its parts directory: --resume reports the finished
// run (it used to refuse the half-removed directory for good: "not a sweep's parts directory").
// The directory is now renamed before it is removed; a leftover of that is removed by the next run.
TEST(CliRobustness, ResumeRecognisesARunKilledWhileRemovingItsParts) {
  const fs::path study = write_study("parts-removal", {});
  const fs::path out = temp_dir() / "parts-removal.h5";
  ASSERT_EQ(run("sweep " + study.string() + " --out " + out.string()).code, 0);
  // What a kill part-way through removing the parts left: a chunk file, the marker already gone.
  const fs::path parts = out.string() + ".parts";
  fs::create_directories(parts);
  std::ofstream(parts / "chunk-000000000000.h5") << "half";
  Outcome r = run("sweep " + study.string() + " --out " + out.string() + " --resume --format json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(json::parse(r.out)["complete"].get<bool>());
  EXPECT_FALSE(fs::exists(parts));
  // The renamed directory of the new removal, left by a kill: gone after the next run.
  const fs::path removing = parts.string() + ".removing";
  fs::create_directories(removing / "x");
  r = run("sweep " + study.string() + " --out " + out.string() + " --resume");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(fs::exists(removing));
}

// Temporaries of writers that died (SIGKILL) are removed by the next writer of the same file;
// those of live processes are left alone.
TEST(CliRobustness, StaleTemporariesOfDeadWritersAreRemoved) {
  const fs::path dir = temp_dir() / "stale";
  fs::create_directories(dir);
  const fs::path out = dir / "x.h5";
  const fs::path stale = out.string() + ".tmp." + std::to_string(dead_pid());
  const fs::path live = out.string() + ".tmp." + std::to_string(getpid());
  std::ofstream(stale) << "left by a killed run";
  std::ofstream(live) << "being written by a live process";
  const Outcome r = run("run " + (source_dir / "scenes/examples/minimal.json").string() +
                        " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(out));
}

// SIGTERM (what a scheduler sends) while a sweep writes its result: the process ends with the
// signal and leaves no temporary beside the result (it used to leave one, full size); the table
// written so far is part of the parts directory, from which --resume finishes the run.
TEST(CliRobustness, SigtermDuringTheFinalWriteRemovesTheTemporary) {
  const fs::path study = write_study("sigterm", {{"samples", 1000000}});
  const fs::path dir = temp_dir() / "sigterm";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "x.h5";
  const pid_t pid = lsi::testing::spawn_quietly({lsi_exe, "sweep", study, "--out", out});
  ASSERT_GE(pid, 0);
  // The first chunk journalled: the table file holds its compressed rows.
  const fs::path table = out.string() + ".parts/chunk-000000000000.h5";
  const auto t0 = std::chrono::steady_clock::now();
  int status = 0;
  bool seen = false, ended = false;
  while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {
    if (fs::exists(table)) {
      seen = true;
      break;
    }
    if (waitpid(pid, &status, WNOHANG) == pid) {
      ended = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  if (!ended) {
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
  }
  ASSERT_TRUE(seen) << "the sweep ended before its result was seen being written";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "status " << status;
  EXPECT_TRUE(files_starting(dir, "x.h5.tmp.").empty());
  const Outcome resumed = run("sweep " + study.string() + " --out " + out.string() + " --resume");
  ASSERT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_EQ(lsi::read_sweep_file(out.string()).table.rows(), 1000000u);
  EXPECT_FALSE(fs::exists(out.string() + ".parts"));
  EXPECT_TRUE(files_starting(dir, "x.h5.tmp.").empty());
}

// A sweep whose table cannot be held in memory, or whose files cannot fit on the disk, is refused
// before it writes anything (a 1e12-sample study used to grow until std::bad_alloc, a 9e15-sample
// one to fail at once with a bare bad_alloc and a parts directory that blocked the rerun).
TEST(CliRobustness, SweepsThatCannotFitAreRefusedBeforeTheyWrite) {
  for (const double samples : {1e12, 9e15}) {
    const fs::path study = write_study("huge", {{"samples", samples}});
    const fs::path out = temp_dir() / "huge.h5";
    const Outcome r = run("sweep " + study.string() + " --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_EQ(lines(r.out), 1u) << r.out;
    EXPECT_NE(r.out.find("samples = "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("of memory"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out.string() + ".parts"));
  }
}

TEST(CliRobustness, SweepsWhoseFilesCannotFitOnTheDiskAreRefused) {
  SmallTmpfs disk(temp_dir() / "sweep-tmpfs", "64k");
  if (!disk.ok) GTEST_SKIP() << "mounting a tmpfs is not allowed here";
  const fs::path study = write_study("disk", {{"samples", 100000}});
  const Outcome r = run("sweep " + study.string() + " --out " + (disk.dir / "x.h5").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("of disk where --out goes"), std::string::npos) << r.out;
  EXPECT_TRUE(files_starting(disk.dir, "x.h5").empty());
}

// MPM runs that cannot fit are refused up front, naming the setting: the state of a fine grid
// (under a 2 GiB address-space limit), snapshots, and histories to an end time far beyond the
// run (a 1e9 s end time used to run on silently).
TEST(CliRobustness, MpmRunsThatCannotFitAreRefusedUpFront) {
  json scene = read_json(source_dir / "scenes/examples/impact-small.json");
  scene["methods"]["mpm"]["cell_size_m"] = 0.004;
  Outcome r = run_in_bash("ulimit -v 2000000",
                          "run " + write_json("fine.json", scene).string() + " --methods mpm");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("methods.mpm.cell_size_m = 0.004: the MPM state"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("a cell of at least"), std::string::npos) << r.out;

  scene = read_json(source_dir / "scenes/examples/impact-small.json");
  scene["methods"]["mpm"]["end_time_s"] = 1e9;
  r = run("run " + write_json("long.json", scene).string() + " --methods mpm");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("methods.mpm.end_time_s = 1000000000: the histories"), std::string::npos)
      << r.out;

  scene = read_json(source_dir / "scenes/examples/impact-small.json");
  scene["methods"]["mpm"]["end_time_s"] = 1e3;
  scene["methods"]["mpm"]["snapshot_interval_s"] = 1e-6;
  r = run("run " + write_json("snapshots.json", scene).string() + " --methods mpm");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("methods.mpm.snapshot_interval_s = 1e-06: snapshots"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("a snapshot_interval_s of at least"), std::string::npos) << r.out;
}

// An MPM sweep's samples run side by side within half the memory, each counted at its own
// scene's footprint: a sample whose histories (one output every 9e-6 s to the default end time)
// would take more than half of the memory under a 4 GB address-space limit, but less than all
// of it, runs alone, the others before and after it side by side; a note names it (and no other)
// as its chunk starts. The numbers are those of a run without the limit (each sample on one
// thread either way). Where runs cannot go side by side there is no share to exceed.
TEST(CliRobustness, AnMpmSampleTooLargeToRunBesideOthersRunsAlone) {
  if (lsi::concurrent_runs(4) < 2) GTEST_SKIP() << "MPM runs go one after the other here";
  json scene = read_json(source_dir / "scenes/examples/impact-small.json");
  scene["methods"]["mpm"]["cell_size_m"] = 0.25;
  const fs::path points = lsi::testing::write_text(
      temp_dir() / "memory_points.csv", "/methods/mpm/output_interval_s\n0.05\n9e-6\n0.05\n0.05\n");
  const json study = {{"name", "memory"},   {"scene", scene},
                      {"design", "points"}, {"points", {{"file", points.string()}}},
                      {"methods", {"mpm"}}, {"outputs", {"peak_force"}}};
  const fs::path file = write_json("memory_study.json", study);
  const fs::path limited = temp_dir() / "memory_limited",
                 unlimited = temp_dir() / "memory_unlimited";
  fs::remove_all(limited.string() + ".h5");
  fs::remove_all(unlimited.string() + ".h5");
  const Outcome a = run_in_bash(
      "ulimit -v 4000000", "--progress none sweep " + file.string() + " --out " + limited.string() +
                               ".h5 --table-csv " + limited.string() + ".csv");
  ASSERT_EQ(a.code, 0) << a.out;
  EXPECT_NE(a.out.find("lsi: note: sample 2 needs"), std::string::npos) << a.out;
  EXPECT_NE(a.out.find("more than its share of half the memory"), std::string::npos) << a.out;
  for (const char* other : {"sample 1 ", "sample 3 ", "sample 4 "})
    EXPECT_EQ(a.out.find(std::string("lsi: note: ") + other), std::string::npos) << a.out;
  EXPECT_NE(a.out.find("4 of 4 samples done, 4 ok"), std::string::npos) << a.out;
  const Outcome b = run("--progress none sweep " + file.string() + " --out " + unlimited.string() +
                        ".h5 --table-csv " + unlimited.string() + ".csv");
  ASSERT_EQ(b.code, 0) << b.out;
  std::ifstream x(limited.string() + ".csv"), y(unlimited.string() + ".csv");
  const std::string tx((std::istreambuf_iterator<char>(x)), std::istreambuf_iterator<char>());
  const std::string ty((std::istreambuf_iterator<char>(y)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(tx.empty());
  EXPECT_EQ(tx, ty);
}

// The footprint that the refusals above rest on, against a run of the same case: the points
// from the bodies' areas (a fill point is kept where its centre lies in the polygon, so cells cut
// by the sloping front may differ: within 5 %), the nodes exactly, and the first step's Courant
// limit with the saturated wave speed against the step the run reports at its first output after
// t = 0 (its tail still moves at the initial speed and no point has expanded yet: 1e-6, round-off
// of the reductions; the dry wave speed would be several times off).
TEST(MpmFootprint, EstimatesThePointsNodesAndTimeStepOfARun) {
  json doc = read_json(source_dir / "scenes/examples/impact-small.json");
  doc["methods"]["mpm"]["end_time_s"] = 0.01;
  const lsi::MpmCase c = lsi::impact_case(lsi::parse_scene(doc));
  const lsi::MpmFootprint f = lsi::estimate_footprint(c);
  const lsi::MpmOutcome o = lsi::run_mpm_case(c);
  EXPECT_NEAR(f.points, o.run().particles, 0.05 * o.run().particles);
  const double dx = c.settings.cell_size_m;
  const double nx = static_cast<int>((c.upper[0] - c.lower[0]) / dx + 0.5) + 1;
  const double ny = static_cast<int>((c.upper[1] - c.lower[1]) / dx + 0.5) + 1;
  EXPECT_EQ(f.nodes, nx * ny);
  const auto& steps = o.result.series.at("time_step").values;  // [0]: the output at t = 0
  ASSERT_GE(steps.size(), 2u);
  const double first_output_step = steps[1];
  EXPECT_NEAR(f.first_time_step, first_output_step, 1e-6 * first_output_step);
  EXPECT_NEAR(f.max_steps, c.settings.end_time_s / f.first_time_step, 1e-9 * f.max_steps);
  EXPECT_GT(f.state_bytes, 200.0 * o.run().particles);  // at least the points' own fields
}

// Closed forms evaluated where their arithmetic overflows or underflows: an input error naming
// the method and the value, never a NaN or an infinity in the results with exit 0. A barrier
// that never stops (no base friction) stays a result.
TEST(CliRobustness, ClosedFormsOutsideTheirComputableRangeAreErrors) {
  struct Case {
    const char* what;
    std::function<void(json&)> edit;
    const char* method;
  };
  const Case cases[] = {
      {"lambda", [](json& s) { s["methods"]["analytical"]["lambda"] = 5e-324; },
       "methods.analytical: "},
      {"a1", [](json& s) { s["methods"]["empirical"]["a1"] = 1e308; }, "methods.empirical: "},
      {"kappa", [](json& s) { s["methods"]["empirical"]["kappa"] = 1e308; }, "methods.empirical: "},
      {"velocity", [](json& s) { s["landslide"]["velocity_m_s"] = 1e-300; }, "methods.empirical: "},
      {"mass", [](json& s) { s["barrier"]["density_kg_m3"] = 5e-320; }, "methods.empirical: "},
      {"momentum lambda",
       [](json& s) {
         s["methods"]["analytical"]["lambda"] = 5e-324;
         s["methods"]["analytical"]["barrier_model"] = "momentum";
       },
       "methods.analytical: "},
  };
  for (const Case& c : cases) {
    json scene = minimal_scene();
    scene["methods"] = {{"empirical", json::object()}, {"analytical", json::object()}};
    c.edit(scene);
    const Outcome r = run("run " + write_json("extreme.json", scene).string() + " --format json");
    EXPECT_EQ(r.code, 2) << c.what << ": " << r.out;
    EXPECT_EQ(lines(r.out), 1u) << c.what << ": " << r.out;
    EXPECT_NE(r.out.find(c.method), std::string::npos) << c.what << ": " << r.out;
    EXPECT_NE(r.out.find("outside the range in which the"), std::string::npos)
        << c.what << ": " << r.out;
  }
  json scene = minimal_scene();
  scene["barrier"]["base_friction"] = 0.0;
  const Outcome r = run("run " + write_json("frictionless.json", scene).string());
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("never stops"), std::string::npos) << r.out;
}

// An option given empty is an error, not the option left out (`--out ''` used to write nothing,
// `--methods ''` to run the scene's methods).
TEST(CliRobustness, EmptyOptionValuesAreErrors) {
  const std::string scene = (source_dir / "scenes/examples/minimal.json").string();
  const std::string study = write_study("empty-options", {}).string();
  const std::pair<std::string, std::string> commands[] = {
      {"run " + scene + " --out ''", "--out"},
      {"run " + scene + " --methods ''", "--methods"},
      {"compare " + scene + " --out-dir ''", "--out-dir"},
      {"sweep " + study + " --out ''", "--out"},
  };
  for (const auto& [command, option] : commands) {
    const Outcome r = run(command);
    EXPECT_EQ(r.code, 2) << command << ": " << r.out;
    EXPECT_NE(r.out.find(option + " = \"\": must not be empty"), std::string::npos)
        << command << ": " << r.out;
  }
}

// Inputs are read with a bound: a device that never ends is refused at once.
TEST(CliRobustness, AnInputThatNeverEndsIsRefused) {
  const Outcome r = run("run /dev/zero");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("/dev/zero: the scene file is larger than 64 MiB"), std::string::npos)
      << r.out;
}

// Names reach terminals and file names: control characters (an escape sequence) are refused,
// and the message shows them escaped.
TEST(CliRobustness, NamesWithControlCharactersAreRefused) {
  json scene = minimal_scene();
  scene["name"] = "a\x1b[31mred";
  const Outcome r = run("run " + write_json("escape.json", scene).string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << "a raw escape reached the output";
  EXPECT_NE(r.out.find("name = \"a\\u001b[31mred\": must not contain control characters"),
            std::string::npos)
      << r.out;
}

// A largest time step below the solvers' smallest (it used to stop the run as "unstable: the
// time step collapsed").
TEST(CliRobustness, AMaxTimeStepBelowTheSolversSmallestIsRefused) {
  json scene = read_json(source_dir / "scenes/examples/impact-small.json");
  scene["methods"]["mpm"]["max_time_step_s"] = 1e-15;
  const Outcome r = run("run " + write_json("tiny-step.json", scene).string() + " --methods mpm");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("max_time_step_s = 1e-15: must be >= 1e-12"), std::string::npos) << r.out;
}

// A study none of whose samples is a valid scene is refused when it is read.
TEST(CliRobustness, AStudyWithoutAValidSampleIsRefused) {
  json extra = read_json(source_dir / "scenes/studies/L1-B1-monte-carlo.json");
  extra["inputs"][0]["sd"] = 1e308;  // lognormal thickness: every draw 0 or infinite
  const fs::path study = write_study("no-valid-sample", {{"inputs", extra["inputs"]}});
  const Outcome r = run("sweep " + study.string() + " --out " + (temp_dir() / "nv.h5").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("inputs: none of the first 256 samples is a valid scene"), std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(temp_dir() / "nv.h5.parts"));
}

// Changes one input value of row `row` in a sweep result file.
void alter_input(const fs::path& file, std::size_t row) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, "/samples/inputs", H5P_DEFAULT);
  ASSERT_GE(d, 0);
  const hid_t space = H5Dget_space(d);
  hsize_t dims[2];
  H5Sget_simple_extent_dims(space, dims, nullptr);
  std::vector<double> v(dims[0] * dims[1]);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  v[row * dims[1]] *= 1.5;
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

// `lsi merge` reads only shard result files, and checks each row against the study (inputs drawn
// again from the seed): an altered shard is refused (it used to be joined with exit 0).
TEST(CliRobustness, MergeRefusesDirectoriesAndAlteredShards) {
  Outcome r = run("merge " + temp_dir().string() + " --out " + (temp_dir() / "m.h5").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("not a regular file"), std::string::npos) << r.out;
  const fs::path study = write_study("merge-check", {{"chunk_samples", 500}});
  std::string shards;
  for (int i = 0; i < 2; ++i) {
    const fs::path f = temp_dir() / ("merge-shard" + std::to_string(i) + ".h5");
    r = run("sweep " + study.string() + " --out " + f.string() + " --shard " + std::to_string(i) +
            "/2");
    ASSERT_EQ(r.code, 0) << r.out;
    shards += " " + f.string();
  }
  r = run("merge" + shards + " --out " + (temp_dir() / "merged.h5").string());
  ASSERT_EQ(r.code, 0) << r.out;
  alter_input(temp_dir() / "merge-shard1.h5", 7);
  r = run("merge" + shards + " --out " + (temp_dir() / "merged2.h5").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("merge-shard1.h5: row 7 (sample "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("where the study's sampler draws"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(temp_dir() / "merged2.h5"));
}

}  // namespace
