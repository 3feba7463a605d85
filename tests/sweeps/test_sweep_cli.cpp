// `lsi sweep` and `lsi merge` end to end: study-file errors, agreement with `lsi run`, invalid
// samples, reproducibility across thread counts, resume after SIGKILL, shards and merge, the
// stopping rules, grid designs, MPM samples.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "model/closed_form_methods.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "model/study.hpp"
#include "model/sweep_table.hpp"
#include "support/run_command.hpp"
#include "support/temp_files.hpp"
#include "io/scene_parser.hpp"
#include "io/study_parser.hpp"
#include "io/hdf5_io.hpp"
#include "io/sweep_file.hpp"
#include "io/sweep_table_stream.hpp"
#include "sweeps/statistics.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;
const fs::path source_dir = LSI_SOURCE_DIR;
const std::string lsi_exe = LSI_EXE;

using Outcome = lsi::testing::CommandOutcome;  // out: stdout and stderr together

Outcome run(const std::string& args, const std::string& env = "") {
  return lsi::testing::run_lsi(lsi_exe, args, env);
}
fs::path temp_dir() { return lsi::testing::process_temp_dir("lsi_sweep_test"); }

// A study of the former reference case L1-B1 (a 14.4 t/m wall: scenes/former-reference/) with `extra` keys
// merged in.
fs::path write_study(const std::string& name, json extra) {
  json s = {{"name", name},
            {"scene", (source_dir / "scenes/former-reference/L1-B1.json").string()},
            {"inputs",
             {{{"path", "/landslide/thickness_m"},
               {"distribution", "lognormal"},
               {"mean", 2.0},
               {"sd", 0.3}},
              {{"path", "/landslide/velocity_m_s"},
               {"distribution", "truncated-normal"},
               {"mean", 6.0},
               {"sd", 1.5},
               {"min", 1.0},
               {"max", 15.0}},
              {{"path", "/landslide/shape/body_squares"},
               {"distribution", "discrete"},
               {"values", {4, 6, 8}}},
              {{"path", "/barrier/base_friction"},
               {"distribution", "uniform"},
               {"min", 0.3},
               {"max", 0.7}}}},
            {"correlation",
             {{{"inputs", {"/landslide/thickness_m", "/landslide/velocity_m_s"}}, {"rho", 0.4}}}},
            {"samples", 20000},
            {"seed", 11},
            {"chunk_samples", 4096},
            {"methods", {"empirical", "analytical"}},
            {"thresholds", {{{"output", "final_displacement"}, {"above", 0.5}}}}};
  if (!extra.is_null()) s.merge_patch(extra);  // `{}` is a null json: nothing to merge
  const fs::path p = temp_dir() / (name + ".json");
  std::ofstream(p) << s.dump(2);
  return p;
}

// Everything but the wall times must be identical.
void expect_same_table(const lsi::SweepFile& a, const lsi::SweepFile& b) {
  ASSERT_EQ(a.table.rows(), b.table.rows());
  EXPECT_EQ(a.table.index, b.table.index);
  EXPECT_EQ(a.table.status, b.table.status);
  EXPECT_EQ(a.table.inputs, b.table.inputs);
  ASSERT_EQ(a.table.outputs.size(), b.table.outputs.size());
  for (std::size_t c = 0; c < a.table.outputs.size(); ++c)
    for (std::size_t i = 0; i < a.table.rows(); ++i) {
      const double x = a.table.outputs[c][i], y = b.table.outputs[c][i];
      if (!(std::isnan(x) && std::isnan(y))) {
        ASSERT_EQ(x, y) << a.table.output_columns[c] << " row " << i;
      }
    }
  EXPECT_EQ(a.table.failure_index, b.table.failure_index);
  EXPECT_EQ(a.table.failure_reason, b.table.failure_reason);
  EXPECT_EQ(a.statistics, b.statistics);
  EXPECT_EQ(a.header.fingerprint, b.header.fingerprint);
}

