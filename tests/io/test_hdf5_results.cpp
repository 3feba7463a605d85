// HDF5 result files: round trip, validation, atomic replacement.
#include "io/hdf5_results.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

namespace fs = std::filesystem;
using lsi::MethodResult;

namespace {

// A fresh, empty directory per test, removed afterwards.
class Hdf5ResultsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("lsi_test_hdf5_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // Every entry of the test directory whose name contains ".tmp.".
  std::vector<std::string> temporaries() const {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir_))
      if (e.path().filename().string().find(".tmp.") != std::string::npos)
        out.push_back(e.path().string());
    return out;
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  fs::path dir_;
};

nlohmann::json sample_scene() {
  return nlohmann::json::parse(R"({
    "name": "round trip",
    "landslide": {"thickness_m": 2.0, "velocity_m_s": 10.0, "density_kg_m3": 2000.0},
    "barrier": {"height_m": 5.0, "base_width_m": 4.0, "top_width_m": 2.0, "density_kg_m3": 2400.0},
    "methods": {"analytical": {}, "empirical": {"tau": 0.14}}
  })");
}

MethodResult full_result() {
  MethodResult r;
  r.method = "analytical";
  for (int i = 0; i < 11; ++i) {
    const double t = 0.1 * i;
    r.time.push_back(t);
    r.force.push_back(1.5e5 * std::max(0.0, 1.0 - std::abs(t - 0.3) / 0.3));
    r.force_horizontal.push_back(r.force.back() * 0.9);
    r.force_vertical.push_back(r.force.back() * 0.1);
    r.landslide_kinetic_energy.push_back(4.0e5 * std::exp(-5.0 * t));
    r.barrier_velocity.push_back(0.2 * std::exp(-t));
    r.barrier_displacement.push_back(0.05 * t);
  }
  r.peak_force = 1.5e5;
  r.rise_time = 0.3;
  r.impact_duration = 0.6;
  r.final_displacement = std::numeric_limits<double>::infinity();
  r.scalars.froude_number = 2.26;
  r.scalars.reduced_mass = 1234.5;
  r.scalars.barrier_stop_time = std::numeric_limits<double>::infinity();
  r.run = lsi::RunStatistics{1024, 5000, 3.5, true, 1.25, 4.1e6, true};
  r.convergence = lsi::ConvergenceBars{
      16, 0.25, {{"peak_force", {1234.0, true}}, {"final_displacement", {0.5, false}}}};
  return r;
}

MethodResult sparse_result() {
  MethodResult r;
  r.method = "empirical";
  r.time = {0.0, 0.5, 1.0};
  r.force = {0.0, 9.0e4, 0.0};  // the other histories are empty: not written
  r.peak_force = 9.0e4;
  r.rise_time = 0.5;
  r.impact_duration = 1.0;
  r.final_displacement = 0.0;
  r.scalars.alpha = 1.781;
  return r;
}

void expect_same(const MethodResult& a, const MethodResult& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.force, b.force);
  EXPECT_EQ(a.force_horizontal, b.force_horizontal);
  EXPECT_EQ(a.force_vertical, b.force_vertical);
  EXPECT_EQ(a.landslide_kinetic_energy, b.landslide_kinetic_energy);
  EXPECT_EQ(a.barrier_velocity, b.barrier_velocity);
  EXPECT_EQ(a.barrier_displacement, b.barrier_displacement);
  EXPECT_EQ(a.peak_force, b.peak_force);
  EXPECT_EQ(a.rise_time, b.rise_time);
  EXPECT_EQ(a.impact_duration, b.impact_duration);
  EXPECT_EQ(a.final_displacement, b.final_displacement);
  EXPECT_EQ(lsi::named_scalars(a), lsi::named_scalars(b));
  EXPECT_EQ(a.run.has_value(), b.run.has_value());
  EXPECT_EQ(a.convergence.has_value(), b.convergence.has_value());
}

// Reads a string attribute with the plain C API (independent of read_results).
std::string string_attribute(hid_t obj, const char* name) {
  const hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
  EXPECT_GE(attr, 0) << name;
  const hid_t type = H5Aget_type(attr);
  char* buf = nullptr;
  std::string out;
  if (H5Tis_variable_str(type) > 0 && H5Aread(attr, type, &buf) >= 0 && buf != nullptr) {
    out = buf;
    H5free_memory(buf);
  }
  H5Tclose(type);
  H5Aclose(attr);
  return out;
}

}  // namespace

