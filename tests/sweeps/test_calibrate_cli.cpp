// `lsi calibrate` end to end on coarse copies of reference scenes (4 cells through the flow's
// thickness: the MPM runs take well under a second each): exit codes, the JSON report, the HDF5
// file with the misfit maps, and the one-line errors for bad options.
#include <gtest/gtest.h>

#include <hdf5.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/temp_files.hpp"
#include <string>

namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
const fs::path source_dir = LSI_SOURCE_DIR;
const std::string lsi_exe = LSI_EXE;

struct Outcome {
  int code;
  std::string out;  // stdout only (stderr goes to err)
  std::string err;
};

fs::path temp_dir() { return lsi::testing::process_temp_dir("lsi_calibrate_cli"); }

Outcome run(const std::string& args) {
  const fs::path err = temp_dir() / "stderr.txt";
  const lsi::testing::CommandOutcome r =
      lsi::testing::run_command(lsi_exe + " " + args + " 2>" + err.string());
  std::ifstream e(err);
  return {r.code, r.out, std::string(std::istreambuf_iterator<char>(e), {})};
}

// A reference scene, renamed, with 4 cells through the thickness (h/4 = 0.5 m for L1).
fs::path coarse_scene(const std::string& reference, const std::string& name, bool fixed) {
  std::ifstream in(source_dir / "scenes/former-reference" / (reference + ".json"));
  json s = json::parse(in);
  s["name"] = name;
  s["barrier"]["fixed"] = fixed;
  s["methods"]["mpm"]["cell_size_m"] = s["landslide"]["thickness_m"].get<double>() / 4;
  const fs::path p = temp_dir() / (name + ".json");
  std::ofstream(p) << s.dump(2);
  return p;
}

bool finite_in(const json& v, double lo, double hi) {
  return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= lo &&
         v.get<double>() <= hi;
}