TEST(SweepCli, StudyErrorsNameTheFieldAndExit2) {
  const std::pair<json, std::string> cases[] = {
      {{{"colour", 1}}, "colour: unknown key"},
      {{{"samples", -5}}, "samples = -5"},
      {{{"design", "quasi"}}, "design = \"quasi\""},
      {{{"inputs",
         {{{"path", "/landslide/velocity_m_s"},
           {"distribution", "normal"},
           {"mean", 6},
           {"sd", -1}}}}},
       "inputs[0].sd = -1: must be > 0"},
      {{{"inputs",
         {{{"path", "/landslide/speed"}, {"distribution", "uniform"}, {"min", 1}, {"max", 2}}}}},
       "inputs[0].path = \"/landslide/speed\": not a numeric scene key"},
      {{{"inputs",
         {{{"path", "/methods/empirical/tau"},
           {"distribution", "uniform"},
           {"min", 0.1},
           {"max", 0.2}}}},
        {"methods", {"analytical"}}},
       "only the empirical method reads it"},
      {{{"inputs",
         {{{"path", "/landslide/shape/body_squares"},
           {"distribution", "uniform"},
           {"min", 2},
           {"max", 5}}}}},
       "must be an integer"},
      {{{"inputs",
         {{{"path", "/methods/analytical/tau"},
           {"distribution", "uniform"},
           {"min", 0.5},
           {"max", 1.5}}}}},
       "the scene with its typical value 1 is invalid: methods.analytical.tau = 1"},
      {{{"correlation",
         {{{"inputs", {"/landslide/thickness_m", "/barrier/height_m"}}, {"rho", 0.5}}}}},
       "not one of the study's inputs"},
      {{{"correlation",
         {{{"inputs", {"/landslide/thickness_m", "/landslide/velocity_m_s"}}, {"rho", 1.5}}}}},
       "rho = 1.5"},
      {json::parse(R"({"stop": {"interval": {"method": "analytical", "output": "peak_force",
                                              "statistic": "mean"}}})"),
       "relative_half_width: missing"},
  };
  for (const auto& [extra, expected] : cases) {
    const fs::path study = write_study("bad", extra);
    const Outcome r = run("sweep " + study.string() + " --out " + (temp_dir() / "bad.h5").string());
    EXPECT_EQ(r.code, 2) << extra.dump() << "\n" << r.out;
    EXPECT_NE(r.out.find(expected), std::string::npos) << "expected '" << expected << "' in:\n"
                                                       << r.out;
    EXPECT_EQ(r.out.find("\n", r.out.find("error")), r.out.size() - 1) << "one line:\n" << r.out;
  }
  const Outcome missing =
      run("sweep " + (temp_dir() / "no-such-study.json").string() + " --out x.h5");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.out.find("no-such-study.json: study file not found"), std::string::npos)
      << missing.out;
  const fs::path ok = write_study("shard", {});
  const Outcome s =
      run("sweep " + ok.string() + " --out " + (temp_dir() / "s.h5").string() + " --shard 3/2");
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.out.find("--shard 3/2: must be i/N with 0 <= i < N"), std::string::npos) << s.out;
  // 20000 samples in chunks of 4096 are 5 chunks: 6 shards would leave one without work, and
  // every shard is refused (before anything is written), naming the chunk size that would do.
  for (const char* shard : {"0/6", "5/6"}) {
    const fs::path out = temp_dir() / "six.h5";
    const Outcome e = run("sweep " + ok.string() + " --out " + out.string() + " --shard " + shard);
    EXPECT_EQ(e.code, 2) << e.out;
    EXPECT_NE(e.out.find("chunk_samples = 4096: the study's 20000 samples make 5 chunk(s), fewer "
                         "than the 6 shards"),
              std::string::npos)
        << e.out;
    EXPECT_NE(e.out.find("set chunk_samples <= 3334"), std::string::npos) << e.out;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(SweepCli, SamplesAgreeWithLsiRunAndStatisticsCountThem) {
  const fs::path study = write_study("agree", {{"samples", 300}});
  const fs::path out = temp_dir() / "agree.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string() + " --format json");
  ASSERT_EQ(r.code, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["complete"].get<bool>());
  EXPECT_EQ(j["samples_done"].get<int>(), 300);
  EXPECT_FALSE(fs::exists(out.string() + ".parts")) << "a complete sweep removes its chunks";
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  ASSERT_EQ(f.table.rows(), 300u);
  const lsi::Study s = lsi::load_study(study.string());
  // Every 30th sample through the scalar methods of `lsi run`. The kernel and the host compile
  // the same formulas, but may contract multiply-adds differently: 1e-12 relative.
  for (std::size_t i = 0; i < 300; i += 30) {
    double x[4];
    for (int d = 0; d < 4; ++d) x[d] = f.table.inputs[d][i];
    const lsi::Scene scene = lsi::parse_scene(lsi::sample_scene_document(s, x));
    const lsi::MethodResult e = lsi::run_empirical(scene), a = lsi::run_analytical(scene);
    const std::pair<std::string, double> expect[] = {
        {"empirical/peak_force", e.peak_force},
        {"empirical/rise_time", e.rise_time},
        {"empirical/impact_duration", e.impact_duration},
        {"empirical/final_displacement", e.final_displacement},
        {"analytical/peak_force", a.peak_force},
        {"analytical/rise_time", a.rise_time},
        {"analytical/impact_duration", a.impact_duration},
        {"analytical/final_displacement", a.final_displacement}};
    for (const auto& [column, value] : expect) {
      const auto it =
          std::find(f.table.output_columns.begin(), f.table.output_columns.end(), column);
      ASSERT_NE(it, f.table.output_columns.end()) << column;
      const double got = f.table.outputs[it - f.table.output_columns.begin()][i];
      EXPECT_NEAR(got, value, 1e-12 * std::fabs(value) + 1e-300) << column << " sample " << i;
    }
  }
  // Statistics: the 300 ok samples; the mean of the stored column.
  EXPECT_EQ(f.statistics["samples_ok"].get<int>(), 300);
  const auto& col = f.table.outputs[1];  // empirical/rise_time... find by name instead
  (void)col;
  const auto it = std::find(f.table.output_columns.begin(), f.table.output_columns.end(),
                            "analytical/peak_force");
  double mean = 0;
  for (double v : f.table.outputs[it - f.table.output_columns.begin()]) mean += v / 300.0;
  EXPECT_NEAR(f.statistics["outputs"]["analytical/peak_force"]["mean"].get<double>(), mean,
              1e-9 * mean);
}

TEST(SweepCli, InvalidSamplesAreRecordedWithTheirReasonAndLeftOutOfStatistics) {
  // Velocity ~ N(1, 2): about 31 % of the samples are <= 0, which the scene forbids.
  const fs::path study = write_study("invalid", {{"samples", 2000},
                                                 {"correlation", nullptr},
                                                 {"inputs",
                                                  {{{"path", "/landslide/velocity_m_s"},
                                                    {"distribution", "normal"},
                                                    {"mean", 1.0},
                                                    {"sd", 2.0}}}}});
  const fs::path out = temp_dir() / "invalid.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  std::size_t bad = 0;
  for (std::size_t i = 0; i < f.table.rows(); ++i) {
    const bool negative = f.table.inputs[0][i] <= 0.0;
    EXPECT_EQ(f.table.status[i], negative ? 1 : 0) << "v = " << f.table.inputs[0][i];
    if (negative) {
      EXPECT_TRUE(std::isnan(f.table.outputs[0][i]));
      ++bad;
    }
  }
  // P(N(1,2) <= 0) = Phi(-0.5) = 0.3085; 2000 samples: sd 0.0103, so +-0.04 is 4 sd.
  EXPECT_NEAR(double(bad) / 2000.0, 0.3085, 0.04);
  ASSERT_EQ(f.table.failure_index.size(), bad);
  EXPECT_NE(f.table.failure_reason[0].find("landslide.velocity_m_s = -"), std::string::npos)
      << f.table.failure_reason[0];
  EXPECT_NE(f.table.failure_reason[0].find("must be > 0"), std::string::npos);
  EXPECT_EQ(f.statistics["samples_ok"].get<std::size_t>(), 2000 - bad);
  EXPECT_EQ(f.statistics["samples_failed"]["invalid input"].get<std::size_t>(), bad);
  EXPECT_EQ(f.statistics["outputs"]["analytical/peak_force"]["count"].get<std::size_t>(),
            2000 - bad);
}

TEST(SweepCli, RangeCheckOfTheKernelAgreesWithTheSceneParser) {
  // Wide distributions over every field the closed forms read, many of them outside the ranges:
  // each sample the kernel accepts must parse, and each it rejects must not (the runner then
  // records the parser's message; a disagreement would show as "rejected by the sweep's range
  // check").
  json inputs = json::array();
  auto wide = [&](const char* path, double lo, double hi) {
    inputs.push_back({{"path", path}, {"distribution", "uniform"}, {"min", lo}, {"max", hi}});
  };
  wide("/landslide/thickness_m", -0.5, 3);
  wide("/landslide/velocity_m_s", -1, 10);
  wide("/landslide/density_kg_m3", -100, 2000);
  wide("/barrier/height_m", -0.5, 6);
  wide("/barrier/base_width_m", 0.5, 3);
  wide("/barrier/top_width_m", -0.2, 2);
  wide("/barrier/face_angle_deg", 60, 100);
  wide("/barrier/density_kg_m3", -100, 2500);
  wide("/barrier/base_friction", -0.1, 1);
  wide("/methods/empirical/a1", -0.2, 2);
  wide("/methods/empirical/a2", -6, 6);
  wide("/methods/empirical/tau", -0.1, 1.1);
  wide("/methods/empirical/kappa", -0.2, 1);
  wide("/methods/analytical/lambda", -0.1, 1.1);
  wide("/methods/analytical/tau", -0.1, 1.1);
  inputs.push_back({{"path", "/landslide/shape/body_squares"},
                    {"distribution", "discrete"},
                    {"values", {3, -1, 0, 7.5}}});
  const fs::path study =
      write_study("mirror", {{"samples", 3000}, {"correlation", nullptr}, {"inputs", inputs}});
  const fs::path out = temp_dir() / "mirror.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  const lsi::Study s = lsi::load_study(study.string());
  std::size_t ok = 0;
  for (std::size_t i = 0; i < f.table.rows(); ++i) {
    std::vector<double> x;
    for (const auto& c : f.table.inputs) x.push_back(c[i]);
    const std::string reason = lsi::invalid_sample_reason(s, x.data());
    EXPECT_EQ(f.table.status[i] == 0, reason.empty()) << "sample " << i << ": " << reason;
    ok += f.table.status[i] == 0;
  }
  for (const auto& why : f.table.failure_reason)
    EXPECT_EQ(why.find("rejected by the sweep's range check"), std::string::npos) << why;
  // The check must see both kinds: with these ranges a few percent of the samples are valid.
  EXPECT_GT(ok, 5u);
  EXPECT_LT(ok, f.table.rows());
}

TEST(SweepCli, SameResultsOnOneAndTwoThreads) {
  const fs::path study = write_study("threads", {});
  const fs::path a = temp_dir() / "t1.h5", b = temp_dir() / "t2.h5";
  const Outcome one = run("sweep " + study.string() + " --out " + a.string(), "OMP_NUM_THREADS=1");
  ASSERT_EQ(one.code, 0) << one.out;
  const Outcome two = run("sweep " + study.string() + " --out " + b.string(), "OMP_NUM_THREADS=2");
  ASSERT_EQ(two.code, 0) << two.out;
  expect_same_table(lsi::read_sweep_file(a.string()), lsi::read_sweep_file(b.string()));
}

TEST(SweepCli, ResumesAfterSigkillWithIdenticalResults) {
  // Small chunks, so that the kill lands between chunk files (or inside one).
  const fs::path study = write_study("kill", {{"samples", 400000}, {"chunk_samples", 2000}});
  const fs::path full = temp_dir() / "full.h5", killed = temp_dir() / "killed.h5";
  ASSERT_EQ(run("sweep " + study.string() + " --out " + full.string()).code, 0);

  const pid_t pid = lsi::testing::spawn_quietly({lsi_exe, "sweep", study, "--out", killed});
  ASSERT_GE(pid, 0);
  const fs::path parts = killed.string() + ".parts";
  auto chunks = [&] {
    std::size_t n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(parts, ec))
      n += e.path().filename().string().rfind("chunk-", 0) == 0 && e.path().extension() == ".h5";
    return n;
  };
  const auto t0 = std::chrono::steady_clock::now();
  while (chunks() < 10 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep finished before it could be killed";
  const std::size_t left = chunks();
  EXPECT_GE(left, 10u);
  EXPECT_LT(left, 200u);

  const Outcome again = run("sweep " + study.string() + " --out " + killed.string());
  EXPECT_EQ(again.code, 2) << again.out;
  EXPECT_NE(again.out.find("--resume"), std::string::npos) << again.out;
  const Outcome resumed =
      run("sweep " + study.string() + " --out " + killed.string() + " --resume --format json");
  ASSERT_EQ(resumed.code, 0) << resumed.out;
  const json j = json::parse(resumed.out);
  EXPECT_EQ(j["samples_run"].get<std::size_t>(), 400000 - 2000 * left)
      << "only the missing chunks run";
  expect_same_table(lsi::read_sweep_file(full.string()), lsi::read_sweep_file(killed.string()));
  // Resuming a finished sweep changes nothing.
  const Outcome done =
      run("sweep " + study.string() + " --out " + killed.string() + " --resume --format json");
  ASSERT_EQ(done.code, 0) << done.out;
  EXPECT_EQ(json::parse(done.out)["samples_run"].get<int>(), 0);
}

TEST(SweepCli, ShardsMergeIntoTheFileOfASingleRun) {
  const fs::path study = write_study("shards", {{"design", "latin-hypercube"}});
  const fs::path single = temp_dir() / "single.h5";
  ASSERT_EQ(run("sweep " + study.string() + " --out " + single.string()).code, 0);
  std::string files;
  for (int i = 0; i < 3; ++i) {
    const fs::path f = temp_dir() / ("shard" + std::to_string(i) + ".h5");
    const Outcome r = run("sweep " + study.string() + " --out " + f.string() + " --shard " +
                          std::to_string(i) + "/3");
    ASSERT_EQ(r.code, 0) << r.out;
    files += " " + f.string();
  }
  const fs::path merged = temp_dir() / "merged.h5";
  // A missing shard is refused.
  const Outcome partial =
      run("merge --out " + merged.string() + " " + (temp_dir() / "shard0.h5").string());
  EXPECT_EQ(partial.code, 2);
  EXPECT_NE(partial.out.find("shard 1/3 is missing"), std::string::npos) << partial.out;
  const Outcome m = run("merge --out " + merged.string() + files);
  ASSERT_EQ(m.code, 0) << m.out;
  expect_same_table(lsi::read_sweep_file(single.string()), lsi::read_sweep_file(merged.string()));
}

TEST(SweepCli, IntervalRuleStopsEarlyAndWallTimeStopsResumably) {
  // The mean peak force of the analytical model to +-2 %: its coefficient of variation is about
  // 0.5, so about (1.96 * 0.5 / 0.02)^2 = 2400 samples are needed, far fewer than 20000.
  const fs::path study = write_study("interval", {{"stop",
                                                   {{"interval",
                                                     {{"method", "analytical"},
                                                      {"output", "peak_force"},
                                                      {"statistic", "mean"},
                                                      {"relative_half_width", 0.02}}}}}});
  const fs::path out = temp_dir() / "interval.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string() + " --format json");
  ASSERT_EQ(r.code, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["complete"].get<bool>());
  EXPECT_NE(j["stopped_by"].get<std::string>().find("confidence interval"), std::string::npos);
  const std::size_t n = j["samples_done"].get<std::size_t>();
  EXPECT_EQ(n % 4096, 0u) << "stops at a chunk boundary";
  EXPECT_GE(n, 4096u);
  EXPECT_LE(n, 8192u);

  // A wall-time limit far below one chunk's time: one chunk per invocation, then --resume.
  const fs::path timed =
      write_study("timed", {{"samples", 10000}, {"stop", {{"wall_time_s", 1e-6}}}});
  const fs::path t = temp_dir() / "timed.h5";
  const Outcome first = run("sweep " + timed.string() + " --out " + t.string() + " --format json");
  ASSERT_EQ(first.code, 0) << first.out;
  EXPECT_FALSE(json::parse(first.out)["complete"].get<bool>());
  EXPECT_EQ(json::parse(first.out)["samples_done"].get<int>(), 4096);
  EXPECT_TRUE(fs::exists(t.string() + ".parts"));
  EXPECT_FALSE(lsi::read_sweep_file(t.string()).header.complete);
  for (int k = 0; k < 2; ++k)
    ASSERT_EQ(run("sweep " + timed.string() + " --out " + t.string() + " --resume").code, 0);
  const lsi::SweepFile f = lsi::read_sweep_file(t.string());
  EXPECT_TRUE(f.header.complete);
  EXPECT_EQ(f.table.rows(), 10000u);
}

// The rows of a chunk of /samples/inputs in a result file.
// The chunk of a result file's /samples/inputs: rows and columns ({0, 0} unless 2-D chunks).
std::array<hsize_t, 2> input_chunk_dims(const fs::path& file) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, "/samples/inputs", H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(d);
  std::array<hsize_t, 2> dims = {0, 0};
  const int rank = H5Pget_chunk(plist, 2, dims.data());
  H5Pclose(plist);
  H5Dclose(d);
  H5Fclose(f);
  return rank == 2 ? dims : std::array<hsize_t, 2>{0, 0};
}