// Lower-case suite name so that `ctest -R hdf5` selects these tests.
using hdf5_results = Hdf5ResultsTest;

TEST_F(hdf5_results, RoundTripTwoMethods) {
  const auto path = (dir_ / "nested" / "deeper" / "result.h5").string();  // parents are created
  const auto scene = sample_scene();
  const std::vector<MethodResult> results = {full_result(), sparse_result()};
  lsi::write_results(path, scene, results);
  ASSERT_TRUE(fs::is_regular_file(path));

  const auto stored = lsi::read_results(path);
  EXPECT_EQ(stored.scene, scene);
  EXPECT_EQ(stored.lsi_version, LSI_VERSION);
  ASSERT_EQ(stored.results.size(), 2u);
  expect_same(stored.results[0], results[0]);  // written order is preserved
  expect_same(stored.results[1], results[1]);
  EXPECT_TRUE(std::isinf(stored.results[0].final_displacement));
  EXPECT_GT(stored.results[0].final_displacement, 0.0);
  EXPECT_TRUE(stored.results[1].barrier_displacement.empty());
}

// Every named scalar (model/result_scalars.hpp) goes to the file and comes back in its own field:
// the table's names are distinct, none is a reserved attribute, and reading sets what writing
// stored (distinct values catch two names bound to one member).
TEST_F(hdf5_results, EveryNamedScalarRoundTrips) {
  const auto path = (dir_ / "scalars.h5").string();
  MethodResult r = sparse_result();
  double v = 1.0;
  for (const lsi::ScalarField& f : lsi::scalar_fields()) r.scalars.*(f.member) = v++;
  r.run = lsi::RunStatistics{7, 11, 2.5, false, 0.75, 3.0e6, true};
  r.convergence = lsi::ConvergenceBars{16, 0.25, {{"impulse", {2.0, true}}}};
  std::set<std::string> names;
  for (const auto& [name, value] : lsi::named_scalars(r)) {
    EXPECT_TRUE(names.insert(name).second) << name << " named twice";
    for (const char* reserved : {"peak_force", "rise_time", "impact_duration", "final_displacement",
                                 "units", "end_state", "status"})
      EXPECT_NE(name, reserved);
  }
  lsi::write_results(path, sample_scene(), {r});
  const MethodResult back = lsi::read_results(path).results.at(0);
  EXPECT_EQ(lsi::named_scalars(back), lsi::named_scalars(r));
  ASSERT_TRUE(back.run.has_value());
  EXPECT_EQ(back.run->particles, 7);
  EXPECT_EQ(back.run->steps, 11);
  EXPECT_FALSE(back.run->finished);
  EXPECT_TRUE(back.run->saturated);
  ASSERT_TRUE(back.convergence.has_value());
  EXPECT_EQ(back.convergence->finer_cells, 16);
  EXPECT_TRUE(back.convergence->outputs.at("impulse").converged);
  EXPECT_EQ(lsi::scalar_by_name(back, "impulse"), r.scalars.impulse.value());
  EXPECT_TRUE(std::isnan(lsi::scalar_by_name(sparse_result(), "impulse")));  // not given
}

