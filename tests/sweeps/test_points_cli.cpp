// `lsi sweep` on a study of design "points" end to end: the given points run through the same
// batched kernel as the drawn designs (the values of a Monte Carlo sweep's own samples, given
// back as points, are that sweep's values), their table comes back as CSV in the order of the
// points, and resume and shards work as for any design.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/sweep_file.hpp"
#include "model/sweep_table.hpp"
#include "support/run_command.hpp"
#include "support/temp_files.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;
const fs::path source_dir = LSI_SOURCE_DIR;
const std::string lsi_exe = LSI_EXE;

using Outcome = lsi::testing::CommandOutcome;  // out: stdout and stderr together

Outcome run(const std::string& args) { return lsi::testing::run_lsi(lsi_exe, args); }
fs::path temp_dir() { return lsi::testing::process_temp_dir("lsi_points_test"); }
fs::path write_json(const std::string& name, const json& j) {
  return lsi::testing::write_text(temp_dir() / name, j.dump(2));
}

std::string shortest(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

// The points file of a table's inputs, one row per sample, each value in its shortest form that
// reads back to the same double.
fs::path write_points(const std::string& name, const lsi::SweepTable& t) {
  std::string text;
  for (std::size_t d = 0; d < t.input_paths.size(); ++d) text += (d ? "," : "") + t.input_paths[d];
  text += "\n";
  for (std::size_t i = 0; i < t.rows(); ++i) {
    for (std::size_t d = 0; d < t.inputs.size(); ++d)
      text += (d ? "," : "") + shortest(t.inputs[d][i]);
    text += "\n";
  }
  return lsi::testing::write_text(temp_dir() / name, text);
}

std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> row;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) row.push_back(cell);
    rows.push_back(row);
  }
  return rows;
}

json base_study(const std::string& name) {
  return {{"name", name},
          {"scene", (source_dir / "scenes/former-reference/L1-B1.json").string()},
          {"methods", {"empirical", "analytical"}}};
}

// The same inputs give bitwise the same outputs: the points design reads each row where the
// Monte Carlo design draws it, into the same kernel, and the points file holds each input in a
// form that reads back to the same double.
TEST(PointsCli, GivenPointsGiveExactlyTheValuesOfTheMonteCarloSweepThatDrewThem) {
  json mc = base_study("drawn");
  mc["samples"] = 3000;
  mc["seed"] = 5;
  mc["chunk_samples"] = 1024;
  mc["inputs"] = {{{"path", "/landslide/thickness_m"},
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
                   {"max", 0.7}}};
  mc["correlation"] = {
      {{"inputs", {"/landslide/thickness_m", "/landslide/velocity_m_s"}}, {"rho", 0.4}}};
  const fs::path drawn_h5 = temp_dir() / "drawn.h5";
  const Outcome m =
      run("sweep " + write_json("drawn.json", mc).string() + " --out " + drawn_h5.string());
  ASSERT_EQ(m.code, 0) << m.out;
  const lsi::SweepFile drawn = lsi::read_sweep_file(drawn_h5.string());
  for (auto s : drawn.table.status) ASSERT_EQ(s, 0);  // every drawn sample is a valid scene

  json given = base_study("given");
  given["design"] = "points";
  given["points"] = {{"file", write_points("drawn.csv", drawn.table).filename().string()}};
  const fs::path given_h5 = temp_dir() / "given.h5", given_csv = temp_dir() / "given.csv";
  const Outcome g =
      run("sweep " + write_json("given.json", given).string() + " --out " + given_h5.string() +
          " --table-csv " + given_csv.string() + " --format json");
  ASSERT_EQ(g.code, 0) << g.out;
  EXPECT_EQ(json::parse(g.out)["statistics"]["design"], "points") << g.out;
  const lsi::SweepFile points = lsi::read_sweep_file(given_h5.string());
  ASSERT_EQ(points.table.rows(), 3000u);
  EXPECT_EQ(points.table.input_paths, drawn.table.input_paths);
  EXPECT_EQ(points.table.inputs, drawn.table.inputs);
  ASSERT_EQ(points.table.output_columns, drawn.table.output_columns);
  for (std::size_t c = 0; c < drawn.table.outputs.size(); ++c)
    for (std::size_t i = 0; i < 3000; ++i)
      ASSERT_EQ(points.table.outputs[c][i], drawn.table.outputs[c][i])
          << drawn.table.output_columns[c] << " sample " << i;
  // The statistics are those of the same values.
  EXPECT_EQ(points.statistics["outputs"], drawn.statistics["outputs"]);

  // The CSV table: a header, then one row per point in the file's order, every number as stored.
  const auto rows = read_csv(given_csv);
  ASSERT_EQ(rows.size(), 3001u);
  std::vector<std::string> header = {"index"};
  for (const auto& p : drawn.table.input_paths) header.push_back(p);
  for (const auto& c : drawn.table.output_columns) header.push_back(c);
  header.push_back("status");
  EXPECT_EQ(rows[0], header);
  for (std::size_t i = 0; i < 3000; ++i) {
    const auto& r = rows[i + 1];
    ASSERT_EQ(r.size(), header.size());
    EXPECT_EQ(r[0], std::to_string(i));
    for (std::size_t d = 0; d < 4; ++d) EXPECT_EQ(std::stod(r[1 + d]), drawn.table.inputs[d][i]);
    for (std::size_t c = 0; c < drawn.table.outputs.size(); ++c)
      ASSERT_EQ(std::stod(r[5 + c]), drawn.table.outputs[c][i]) << header[5 + c] << " row " << i;
    EXPECT_EQ(r.back(), "0");
  }
}