hsize_t input_chunk_rows(const fs::path& file) { return input_chunk_dims(file)[0]; }

// Edits the journal of each entry in `parts` (the attribute `journal` of chunk-*.h5).
template <class Edit>
void edit_journals(const fs::path& parts, const Edit& edit) {
  for (const auto& e : fs::directory_iterator(parts)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("chunk-", 0) != 0) continue;
    const hid_t f = H5Fopen(e.path().c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0) << name;
    json j = json::parse(lsi::hdf5::read_string_attribute(f, "journal"));
    edit(name, j);
    H5Adelete(f, "journal");
    lsi::hdf5::write_string_attribute(f, "journal", j.dump());
    H5Fclose(f);
  }
}

// The sampled rows of two result files: the same samples, inputs and outputs.
void expect_same_rows(const lsi::SweepTable& a, const lsi::SweepTable& b) {
  ASSERT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.index, b.index);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.inputs, b.inputs);
  ASSERT_EQ(a.outputs.size(), b.outputs.size());
  for (std::size_t c = 0; c < a.outputs.size(); ++c)
    for (std::size_t i = 0; i < a.rows(); ++i)
      if (!(std::isnan(a.outputs[c][i]) && std::isnan(b.outputs[c][i]))) {
        ASSERT_EQ(a.outputs[c][i], b.outputs[c][i]) << a.output_columns[c] << " row " << i;
      }
}