TEST(CalibrateCli, FitsCoarseReferenceScenesAndWritesTheMaps) {
  const fs::path dir = temp_dir();
  const fs::path a = coarse_scene("L1-B1", "c-free-a", false);
  const fs::path b = coarse_scene("L1-B2", "c-free-b", false);
  const fs::path f = coarse_scene("L1-B3", "c-fixed", true);
  // c-free-a's history comes from a results directory (as `lsi run --out` writes it); the other
  // two have none there and their MPM runs inside `lsi calibrate`.
  fs::create_directories(dir / "res");
  const Outcome pre =
      run("run " + a.string() + " --methods mpm --out " + (dir / "res/c-free-a.h5").string());
  ASSERT_EQ(pre.code, 0) << pre.out << pre.err;
  const fs::path h5 = dir / "cal.h5";
  const Outcome r =
      run("calibrate " + a.string() + " " + b.string() + " " + f.string() + " --results-dir " +
          (dir / "res").string() + " --grid 21x11 --format json --out " + h5.string());
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["objective"], "nrms");
  ASSERT_EQ(j["cases"].size(), 3u);
  EXPECT_EQ(j["cases"][0]["source"].get<std::string>().rfind("file ", 0), 0u);
  EXPECT_EQ(j["cases"][1]["source"], "mpm run");
  EXPECT_EQ(j["cases"][2]["group"], "fixed");
  for (const auto& c : j["cases"]) {
    const auto& an = c["analytical"];
    // The parameters' allowed ranges: lambda in (0, 1], tau in (0, 1).
    EXPECT_TRUE(finite_in(an["lambda"], 1e-9, 1.0)) << c.dump();
    EXPECT_TRUE(finite_in(an["tau"], 1e-9, 1.0 - 1e-9)) << c.dump();
    // A normalised RMS misfit of a pulse against a history it roughly follows: in (0, 1); LM
    // never ends above the best node of the map.
    EXPECT_TRUE(finite_in(an["misfit"], 0.0, 1.0)) << c.dump();
    EXPECT_LE(an["misfit"].get<double>(), an["grid_misfit"].get<double>());
    EXPECT_TRUE(finite_in(an["sigma_lambda"], 0.0, 10.0)) << c.dump();
    EXPECT_TRUE(finite_in(an["sigma_tau"], 0.0, 10.0)) << c.dump();
    // The profile range brackets the best fit.
    EXPECT_LE(an["lambda_range"][0].get<double>(), an["lambda"].get<double>());
    EXPECT_GE(an["lambda_range"][1].get<double>(), an["lambda"].get<double>());
    EXPECT_GT(an["iterations"].get<int>(), 0);
    const auto& em = c["empirical"];
    // L1: v0 = 6 m/s, h = 2 m, beta 60-80 deg: Fr = 6 sin(beta) / sqrt(9.81 * 2) in [1.17, 1.34];
    // the MPM's peak force gives alpha_MPM of order 1 (0.5 to 5 covers every resolution seen).
    EXPECT_TRUE(finite_in(em["froude"], 1.17, 1.34)) << c.dump();
    EXPECT_TRUE(finite_in(em["alpha"], 0.5, 5.0)) << c.dump();
    EXPECT_TRUE(finite_in(em["tau"], 1e-9, 1.0 - 1e-9)) << c.dump();
    EXPECT_TRUE(finite_in(c["mpm"]["peak_force"], 1e4, 1e7)) << c.dump();
    EXPECT_TRUE(finite_in(c["mpm"]["run_time_s"], 1e-6, 60.0)) << c.dump();
  }
  // The two MPM runs of the campaign went side by side, one thread each (--runs-at-once 0, the
  // default); one after the other with every thread they give the same histories: their sums
  // only run in another order, 1e-9 of the peak covers the round-off a run's plastic flow may
  // amplify, far below any change of the physics.
  const Outcome one =
      run("--runs-at-once 1 calibrate " + a.string() + " " + b.string() + " " + f.string() +
          " --results-dir " + (dir / "res").string() + " --grid 21x11 --format json");
  ASSERT_EQ(one.code, 0) << one.out << one.err;
  const json k = json::parse(one.out);
  for (int c : {1, 2}) {
    const double side = j["cases"][c]["mpm"]["peak_force"],
                 after = k["cases"][c]["mpm"]["peak_force"];
    EXPECT_NEAR(side, after, 1e-9 * after) << c;
  }
  ASSERT_EQ(j["groups"].size(), 2u);
  for (const auto& g : j["groups"]) {
    const bool fixed = g["group"] == "fixed";
    EXPECT_EQ(g["n"].get<int>(), fixed ? 1 : 2);
    EXPECT_TRUE(finite_in(g["analytical"]["lambda"]["mean"], 1e-9, 1.0));
    EXPECT_DOUBLE_EQ(g["analytical"]["paper"]["lambda"].get<double>(), fixed ? 0.72 : 0.41);
    EXPECT_DOUBLE_EQ(g["analytical"]["paper"]["tau"].get<double>(), fixed ? 0.17 : 0.25);
    // Two free cases: a Student-t interval (t_{0.975,1} = 12.7) around the mean; one fixed case:
    // none (null).
    if (fixed) {
      EXPECT_TRUE(g["analytical"]["lambda"]["ci"][0].is_null());
    } else {
      EXPECT_LE(g["analytical"]["lambda"]["ci"][0].get<double>(),
                g["analytical"]["lambda"]["mean"].get<double>());
      EXPECT_GE(g["analytical"]["lambda"]["ci"][1].get<double>(),
                g["analytical"]["lambda"]["mean"].get<double>());
      // Two distinct Froude numbers: a1, a2 determined (no interval with n - 2 = 0).
      EXPECT_TRUE(finite_in(g["empirical"]["a1"], 1e-3, 1e3));
      EXPECT_TRUE(finite_in(g["empirical"]["a2"], -20.0, 20.0));
    }
  }
  // Six rows per case: empirical default/calibrated, analytical default/calibrated/case fit, MPM.
  ASSERT_EQ(j["comparison"].size(), 18u);
  for (const auto& row : j["comparison"]) {
    EXPECT_TRUE(finite_in(row["peak_force"], 1e3, 1e8)) << row.dump();
    EXPECT_TRUE(finite_in(row["impact_duration"], 1e-3, 100.0)) << row.dump();
    // Closed forms in microseconds (they sample 1001 points), below 0.1 s even on a loaded machine.
    if (row["method"] != "mpm") {
      EXPECT_TRUE(finite_in(row["run_time_s"], 1e-9, 0.1)) << row.dump();
      EXPECT_TRUE(finite_in(row["peak_force_rel_error"], -1.0, 100.0)) << row.dump();
    }
  }

  // The HDF5 file: maps with their axes, groups, comparison; no temporary file left behind.
  hid_t file = H5Fopen(h5.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  for (const char* name : {"c-free-a", "c-free-b", "c-fixed"}) {
    const std::string base = std::string("/cases/") + name;
    hid_t d = H5Dopen2(file, (base + "/misfit_map").c_str(), H5P_DEFAULT);
    ASSERT_GE(d, 0) << name;
    hid_t s = H5Dget_space(d);
    hsize_t dims[2] = {0, 0};
    EXPECT_EQ(H5Sget_simple_extent_ndims(s), 2);
    H5Sget_simple_extent_dims(s, dims, nullptr);
    EXPECT_EQ(dims[0], 21u);  // lambda cells
    EXPECT_EQ(dims[1], 11u);  // tau cells
    std::vector<double> map(dims[0] * dims[1]);
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, map.data());
    for (double m : map) EXPECT_TRUE(std::isfinite(m) && m >= 0.0);
    H5Sclose(s);
    H5Dclose(d);
    for (const char* axis : {"/lambda", "/tau"}) {
      hid_t a = H5Dopen2(file, (base + axis).c_str(), H5P_DEFAULT);
      ASSERT_GE(a, 0) << base << axis;
      hid_t as = H5Dget_space(a);
      EXPECT_EQ(H5Sget_simple_extent_npoints(as), axis[1] == 'l' ? 21 : 11);
      H5Sclose(as);
      H5Dclose(a);
    }
  }
  for (const char* path : {"/groups/free", "/groups/fixed", "/comparison/peak_force"})
    EXPECT_GT(H5Lexists(file, path, H5P_DEFAULT), 0) << path;
  H5Fclose(file);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();

  // The table format prints the groups beside the paper's values.
  const Outcome t = run("calibrate " + a.string() + " --results-dir " + (dir / "res").string() +
                        " --objective peak-duration --grid 11x11");
  ASSERT_EQ(t.code, 0) << t.out << t.err;
  EXPECT_NE(t.out.find("(paper 0.41)"), std::string::npos) << t.out;
}