TEST_F(hdf5_results, LayoutAndMetadata) {
  const auto path = (dir_ / "layout.h5").string();
  lsi::write_results(path, sample_scene(), {full_result(), sparse_result()});

  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(string_attribute(f, "scene"), sample_scene().dump(2));
  EXPECT_EQ(string_attribute(f, "lsi_version"), LSI_VERSION);
  EXPECT_EQ(string_attribute(f, "git_revision"), LSI_GIT_REVISION);

  const hid_t g = H5Gopen2(f, "analytical", H5P_DEFAULT);
  ASSERT_GE(g, 0);
  EXPECT_EQ(string_attribute(g, "units"),
            "peak_force N/m; rise_time s; impact_duration s; final_displacement m");
  const std::pair<const char*, const char*> expected_units[] = {{"time", "s"},
                                                                {"force", "N/m"},
                                                                {"force_horizontal", "N/m"},
                                                                {"force_vertical", "N/m"},
                                                                {"landslide_kinetic_energy", "J/m"},
                                                                {"barrier_velocity", "m/s"},
                                                                {"barrier_displacement", "m"}};
  for (const auto& [name, units] : expected_units) {
    const hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
    ASSERT_GE(d, 0) << name;
    EXPECT_EQ(string_attribute(d, "units"), units) << name;
    EXPECT_FALSE(string_attribute(d, "description").empty()) << name;
    H5Dclose(d);
  }
  H5Gclose(g);

  const hid_t e = H5Gopen2(f, "empirical", H5P_DEFAULT);
  ASSERT_GE(e, 0);
  EXPECT_GT(H5Lexists(e, "force", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Lexists(e, "barrier_velocity", H5P_DEFAULT), 0);  // empty: not written
  EXPECT_EQ(H5Lexists(e, "landslide_kinetic_energy", H5P_DEFAULT), 0);
  H5Gclose(e);
  H5Fclose(f);
}

TEST_F(hdf5_results, LengthMismatchIsRejectedNamingTheDataset) {
  const auto path = (dir_ / "bad.h5").string();
  auto r = full_result();
  r.barrier_velocity.pop_back();
  try {
    lsi::write_results(path, sample_scene(), {sparse_result(), r});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("barrier_velocity"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(temporaries().empty());

  // A history without a time axis is a mismatch too.
  MethodResult no_time;
  no_time.method = "mpm";
  no_time.force = {1.0, 2.0};
  try {
    lsi::write_results(path, sample_scene(), {no_time});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("force"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(hdf5_results, InvalidNamesAreRejected) {
  const auto path = (dir_ / "bad.h5").string();
  const std::vector<MethodResult> dup = {full_result(), full_result()};
  EXPECT_THROW(lsi::write_results(path, sample_scene(), dup), std::invalid_argument);
  auto slash = full_result();
  slash.method = "a/b";
  EXPECT_THROW(lsi::write_results(path, sample_scene(), {slash}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(hdf5_results, NoTemporaryFileAfterSuccessAndOverwriteReplaces) {
  const auto path = (dir_ / "result.h5").string();
  lsi::write_results(path, sample_scene(), {full_result()});
  EXPECT_TRUE(temporaries().empty());

  lsi::write_results(path, sample_scene(), {sparse_result()});  // replaces the old file
  EXPECT_TRUE(temporaries().empty());
  const auto stored = lsi::read_results(path);
  ASSERT_EQ(stored.results.size(), 1u);
  EXPECT_EQ(stored.results[0].method, "empirical");
}

TEST_F(hdf5_results, FailedWriteLeavesNoTemporaryAndKeepsOtherFiles) {
  // A good file that must survive untouched.
  const auto good = (dir_ / "good.h5").string();
  lsi::write_results(good, sample_scene(), {full_result()});
  const std::string good_bytes = slurp(good);

  // The target is an existing, non-empty directory: everything up to the rename succeeds, the
  // rename fails (this works as root too, unlike permission bits).
  const auto target = dir_ / "occupied.h5";
  fs::create_directories(target);
  { std::ofstream(target / "keep.txt") << "x"; }
  try {
    lsi::write_results(target.string(), sample_scene(), {sparse_result()});
    FAIL() << "expected std::runtime_error";
  } catch (const std::invalid_argument&) {
    FAIL() << "expected std::runtime_error, got std::invalid_argument";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(temporaries().empty());
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_TRUE(fs::exists(target / "keep.txt"));
  EXPECT_EQ(slurp(good), good_bytes);
  EXPECT_EQ(lsi::read_results(good).results.size(), 1u);
}

TEST_F(hdf5_results, FailedWriteOverAnExistingFileKeepsIt) {
  // The temporary file cannot be created (its name is taken by a directory), so the write fails
  // before the rename: the existing good file at the target stays as it was.
  const auto path = (dir_ / "result.h5").string();
  lsi::write_results(path, sample_scene(), {full_result()});
  const std::string before = slurp(path);
  const auto blocker = fs::path(path + ".tmp." + std::to_string(::getpid()));
  fs::create_directories(blocker);
  EXPECT_THROW(lsi::write_results(path, sample_scene(), {sparse_result()}), std::runtime_error);
  EXPECT_EQ(slurp(path), before);
  EXPECT_TRUE(fs::is_directory(blocker));  // not ours to delete
  fs::remove(blocker);
  EXPECT_EQ(lsi::read_results(path).results.at(0).method, "analytical");
}

TEST_F(hdf5_results, ReadingAMissingFileThrowsNamingIt) {
  const auto path = (dir_ / "missing.h5").string();
  try {
    lsi::read_results(path);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}