TEST(SweepCli, TableChunksFollowChunkSamplesAndTheJournalNamesThem) {
  using lsi::SweepTableStream;
  // The rule: 5 inputs are 40 bytes a row; 4096 rows (160 KiB) are the most within 256 KiB,
  // doubled while fewer than the rows arriving at once and within 1 MiB.
  EXPECT_EQ(SweepTableStream::chunk_rows_for(5, 10000000, 1), 4096u);
  EXPECT_EQ(SweepTableStream::chunk_rows_for(5, 10000000, 5000), 8192u);
  EXPECT_EQ(SweepTableStream::chunk_rows_for(5, 10000000, 1 << 20), 16384u);  // 640 KiB
  EXPECT_EQ(SweepTableStream::chunk_rows_for(4, 10000000, 1 << 20), 32768u);  // 1 MiB
  EXPECT_EQ(SweepTableStream::chunk_rows_for(5, 1000, 1 << 20), 1000u);

  // The study's 4 inputs in chunks of 16384 rows, as its chunk_samples; a run stopped after its
  // first chunk journals them, and its resumption writes the same table in the same chunks.
  const json big = {{"samples", 40000}, {"chunk_samples", 16384}};
  const fs::path whole = temp_dir() / "chunkrows-whole.h5";
  ASSERT_EQ(
      run("sweep " + write_study("chunkrows", big).string() + " --out " + whole.string()).code, 0);
  EXPECT_EQ(input_chunk_rows(whole), 16384u);
  json timed_big = big;
  timed_big["stop"] = {{"wall_time_s", 1e-6}};
  const fs::path timed = write_study("chunkrows-timed", timed_big);
  const fs::path t = temp_dir() / "chunkrows-timed.h5";
  ASSERT_EQ(run("sweep " + timed.string() + " --out " + t.string()).code, 0);
  int entries = 0;
  edit_journals(t.string() + ".parts", [&](const std::string& name, json& j) {
    EXPECT_EQ(j.value("chunk_rows", 0), 16384) << name;
    ++entries;
  });
  EXPECT_EQ(entries, 1);
  for (int k = 0; k < 2; ++k)
    ASSERT_EQ(run("sweep " + timed.string() + " --out " + t.string() + " --resume").code, 0);
  EXPECT_EQ(input_chunk_rows(t), 16384u);
  expect_same_rows(lsi::read_sweep_file(t.string()).table,
                   lsi::read_sweep_file(whole.string()).table);

  // Journal entries that do not name their chunk rows (older parts directories, or some of them
  // left so by a resumption killed while it rewrote the entries) are read as the 256 KiB chunks:
  // 8192 rows of 4 inputs, which this study's chunk_samples gives too, so this checks that such
  // entries resume, beside entries that name theirs, not which rule they are read with.
  const json small = {{"samples", 10000}};
  const fs::path small_whole = temp_dir() / "oldjournal-whole.h5";
  ASSERT_EQ(
      run("sweep " + write_study("oldjournal", small).string() + " --out " + small_whole.string())
          .code,
      0);
  json timed_small = small;
  timed_small["stop"] = {{"wall_time_s", 1e-6}};
  const fs::path old_study = write_study("oldjournal-timed", timed_small);
  const fs::path o = temp_dir() / "oldjournal-timed.h5";
  ASSERT_EQ(run("sweep " + old_study.string() + " --out " + o.string()).code, 0);
  ASSERT_EQ(run("sweep " + old_study.string() + " --out " + o.string() + " --resume").code, 0);
  edit_journals(o.string() + ".parts", [](const std::string& name, json& j) {
    if (name != "chunk-000000000000.h5") j.erase("chunk_rows");
  });
  ASSERT_EQ(run("sweep " + old_study.string() + " --out " + o.string() + " --resume").code, 0);
  EXPECT_EQ(input_chunk_rows(o), 8192u);
  expect_same_rows(lsi::read_sweep_file(o.string()).table,
                   lsi::read_sweep_file(small_whole.string()).table);

  // Entries that disagree are refused, naming the file and both chunk sizes.
  const fs::path m = temp_dir() / "mixed-timed.h5";
  ASSERT_EQ(run("sweep " + old_study.string() + " --out " + m.string()).code, 0);
  ASSERT_EQ(run("sweep " + old_study.string() + " --out " + m.string() + " --resume").code, 0);
  edit_journals(m.string() + ".parts", [](const std::string& name, json& j) {
    if (name == "chunk-000000000001.h5") j["chunk_rows"] = 4096;
  });
  const Outcome mixed = run("sweep " + old_study.string() + " --out " + m.string() + " --resume");
  EXPECT_EQ(mixed.code, 2) << mixed.out;
  EXPECT_NE(mixed.out.find("chunk-000000000001.h5: journals chunks of 4096 rows"),
            std::string::npos)
      << mixed.out;
}