TEST(CalibrateCli, BadOptionsExitTwoNamingTheOption) {
  const fs::path a = coarse_scene("L1-B1", "c-bad", false);
  const Outcome o = run("calibrate " + a.string() + " --objective foo");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--objective foo"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("nrms, peak-duration"), std::string::npos) << o.err;
  for (const char* grid : {"0x5", "41", "3x1", "axb"}) {
    const Outcome g = run("calibrate " + a.string() + " --grid " + grid);
    EXPECT_EQ(g.code, 2) << grid;
    EXPECT_NE(g.err.find(std::string("--grid ") + grid), std::string::npos) << g.err;
    EXPECT_NE(g.err.find("[2, 2001]"), std::string::npos) << g.err;
  }
  for (const char* runs : {"-1", "two"}) {
    const Outcome r = run(std::string("--runs-at-once ") + runs + " calibrate " + a.string());
    EXPECT_EQ(r.code, 2) << runs;
    EXPECT_NE(r.err.find("--runs-at-once"), std::string::npos) << r.err;
  }
  const Outcome fmt = run("calibrate " + a.string() + " --format xml");
  EXPECT_EQ(fmt.code, 2);
  EXPECT_NE(fmt.err.find("--format xml"), std::string::npos) << fmt.err;
  // A scene without methods.mpm and no stored history: the missing field is named.
  std::ifstream in(source_dir / "scenes/former-reference/L1-B1.json");
  json s = json::parse(in);
  s["methods"].erase("mpm");
  const fs::path nompm = temp_dir() / "no-mpm.json";
  std::ofstream(nompm) << s.dump();
  const Outcome m = run("calibrate " + nompm.string());
  EXPECT_EQ(m.code, 2);
  EXPECT_NE(m.err.find("methods.mpm"), std::string::npos) << m.err;
}

}  // namespace