TEST(PointsCli, ResumeRefusesAChangedPointsFileAndShardsMergeIntoOneRun) {
  json mc = base_study("few");
  mc["samples"] = 600;
  mc["inputs"] = {
      {{"path", "/landslide/velocity_m_s"}, {"distribution", "uniform"}, {"min", 4}, {"max", 8}}};
  const fs::path drawn_h5 = temp_dir() / "few.h5";
  ASSERT_EQ(
      run("sweep " + write_json("few.json", mc).string() + " --out " + drawn_h5.string()).code, 0);
  const lsi::SweepTable drawn = lsi::read_sweep_file(drawn_h5.string()).table;
  const fs::path points = write_points("few.csv", drawn);

  json given = base_study("few-given");
  given["design"] = "points";
  given["points"] = {{"file", points.string()}};
  given["chunk_samples"] = 200;
  const fs::path whole = temp_dir() / "whole.h5";
  const fs::path study = write_json("few-given.json", given);
  ASSERT_EQ(run("sweep " + study.string() + " --out " + whole.string()).code, 0);

  // Three shards of 200 points each, merged: the file of the single run (wall times aside).
  std::string files;
  for (int k = 0; k < 3; ++k) {
    const fs::path f = temp_dir() / ("few-shard" + std::to_string(k) + ".h5");
    const Outcome r = run("sweep " + study.string() + " --out " + f.string() + " --shard " +
                          std::to_string(k) + "/3");
    ASSERT_EQ(r.code, 0) << r.out;
    files += " " + f.string();
  }
  const fs::path merged = temp_dir() / "few-merged.h5";
  const Outcome m = run("merge --out " + merged.string() + files);
  ASSERT_EQ(m.code, 0) << m.out;
  const lsi::SweepFile a = lsi::read_sweep_file(whole.string()),
                       b = lsi::read_sweep_file(merged.string());
  EXPECT_EQ(a.header.fingerprint, b.header.fingerprint);
  EXPECT_EQ(a.table.inputs, b.table.inputs);
  EXPECT_EQ(a.table.outputs, b.table.outputs);

  // A run stopped by its wall time after one chunk; the points file then changes: it is another
  // study, which --resume refuses to continue.
  given["stop"] = {{"wall_time_s", 1e-6}};
  const fs::path timed = write_json("few-timed.json", given);
  const fs::path t = temp_dir() / "few-timed.h5";
  ASSERT_EQ(run("sweep " + timed.string() + " --out " + t.string()).code, 0);
  ASSERT_TRUE(fs::exists(t.string() + ".parts"));
  std::string text;
  {
    std::ifstream in(points);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(points) << text.substr(0, text.rfind('\n', text.size() - 2) + 1) << "5\n";
  const Outcome changed = run("sweep " + timed.string() + " --out " + t.string() + " --resume");
  EXPECT_EQ(changed.code, 2) << changed.out;
  EXPECT_NE(changed.out.find("left by another study"), std::string::npos) << changed.out;
  std::ofstream(points) << text;  // restored: the same study again, resumed to the end
  for (int k = 0; k < 2; ++k)
    ASSERT_EQ(run("sweep " + timed.string() + " --out " + t.string() + " --resume").code, 0);
  const lsi::SweepFile resumed = lsi::read_sweep_file(t.string());
  EXPECT_TRUE(resumed.header.complete);
  EXPECT_EQ(resumed.table.outputs, a.table.outputs);
}

}  // namespace