// The inputs' chunks hold one column each; a parts directory journalled by an earlier lsi, whose
// inputs' chunks hold whole rows (journal format 2), resumes in whole rows to the same rows.
TEST(SweepCli, InputChunksHoldAColumnAndOlderPartsResumeInWholeRows) {
  // Three chunks of 4096 samples; the table's chunks of 8192 rows (4 inputs).
  const json small = {{"samples", 10000}};
  const fs::path whole = temp_dir() / "inputcolumns-whole.h5";
  ASSERT_EQ(
      run("sweep " + write_study("inputcolumns", small).string() + " --out " + whole.string()).code,
      0);
  EXPECT_EQ(input_chunk_dims(whole)[1], 1u);
  json timed_small = small;
  timed_small["stop"] = {{"wall_time_s", 1e-6}};  // a chunk an invocation
  const fs::path study = write_study("inputcolumns-timed", timed_small);
  const fs::path o = temp_dir() / "inputcolumns-timed.h5";
  ASSERT_EQ(run("sweep " + study.string() + " --out " + o.string()).code, 0);
  ASSERT_EQ(run("sweep " + study.string() + " --out " + o.string() + " --resume").code, 0);
  // The parts as format 2 wrote them after two chunks: their rows in a table of whole input rows
  // (one compressed chunk, written with the second chunk), the entries' chunks without columns.
  const fs::path parts = o.string() + ".parts";
  const lsi::SweepTable so_far = lsi::read_sweep_file(o.string()).table;
  ASSERT_EQ(so_far.rows(), 8192u);
  const std::uint64_t chunk_rows = 8192;
  std::size_t written_chunks = 0;
  {
    lsi::SweepTableStream old((parts / "table-7.h5").string(), so_far.input_paths,
                              so_far.output_columns, 10000, chunk_rows, true);
    for (std::uint64_t m = 0; m < 2; ++m) {
      const fs::path entry = parts / ("chunk-00000000000" + std::to_string(m) + ".h5");
      lsi::SweepFile journalled = lsi::read_sweep_file(entry.string());
      ASSERT_EQ(journalled.header.journal.at("chunk_rows"), chunk_rows);
      lsi::SweepTable rows =
          lsi::SweepTable::with_columns(so_far.input_paths, so_far.output_columns);
      auto take = [&](auto& into, const auto& v) {
        into.assign(v.begin() + 4096 * m, v.begin() + 4096 * (m + 1));
      };
      take(rows.index, so_far.index);
      take(rows.status, so_far.status);
      take(rows.wall_time, so_far.wall_time);
      for (std::size_t k = 0; k < rows.inputs.size(); ++k) take(rows.inputs[k], so_far.inputs[k]);
      for (std::size_t c = 0; c < rows.outputs.size(); ++c)
        take(rows.outputs[c], so_far.outputs[c]);
      json chunks = json::array();
      for (const lsi::StoredChunk& k : old.append(rows)) {
        chunks.push_back({k.dataset, k.chunk, k.address, k.size});
        ++written_chunks;
      }
      journalled.header.journal = {{"format", 2},
                                   {"table_file", "table-7.h5"},
                                   {"chunk_rows", chunk_rows},
                                   {"stored_rows", old.stored_rows()},
                                   {"chunks", chunks},
                                   {"failures", journalled.header.journal.at("failures")}};
      lsi::write_sweep_file(entry.string(), journalled.header, old.pending(), nullptr,
                            lsi::SweepStorage::Plain);
    }
  }
  ASSERT_GT(written_chunks, 0u);
  for (int k = 0; k < 3 && fs::exists(parts); ++k)
    ASSERT_EQ(run("sweep " + study.string() + " --out " + o.string() + " --resume").code, 0);
  EXPECT_FALSE(fs::exists(parts));
  const std::array<hsize_t, 2> row_chunk = input_chunk_dims(o);
  EXPECT_EQ(row_chunk[0], chunk_rows);
  EXPECT_EQ(row_chunk[1], so_far.input_paths.size());
  expect_same_rows(lsi::read_sweep_file(o.string()).table,
                   lsi::read_sweep_file(whole.string()).table);
}

TEST(SweepCli, AChunkOfSeveralKernelBlocksHoldsTheRowsOfSmallChunks) {
  // On the host a chunk runs through the kernel a block of 16384 samples at a time: a chunk of
  // 40000 samples is two whole blocks and a partial one. Its rows must be, bit for bit, those of
  // chunks of 4096 (one block each), invalid samples (v <= 0, about 2 %) and their reasons
  // included.
  const json velocity = {
      {"path", "/landslide/velocity_m_s"}, {"distribution", "normal"}, {"mean", 6.0}, {"sd", 3.0}};
  const json inputs = {{{"path", "/landslide/thickness_m"},
                        {"distribution", "lognormal"},
                        {"mean", 2.0},
                        {"sd", 0.3}},
                       velocity,
                       {{"path", "/barrier/base_friction"},
                        {"distribution", "uniform"},
                        {"min", 0.3},
                        {"max", 0.7}}};
  const fs::path small = write_study(
      "small_chunks", {{"samples", 40000}, {"chunk_samples", 4096}, {"inputs", inputs}});
  const fs::path large = write_study(
      "large_chunk", {{"samples", 40000}, {"chunk_samples", 40000}, {"inputs", inputs}});
  const fs::path a = temp_dir() / "small_chunks.h5", b = temp_dir() / "large_chunk.h5";
  const Outcome ra = run("sweep " + small.string() + " --out " + a.string());
  ASSERT_EQ(ra.code, 0) << ra.out;
  const Outcome rb = run("sweep " + large.string() + " --out " + b.string());
  ASSERT_EQ(rb.code, 0) << rb.out;
  const lsi::SweepFile fa = lsi::read_sweep_file(a.string()), fb = lsi::read_sweep_file(b.string());
  expect_same_rows(fa.table, fb.table);
  EXPECT_EQ(fa.table.failure_index, fb.table.failure_index);
  EXPECT_EQ(fa.table.failure_reason, fb.table.failure_reason);
  // P(N(6, 3) <= 0) = Phi(-2) = 0.0228: 911 of 40000 expected (sd 30); the invalid rows are
  // spread over the blocks.
  EXPECT_GT(fb.table.failure_index.size(), 700u);
  EXPECT_LT(fb.table.failure_index.size(), 1100u);
  EXPECT_GT(fb.table.failure_index.back(), 2u * 16384u);
  EXPECT_EQ(fa.statistics["outputs"], fb.statistics["outputs"]);
}

TEST(SweepCli, GridDesignRunsTheFullFactorialFirstInputFastest) {
  const fs::path study = write_study("grid", {{"design", "grid"},
                                              {"samples", nullptr},
                                              {"correlation", nullptr},
                                              {"inputs",
                                               {{{"path", "/landslide/velocity_m_s"},
                                                 {"distribution", "grid"},
                                                 {"min", 4},
                                                 {"max", 8},
                                                 {"count", 3}},
                                                {{"path", "/barrier/base_friction"},
                                                 {"distribution", "discrete"},
                                                 {"values", {0.4, 0.6}}}}}});
  const fs::path out = temp_dir() / "grid.h5";
  ASSERT_EQ(run("sweep " + study.string() + " --out " + out.string()).code, 0);
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  ASSERT_EQ(f.table.rows(), 6u);
  const double v[6] = {4, 6, 8, 4, 6, 8}, mu[6] = {0.4, 0.4, 0.4, 0.6, 0.6, 0.6};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(f.table.inputs[0][i], v[i]);
    EXPECT_EQ(f.table.inputs[1][i], mu[i]);
  }
}

// A grid walked in order is no random sample: its first values (those the statistics locate the
// quantiles from, 2^18 of them) cover the lower velocities only, so the statistics read the
// table file back for the quantiles. 300000 samples in chunks of 50000 (the last rows pending in
// the table when the file is read); the statistics are those of the table's ok rows.
TEST(SweepCli, AGridWalkedInOrderIsDescribedFromTheTableReadBack) {
  const fs::path study = write_study("big-grid", {{"design", "grid"},
                                                  {"samples", nullptr},
                                                  {"correlation", nullptr},
                                                  {"chunk_samples", 50000},
                                                  {"inputs",
                                                   {{{"path", "/barrier/base_friction"},
                                                     {"distribution", "grid"},
                                                     {"min", 0.3},
                                                     {"max", 0.7},
                                                     {"count", 3}},
                                                    {{"path", "/landslide/velocity_m_s"},
                                                     {"distribution", "grid"},
                                                     {"min", 2},
                                                     {"max", 12},
                                                     {"count", 100000}}}}});
  const fs::path out = temp_dir() / "big-grid.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  ASSERT_EQ(f.table.rows(), 300000u);
  for (std::size_t c = 0; c < f.table.output_columns.size(); ++c) {
    std::vector<double> ok;
    for (std::size_t i = 0; i < f.table.rows(); ++i)
      if (f.table.status[i] == 0) ok.push_back(f.table.outputs[c][i]);
    const lsi::sweeps::OutputStatistics want = lsi::sweeps::describe(ok, 0.95);
    const json& o = f.statistics["outputs"][f.table.output_columns[c]];
    ASSERT_TRUE(o.contains("q95")) << o.dump();
    EXPECT_EQ(o["count"].get<std::size_t>(), ok.size());
    EXPECT_EQ(o["mean"].get<double>(), want.mean);
    EXPECT_EQ(o["standard_deviation"].get<double>(), want.standard_deviation);
    EXPECT_EQ(o["q05"].get<double>(), want.q05);
    EXPECT_EQ(o["q50"].get<double>(), want.q50);
    EXPECT_EQ(o["q95"].get<double>(), want.q95);
    EXPECT_EQ(o["q95_ci"][1].get<double>(), want.q95_ci.high);
    EXPECT_EQ(o["max"].get<double>(), want.max);
  }
}

TEST(SweepCli, MpmSamplesRunBesideTheClosedForms) {
  // Two coarse MPM runs (cell h/4, 1 particle per cell: about a second each), in one chunk: side
  // by side on two threads (model/concurrent_runs.hpp).
  json scene;
  std::ifstream(source_dir / "scenes/former-reference/L1-B1.json") >> scene;
  scene["methods"]["mpm"] = {
      {"cell_size_m", 0.5}, {"phases", "dry"}, {"transfer", "pic"}, {"particles_per_cell", 1}};
  const fs::path study = write_study("mpm", {{"scene", scene},
                                             {"samples", 2},
                                             {"chunk_samples", 2},
                                             {"correlation", nullptr},
                                             {"thresholds", nullptr},
                                             {"methods", {"analytical", "mpm"}},
                                             {"outputs", {"peak_force", "impact_duration"}},
                                             {"inputs",
                                              {{{"path", "/landslide/velocity_m_s"},
                                                {"distribution", "uniform"},
                                                {"min", 5},
                                                {"max", 7}}}}});
  const fs::path out = temp_dir() / "mpm.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  ASSERT_EQ(f.table.rows(), 2u);
  const std::vector<std::string> cols = {"analytical/peak_force", "analytical/impact_duration",
                                         "mpm/peak_force", "mpm/impact_duration"};
  EXPECT_EQ(f.table.output_columns, cols);
  const lsi::Study st = lsi::load_study(study.string());
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(f.table.status[i], 0)
        << (f.table.failure_reason.empty() ? std::string("") : f.table.failure_reason[0]);
    EXPECT_GT(f.table.wall_time[i], 0.0f);
    // The same sample run directly: the sweep must store what the MPM gives. Same code, so equal
    // up to the order of floating-point sums (one thread side by side, two here): 1e-9 relative.
    const double x = f.table.inputs[0][i];
    const lsi::MpmOutcome o =
        lsi::run_mpm_case(lsi::impact_case(lsi::parse_scene(lsi::sample_scene_document(st, &x))));
    ASSERT_TRUE(o.finished()) << o.status();
    EXPECT_NEAR(f.table.outputs[2][i], o.result.peak_force, 1e-9 * o.result.peak_force);
    EXPECT_NEAR(f.table.outputs[3][i], o.result.impact_duration, 1e-9 * o.result.impact_duration);
    // The closed form beside it is the scalar model's.
    const lsi::MethodResult a =
        lsi::run_analytical(lsi::parse_scene(lsi::sample_scene_document(st, &x)));
    EXPECT_NEAR(f.table.outputs[0][i], a.peak_force, 1e-12 * a.peak_force);
  }
}

// A study of coarse MPM runs (cell h/4, one particle per cell: a few hundred points, tens of
// milliseconds each): velocity and base friction sampled, the friction below zero (invalid: the
// range check refuses it) for about a fifth of the samples, so that failures and MPM rows mix.
fs::path write_mpm_study(const std::string& name, json extra) {
  json scene;
  std::ifstream(source_dir / "scenes/former-reference/L1-B1.json") >> scene;
  scene["methods"]["mpm"] = {
      {"cell_size_m", 0.5}, {"phases", "dry"}, {"transfer", "pic"}, {"particles_per_cell", 1}};
  json study = {
      {"scene", scene},
      {"samples", 16},
      {"chunk_samples", nullptr},  // the default: 1 for a study that runs the MPM
      {"correlation", nullptr},
      {"thresholds", nullptr},
      {"methods", {"analytical", "mpm"}},
      {"outputs", {"peak_force", "final_displacement"}},
      {"inputs",
       {{{"path", "/landslide/velocity_m_s"}, {"distribution", "uniform"}, {"min", 5}, {"max", 7}},
        {{"path", "/barrier/base_friction"},
         {"distribution", "uniform"},
         {"min", -0.2},
         {"max", 0.7}}}}};
  if (!extra.is_null()) study.merge_patch(extra);  // `{}` is a null json: nothing to merge
  return write_study(name, study);
}

// The rows and failures of two result files of one study's samples (their chunks may differ).
void expect_same_samples(const lsi::SweepFile& a, const lsi::SweepFile& b) {
  expect_same_rows(a.table, b.table);
  EXPECT_EQ(a.table.failure_index, b.table.failure_index);
  EXPECT_EQ(a.table.failure_reason, b.table.failure_reason);
}

TEST(SweepCli, MpmSamplesOfSmallChunksRunSideBySideWithTheSameNumbers) {
  // Every run on every thread it is given (--points-per-thread 0): alone, that is every thread;
  // side by side, one. A sweep's MPM samples run one thread each however the chunks cut them
  // (model/concurrent_runs.hpp), so that a chunk a sample, one chunk of every sample, and a run
  // stopped by its wall-time limit and resumed give the same numbers, bit for bit. Two runs at
  // once at most, whatever the machine, for the bound on the first invocation below.
  const std::string opts = "--points-per-thread 0 --runs-at-once 2 sweep ";
  const fs::path small = write_mpm_study("mpm-small-chunks", {});
  const fs::path one = write_mpm_study("mpm-one-chunk", {{"chunk_samples", 16}});
  const fs::path timed = write_mpm_study("mpm-timed", {{"stop", {{"wall_time_s", 1e-6}}}});
  const fs::path a = temp_dir() / "mpm-small.h5", b = temp_dir() / "mpm-one.h5",
                 c = temp_dir() / "mpm-timed.h5";
  const Outcome ra = run(opts + small.string() + " --out " + a.string());
  ASSERT_EQ(ra.code, 0) << ra.out;
  const Outcome rb = run(opts + one.string() + " --out " + b.string());
  ASSERT_EQ(rb.code, 0) << rb.out;
  const lsi::SweepFile fa = lsi::read_sweep_file(a.string());
  ASSERT_EQ(fa.table.rows(), 16u);
  std::size_t invalid = 0;
  for (const auto s : fa.table.status)
    invalid += s == std::int8_t(lsi::SampleStatus::invalid_input);
  EXPECT_GT(invalid, 0u) << "some samples must be refused, between MPM rows";
  EXPECT_LT(invalid, 12u) << "most samples must run the MPM";
  expect_same_samples(fa, lsi::read_sweep_file(b.string()));

  // Stopped at its first chunk's commit: no run starts any more, the runs under way finish and
  // the chunks whose runs have all started are committed (at most the rows in flight: four a
  // run at once, and a chunk); --resume goes on until the study is complete.
  const Outcome first = run(opts + timed.string() + " --out " + c.string() + " --format json");
  ASSERT_EQ(first.code, 0) << first.out;
  const std::size_t n = json::parse(first.out)["samples_done"].get<std::size_t>();
  EXPECT_GE(n, 1u);
  EXPECT_LE(n, 4u * 2u + 1u) << "a wall-time stop starts no run after the first commit";
  for (int k = 0; k < 16 && !lsi::read_sweep_file(c.string()).header.complete; ++k)
    ASSERT_EQ(run(opts + timed.string() + " --out " + c.string() + " --resume").code, 0);
  const lsi::SweepFile fc = lsi::read_sweep_file(c.string());
  ASSERT_TRUE(fc.header.complete);
  expect_same_samples(fa, fc);
}

TEST(SweepCli, AnIntervalRuleMetAmongMpmSamplesSideBySideStopsWhereOneAtATimeStops) {
  // The analytical peak force's mean to +-8 %: its coefficient of variation is about 0.2 here,
  // so (1.96 * 0.2 / 0.08)^2 = 24 or so ok samples (of some 40: refused samples and MPM runs
  // ended with the barrier sliding are not ok); chunks started after the chunk that meets the
  // rule are dropped, as a run one sample at a time never starts them.
  const fs::path study = write_mpm_study("mpm-interval", {{"samples", 200},
                                                          {"stop",
                                                           {{"interval",
                                                             {{"method", "analytical"},
                                                              {"output", "peak_force"},
                                                              {"statistic", "mean"},
                                                              {"relative_half_width", 0.08},
                                                              {"min_samples", 5}}}}}});
  const fs::path a = temp_dir() / "mpm-interval-a.h5", b = temp_dir() / "mpm-interval-b.h5";
  const Outcome side = run("sweep " + study.string() + " --out " + a.string() + " --format json");
  ASSERT_EQ(side.code, 0) << side.out;
  const Outcome alone =
      run("--runs-at-once 1 sweep " + study.string() + " --out " + b.string() + " --format json");
  ASSERT_EQ(alone.code, 0) << alone.out;
  const json ja = json::parse(side.out), jb = json::parse(alone.out);
  EXPECT_NE(ja["stopped_by"].get<std::string>().find("confidence interval"), std::string::npos);
  EXPECT_EQ(ja["stopped_by"], jb["stopped_by"]);
  const std::size_t n = ja["samples_done"].get<std::size_t>();
  EXPECT_EQ(n, jb["samples_done"].get<std::size_t>());
  EXPECT_GE(n, 10u);
  EXPECT_LT(n, 100u);
  // A run of a few hundred points runs on one thread alone too (model/run_threads.hpp).
  expect_same_samples(lsi::read_sweep_file(a.string()), lsi::read_sweep_file(b.string()));
}

TEST(SweepCli, MpmRunsAtQuantilesOfAClosedFormOutput) {
  json scene;
  std::ifstream(source_dir / "scenes/former-reference/L1-B1.json") >> scene;
  scene["methods"]["mpm"] = {
      {"cell_size_m", 0.5}, {"phases", "dry"}, {"transfer", "pic"}, {"particles_per_cell", 1}};
  const fs::path study = write_study(
      "quantiles", {{"scene", scene},
                    {"samples", 1001},
                    {"correlation", nullptr},
                    {"thresholds", nullptr},
                    {"outputs", {"peak_force"}},
                    {"inputs",
                     {{{"path", "/landslide/velocity_m_s"},
                       {"distribution", "uniform"},
                       {"min", 4},
                       {"max", 8}}}},
                    {"mpm_at_quantiles",
                     {{"method", "analytical"}, {"output", "peak_force"}, {"quantiles", {0.5}}}}});
  const fs::path out = temp_dir() / "quantiles.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("MPM at quantiles of analytical/peak_force"), std::string::npos) << r.out;
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  const json& q = f.statistics["mpm_at_quantiles"];
  ASSERT_EQ(q.size(), 1u);
  // The median of 1001 values is one of them: the chosen sample's peak force is exactly it.
  std::vector<double> peaks = f.table.outputs[1];
  std::sort(peaks.begin(), peaks.end());
  const std::size_t sample = q[0]["sample"].get<std::size_t>();
  EXPECT_EQ(f.table.outputs[1][sample], peaks[500]);
  EXPECT_EQ(q[0]["closed_form"]["analytical/peak_force"].get<double>(), peaks[500]);
  // The MPM value is that of the sample's scene run directly (1e-9: order of sums only), and the
  // error is (closed form - MPM) / MPM.
  const lsi::Study st = lsi::load_study(study.string());
  const double x = f.table.inputs[0][sample];
  const lsi::MpmOutcome o =
      lsi::run_mpm_case(lsi::impact_case(lsi::parse_scene(lsi::sample_scene_document(st, &x))));
  const double m = q[0]["mpm"]["peak_force"].get<double>();
  EXPECT_NEAR(m, o.result.peak_force, 1e-9 * m);
  EXPECT_NEAR(q[0]["relative_error"]["analytical/peak_force"].get<double>(), (peaks[500] - m) / m,
              1e-12);
}

}  // namespace

namespace {
// The momentum-consistent barrier (the scene's "barrier_model") runs in the sweep's kernel: each
// sample's outputs equal the scene-level model's (model/closed_form_methods.cpp) for the same
// inputs; the same adaptive integration on both sides, so to round-off (1e-9: the error control
// may take other steps where an input differs in its last bits through the sampler).
TEST(SweepCli, MomentumBarrierModelRunsInTheSweepKernel) {
  json scene;
  std::ifstream(source_dir / "scenes/reference/L2-B1.json") >> scene;
  scene["methods"] = {{"empirical", {{"barrier_model", "momentum"}}},
                      {"analytical", {{"barrier_model", "momentum"}}}};
  const fs::path study = write_study("momentum", {{"scene", scene},
                                                  {"samples", 24},
                                                  {"correlation", nullptr},
                                                  {"thresholds", nullptr},
                                                  {"inputs",
                                                   {{{"path", "/landslide/velocity_m_s"},
                                                     {"distribution", "uniform"},
                                                     {"min", 4},
                                                     {"max", 12}},
                                                    {{"path", "/barrier/face_friction"},
                                                     {"distribution", "uniform"},
                                                     {"min", 0},
                                                     {"max", 0.5}}}}});
  const fs::path out = temp_dir() / "momentum.h5";
  const Outcome r = run("sweep " + study.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const lsi::SweepFile f = lsi::read_sweep_file(out.string());
  const lsi::Study st = lsi::load_study(study.string());
  ASSERT_EQ(f.table.rows(), 24u);
  int sliding = 0;
  for (std::size_t i = 0; i < 24; ++i) {
    ASSERT_EQ(f.table.status[i], 0);
    const double x[2] = {f.table.inputs[0][i], f.table.inputs[1][i]};
    const lsi::Scene s = lsi::parse_scene(lsi::sample_scene_document(st, x));
    const lsi::MethodResult e = lsi::run_empirical(s), a = lsi::run_analytical(s);
    EXPECT_EQ(a.barrier_model, "momentum");
    // Columns: empirical peak, rise, duration, displacement, then the analytical's.
    const double want[8] = {e.peak_force, e.rise_time, e.impact_duration, e.final_displacement,
                            a.peak_force, a.rise_time, a.impact_duration, a.final_displacement};
    for (int c = 0; c < 8; ++c)
      EXPECT_NEAR(f.table.outputs[c][i], want[c], 1e-9 * std::fabs(want[c]) + 1e-12)
          << "sample " << i << " column " << f.table.output_columns[c];
    sliding += a.final_displacement > 0.01;
  }
  EXPECT_GT(sliding, 10);  // most samples slide: the comparison covers the sliding phases
}
}  // namespace
