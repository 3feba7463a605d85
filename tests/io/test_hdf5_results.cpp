// HDF5 result files: round trip, validation, atomic replacement; what makes them self-describing
// (units and descriptions everywhere, typed counts and flags, time as a dimension scale, the scene
// as run and the command line); sweep files: compression and the statistics as datasets.
#include "io/hdf5_results.hpp"

#include <hdf5_hl.h>  // dimension scales (H5DS)
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "io/mpm_scene.hpp"
#include "io/provenance.hpp"
#include "io/resolved_scene.hpp"
#include "io/scene_parser.hpp"
#include "io/study_parser.hpp"
#include "io/sweep_file.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time
#include "model/sweep_statistics.hpp"

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

// ---------------------------------------------------------------------------------------------
// Self-describing files.

namespace {

// Every dataset of a file, by its path (H5Ovisit).
std::vector<std::string> dataset_paths(hid_t file) {
  std::vector<std::string> out;
  H5Ovisit(
      file, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
        if (info->type == H5O_TYPE_DATASET)
          static_cast<std::vector<std::string>*>(data)->push_back(std::string("/") + name);
        return 0;
      },
      &out);
  return out;
}

bool has_attr(hid_t obj, const char* name) { return H5Aexists(obj, name) > 0; }

// A dataset's values as doubles (any numeric type, converted), and its rank.
std::vector<double> doubles(hid_t file, const std::string& path, int* rank = nullptr) {
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << path;
  const hid_t space = H5Dget_space(d);
  if (rank) *rank = H5Sget_simple_extent_ndims(space);
  std::vector<double> v(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  if (!v.empty()) {
    EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  }
  H5Sclose(space);
  H5Dclose(d);
  return v;
}

double scalar(hid_t file, const std::string& path) {
  int rank = -1;
  const std::vector<double> v = doubles(file, path, &rank);
  EXPECT_EQ(rank, 0) << path << " is not a 0-d dataset";
  return v.empty() ? std::nan("") : v[0];
}

std::string dataset_string_attribute(hid_t file, const std::string& path, const char* name) {
  const hid_t d = H5Oopen(file, path.c_str(), H5P_DEFAULT);
  const std::string out = has_attr(d, name) ? string_attribute(d, name) : std::string("<none>");
  H5Oclose(d);
  return out;
}

// The class of a dataset's or attribute's type.
H5T_class_t dataset_class(hid_t file, const std::string& path) {
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t t = H5Dget_type(d);
  const H5T_class_t c = H5Tget_class(t);
  H5Tclose(t);
  H5Dclose(d);
  return c;
}

H5T_class_t attribute_class(hid_t obj, const char* name) {
  const hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  const hid_t t = H5Aget_type(a);
  const H5T_class_t c = H5Tget_class(t);
  H5Tclose(t);
  H5Aclose(a);
  return c;
}

// A boolean as h5py writes numpy's bool: an enum of a 1-byte integer with FALSE = 0, TRUE = 1.
// Returns its value's member name ("TRUE" / "FALSE"), or why it is not such a boolean.
std::string boolean_value(hid_t file, const std::string& path) {
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t t = H5Dget_type(d);
  std::string out;
  if (H5Tget_class(t) != H5T_ENUM || H5Tget_size(t) != 1 || H5Tget_nmembers(t) != 2) {
    out = "not a 1-byte enum of two members";
  } else {
    char n0[16] = {}, n1[16] = {};
    signed char v0 = 0, v1 = 1, value = -1;
    H5Tenum_nameof(t, &v0, n0, sizeof n0);
    H5Tenum_nameof(t, &v1, n1, sizeof n1);
    if (std::string(n0) != "FALSE" || std::string(n1) != "TRUE") {
      out = std::string("members ") + n0 + ", " + n1;
    } else {
      H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value);
      out = value == 1 ? "TRUE" : value == 0 ? "FALSE" : "?";
    }
  }
  H5Tclose(t);
  H5Dclose(d);
  return out;
}

// A scene parse_scene accepts, leaving the defaults out (barrier frictions, the material, the
// analytical lambda and tau).
nlohmann::json valid_scene() {
  return nlohmann::json::parse(R"({
    "name": "defaults",
    "landslide": {"thickness_m": 1.0, "velocity_m_s": 5, "density_kg_m3": 1800,
                  "shape": {"kind": "front-body-tail", "body_squares": 3}},
    "barrier": {"height_m": 2.0, "base_width_m": 2.0, "top_width_m": 1.0, "face_angle_deg": 80,
                "density_kg_m3": 2400},
    "methods": {"empirical": {}, "analytical": {}}
  })");
}

MethodResult result_with_series() {
  MethodResult r = full_result();
  r.method = "mpm";
  std::vector<double> residual(r.time.size(), 1e-3);
  r.series["energy_residual"] = {"1", "relative energy residual", residual};
  r.series["kinetic_energy"] = {"J/m", "kinetic energy", r.landslide_kinetic_energy};
  return r;
}

}  // namespace

// Every dataset carries units and a description, every scalar is a 0-d dataset of
// /<method>/scalars with its own units, and the group attributes kept from earlier versions are
// copies of those scalars.
TEST_F(hdf5_results, EveryDatasetAndScalarHasUnitsAndADescription) {
  const auto path = (dir_ / "units.h5").string();
  const std::vector<MethodResult> results = {result_with_series(), sparse_result()};
  lsi::write_results(path, sample_scene(), results);

  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const auto paths = dataset_paths(f);
  ASSERT_FALSE(paths.empty());
  for (const auto& p : paths) {
    const hid_t d = H5Dopen2(f, p.c_str(), H5P_DEFAULT);
    EXPECT_TRUE(has_attr(d, "units")) << p;
    EXPECT_TRUE(has_attr(d, "description")) << p;
    if (has_attr(d, "units")) {
      EXPECT_FALSE(string_attribute(d, "units").empty()) << p;
    }
    if (has_attr(d, "description")) {
      EXPECT_FALSE(string_attribute(d, "description").empty()) << p;
    }
    H5Dclose(d);
  }
  for (const MethodResult& r : results) {
    const std::vector<lsi::DescribedScalar> described = lsi::described_scalars(r);
    ASSERT_FALSE(described.empty());
    for (const auto& s : described) {
      const std::string p = "/" + r.method + "/scalars/" + s.name;
      ASSERT_GT(H5Lexists(f, p.c_str(), H5P_DEFAULT), 0) << p;
      EXPECT_EQ(dataset_string_attribute(f, p, "units"), s.units) << p;
      EXPECT_EQ(scalar(f, p), s.value) << p;  // +inf (a barrier that never stops) as inf
    }
    // No more datasets than scalars in the group, and the deprecated attributes mirror them.
    H5G_info_t info;
    ASSERT_GE(H5Gget_info_by_name(f, ("/" + r.method + "/scalars").c_str(), &info, H5P_DEFAULT), 0);
    EXPECT_EQ(info.nlinks, described.size()) << r.method;
    const hid_t g = H5Gopen2(f, r.method.c_str(), H5P_DEFAULT);
    for (const auto& s : described) {
      ASSERT_TRUE(has_attr(g, s.name.c_str())) << r.method << " attribute " << s.name;
      double legacy = 0;
      const hid_t a = H5Aopen(g, s.name.c_str(), H5P_DEFAULT);
      H5Aread(a, H5T_NATIVE_DOUBLE, &legacy);
      H5Aclose(a);
      EXPECT_EQ(legacy, s.value) << s.name;
    }
    H5Gclose(g);
  }
  // Units by kind: a summary, a further scalar, run statistics, an error bar.
  EXPECT_EQ(dataset_string_attribute(f, "/mpm/scalars/peak_force", "units"), "N/m");
  EXPECT_EQ(dataset_string_attribute(f, "/mpm/scalars/final_displacement", "units"), "m");
  EXPECT_EQ(dataset_string_attribute(f, "/mpm/scalars/reduced_mass", "units"), "kg/m");
  EXPECT_EQ(dataset_string_attribute(f, "/mpm/scalars/froude_number", "units"), "1");
  EXPECT_EQ(dataset_string_attribute(f, "/mpm/scalars/solver_seconds", "units"), "s");
  EXPECT_EQ(dataset_string_attribute(f, "/mpm/scalars/peak_force_spread", "units"), "N/m");
  EXPECT_EQ(dataset_string_attribute(f, "/mpm/energy_residual", "units"), "1");
  H5Fclose(f);
}

// Counts are 64-bit integers, flags booleans (an enum FALSE/TRUE, which h5py reads as bool),
// everything else float64.
TEST_F(hdf5_results, CountsAreIntegersAndFlagsAreBooleans) {
  const auto path = (dir_ / "types.h5").string();
  MethodResult r = result_with_series();
  r.run = lsi::RunStatistics{1024, 5000, 3.5, true, 1.25, 4.1e6, false};
  lsi::write_results(path, sample_scene(), {r});
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  for (const auto& [name, value] : std::map<std::string, double>{
           {"particles", 1024}, {"steps", 5000}, {"convergence_finer_cells", 16}}) {
    const std::string p = "/mpm/scalars/" + name;
    EXPECT_EQ(dataset_class(f, p), H5T_INTEGER) << p;
    const hid_t d = H5Dopen2(f, p.c_str(), H5P_DEFAULT);
    const hid_t t = H5Dget_type(d);
    EXPECT_EQ(H5Tget_size(t), 8u) << p;
    EXPECT_EQ(H5Tget_sign(t), H5T_SGN_2) << p;
    long long v = 0;
    H5Dread(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v);
    EXPECT_EQ(v, value) << p;
    H5Tclose(t);
    H5Dclose(d);
  }
  EXPECT_EQ(boolean_value(f, "/mpm/scalars/finished"), "TRUE");
  EXPECT_EQ(boolean_value(f, "/mpm/scalars/saturated"), "FALSE");
  EXPECT_EQ(boolean_value(f, "/mpm/scalars/peak_force_converged"), "TRUE");
  EXPECT_EQ(boolean_value(f, "/mpm/scalars/final_displacement_converged"), "FALSE");
  for (const char* p : {"/mpm/scalars/peak_force", "/mpm/scalars/end_time", "/mpm/time"})
    EXPECT_EQ(dataset_class(f, p), H5T_FLOAT) << p;
  H5Fclose(f);
  // And they read back as what they were.
  const MethodResult back = lsi::read_results(path).results.at(0);
  ASSERT_TRUE(back.run.has_value());
  EXPECT_EQ(back.run->particles, 1024);
  EXPECT_EQ(back.run->steps, 5000);
  EXPECT_TRUE(back.run->finished);
  EXPECT_FALSE(back.run->saturated);
  EXPECT_TRUE(back.convergence->outputs.at("peak_force").converged);
  EXPECT_FALSE(back.convergence->outputs.at("final_displacement").converged);
}

// `time` is a dimension scale, attached to dimension 0 of every other history of its group (the
// standard ones and the further series) and labelled: h5py's dataset.dims[0][0] is the time.
TEST_F(hdf5_results, TimeIsTheDimensionScaleOfEveryHistory) {
  const auto path = (dir_ / "scales.h5").string();
  lsi::write_results(path, sample_scene(), {result_with_series(), sparse_result()});
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  int histories = 0;
  for (const char* method : {"mpm", "empirical"}) {
    const std::string group = std::string("/") + method;
    const hid_t time = H5Dopen2(f, (group + "/time").c_str(), H5P_DEFAULT);
    ASSERT_GE(time, 0);
    EXPECT_GT(H5DSis_scale(time), 0) << group;
    char name[32] = {};
    H5DSget_scale_name(time, name, sizeof name);
    EXPECT_STREQ(name, "time");
    for (const auto& p : dataset_paths(f)) {
      if (p.rfind(group + "/", 0) != 0 || p == group + "/time" ||
          p.find("/scalars/") != std::string::npos)
        continue;
      const hid_t d = H5Dopen2(f, p.c_str(), H5P_DEFAULT);
      EXPECT_GT(H5DSis_attached(d, time, 0), 0) << p;
      EXPECT_EQ(H5DSget_num_scales(d, 0), 1) << p;
      char label[32] = {};
      H5DSget_label(d, 0, label, sizeof label);
      EXPECT_STREQ(label, "time") << p;
      H5Dclose(d);
      ++histories;
    }
    H5Dclose(time);
  }
  EXPECT_EQ(histories, 6 + 2 + 1);  // mpm: 6 standard and 2 series; empirical: force
  H5Fclose(f);
}

// The root stores the scene as run (every default filled in) and the command line that wrote
// the file, as one shell line and as its words.
TEST_F(hdf5_results, SceneAsRunAndCommandLineAreStored) {
  const auto path = (dir_ / "provenance.h5").string();
  const char* argv[] = {"lsi", "run", "my scene.json", "--out", "it's.h5"};
  lsi::set_command_line(5, argv);
  const lsi::Scene scene = lsi::parse_scene(valid_scene());
  const nlohmann::json resolved = lsi::resolved_scene_json(scene);
  lsi::write_results(path, sample_scene(), {full_result()}, {}, resolved);
  lsi::set_command_line(0, nullptr);

  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(string_attribute(f, "command_line"), "lsi run 'my scene.json' --out 'it'\\''s.h5'");
  EXPECT_EQ(nlohmann::json::parse(string_attribute(f, "scene_resolved")), resolved);
  H5Fclose(f);

  const lsi::StoredResults stored = lsi::read_results(path);
  EXPECT_EQ(stored.argv, std::vector<std::string>(argv, argv + 5));
  EXPECT_EQ(stored.scene_resolved, resolved);
  EXPECT_EQ(stored.git_revision, LSI_GIT_REVISION);
  // The defaults the scene leaves out are there, with the values the methods use.
  EXPECT_EQ(resolved["barrier"]["base_friction"], 0.5);
  EXPECT_EQ(resolved["barrier"]["fixed"], false);
  EXPECT_EQ(resolved["landslide"]["material"]["porosity"], 0.5);
  EXPECT_EQ(resolved["landslide"]["shape"]["kind"], "front-body-tail");
  EXPECT_EQ(resolved["methods"]["empirical"]["a1"], 1.781);
  EXPECT_EQ(resolved["methods"]["analytical"]["lambda"], 0.41);  // the paper's, free barrier
  EXPECT_EQ(resolved["methods"]["analytical"]["tau"], 0.25);

  // Without a recorded command line the attributes are there and empty.
  lsi::write_results(path, sample_scene(), {full_result()});
  EXPECT_TRUE(lsi::read_results(path).argv.empty());
  EXPECT_TRUE(lsi::read_results(path).scene_resolved.is_null());
}

// The scene as run parses back into the same scene, MPM settings included (impact and
// verification blocks, with the settings' variants that change which keys are written).
TEST(resolved_scene, ParsesBackToTheSameScene) {
  for (const char* mpm : {R"({"cell_size_m": 0.1})",
                          R"({"cell_size_m": 0.1, "phases": "dry", "transfer": "flip",
                              "flip_ratio": 0.9, "small_mass_fraction": 0.01})",
                          R"({"cell_size_m": 0.1, "transfer": "pic", "end_time_s": 3,
                              "output_interval_s": 0.02, "face_band_m": 0.25,
                              "snapshot_interval_s": 0.5, "drag": "explicit",
                              "pore_pressure": "cell", "transfer_dissipation": true})"}) {
    nlohmann::json doc = valid_scene();
    doc["methods"]["mpm"] = nlohmann::json::parse(mpm);
    doc["barrier"]["fixed"] = true;
    doc["landslide"]["shape"] = {{"kind", "rectangle"}, {"length_m", 7.5}};
    const lsi::Scene a = lsi::parse_scene(doc);
    const nlohmann::json resolved = lsi::resolved_scene_json(a);
    const lsi::Scene b = lsi::parse_scene(resolved);
    EXPECT_EQ(lsi::resolved_scene_json(b), resolved) << mpm;
    ASSERT_TRUE(b.methods.mpm.has_value());
    EXPECT_TRUE(*b.methods.mpm == *a.methods.mpm) << mpm << "\n" << resolved.dump(1);
    EXPECT_EQ(resolved["methods"]["analytical"]["lambda"], 0.72);  // the fixed barrier's
  }
  const nlohmann::json block = {{"cell_size_m", 0.05}, {"end_time_s", 2.0}, {"wall_band_m", 0.02}};
  const lsi::MpmSettings s = lsi::parse_mpm_settings(block, "methods.mpm", false);
  const nlohmann::json written = lsi::mpm_settings_json(s, false);
  EXPECT_EQ(written["output_interval_s"], 2.0 / 200);  // the default, filled in
  EXPECT_TRUE(lsi::parse_mpm_settings(written, "methods.mpm", false) == s) << written.dump();
}

// Files of earlier versions kept the scalars as attributes of the method group only: they read
// back the same.
TEST_F(hdf5_results, FilesWithoutTheScalarsGroupReadFromTheAttributes) {
  const auto path = (dir_ / "earlier.h5").string();
  const std::vector<MethodResult> results = {result_with_series(), sparse_result()};
  lsi::write_results(path, sample_scene(), results);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  for (const auto& r : results)
    ASSERT_GE(H5Ldelete(f, ("/" + r.method + "/scalars").c_str(), H5P_DEFAULT), 0);
  H5Fclose(f);
  const auto stored = lsi::read_results(path);
  ASSERT_EQ(stored.results.size(), 2u);
  expect_same(stored.results[0], results[0]);
  expect_same(stored.results[1], results[1]);
  EXPECT_EQ(stored.results[0].run->particles, results[0].run->particles);
}

// ---------------------------------------------------------------------------------------------
// Sweep files.

namespace {

// The filters of a dataset's creation properties, with deflate's level.
std::set<H5Z_filter_t> filters_of(hid_t file, const std::string& path, unsigned* deflate_level) {
  std::set<H5Z_filter_t> out;
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t dcpl = H5Dget_create_plist(d);
  for (int k = 0; k < H5Pget_nfilters(dcpl); ++k) {
    unsigned flags = 0, config = 0, cd[8] = {};
    size_t n = 8;
    char name[64];
    const H5Z_filter_t id = H5Pget_filter2(dcpl, k, &flags, &n, cd, sizeof name, name, &config);
    out.insert(id);
    if (id == H5Z_FILTER_DEFLATE && n > 0 && deflate_level) *deflate_level = cd[0];
  }
  H5Pclose(dcpl);
  H5Dclose(d);
  return out;
}

std::vector<std::string> strings(hid_t file, const std::string& path) {
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  std::vector<char*> buf(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  const hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data());
  std::vector<std::string> out;
  for (char* p : buf) {
    out.emplace_back(p ? p : "");
    H5free_memory(p);
  }
  H5Tclose(t);
  H5Sclose(space);
  H5Dclose(d);
  return out;
}

}  // namespace

// A sweep result: every /samples table chunked and compressed (shuffle, deflate 1) and still read
// back exactly; every dataset described; counts and flags typed; the statistics also as datasets
// that hold the numbers of the JSON record, with the quantiles and thresholds as dimension scales.
TEST_F(hdf5_results, SweepFileIsCompressedDescribedAndHoldsItsStatisticsAsDatasets) {
  nlohmann::json study_doc = {{"name", "compressed"},
                              {"scene", valid_scene()},
                              {"inputs",
                               {{{"path", "/landslide/velocity_m_s"},
                                 {"distribution", "uniform"},
                                 {"min", 5},
                                 {"max", 15}}}},
                              {"samples", 5000},
                              {"seed", 1},
                              {"methods", {"empirical", "analytical"}},
                              {"outputs", {"peak_force", "final_displacement"}},
                              {"thresholds", {{{"output", "peak_force"}, {"above", 2.0e5}}}}};
  const lsi::Study study = lsi::parse_study(study_doc, "");
  lsi::SweepTable t =
      lsi::SweepTable::with_columns({"/landslide/velocity_m_s"}, study.output_columns());
  const std::size_t n = 5000;
  for (std::size_t i = 0; i < n; ++i) {
    const bool failed = i == 3;
    t.index.push_back(i);
    t.status.push_back(failed ? 3 : 0);
    t.wall_time.push_back(1e-5f);
    t.inputs[0].push_back(5.0 + 10.0 * (i % 97) / 97.0);
    for (std::size_t c = 0; c < t.output_columns.size(); ++c)
      t.outputs[c].push_back(failed ? std::nan("") : 1.0e5 * (c + 1) + 37.0 * (i % 101));
  }
  t.failure_index = {3};
  t.failure_reason = {"failed: a test's failure"};
  nlohmann::json statistics = lsi::sweep_statistics(study, t);
  statistics["mpm_at_quantiles"] = nlohmann::json::array(
      {{{"quantile", 0.5},
        {"quantile_value", 2.0e5},
        {"column", "analytical/peak_force"},
        {"sample", 42},
        {"inputs", {{"/landslide/velocity_m_s", 9.3}}},
        {"closed_form", {{"analytical/peak_force", 2.1e5}, {"empirical/peak_force", 1.1e5}}},
        {"mpm_status", "finished"},
        {"mpm_end_state", "at_rest"},
        {"mpm", {{"peak_force", 1.9e5}, {"final_displacement", 0.2}}},
        {"relative_error", {{"analytical/peak_force", 0.105}, {"empirical/peak_force", nullptr}}},
        {"mpm_seconds", 12.5}}});
  lsi::SweepHeader h;
  h.study = study.source;
  h.scene_resolved = lsi::resolved_scene_json(study.base);
  h.fingerprint = study.fingerprint;
  h.planned_samples = n;
  h.chunk_samples = 1000;
  h.complete = true;
  const auto path = (dir_ / "sweep.h5").string();
  const auto chunk = (dir_ / "chunk.h5").string();
  lsi::write_sweep_file(path, h, t, &statistics);
  lsi::write_sweep_file(chunk, h, t, nullptr, lsi::SweepStorage::Plain);

  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  // Compression of the sample tables, none in a chunk file.
  std::vector<std::string> tables = {"/samples/index", "/samples/status", "/samples/wall_time",
                                     "/samples/inputs"};
  for (const auto& c : t.output_columns) tables.push_back("/samples/" + c);
  const hid_t plain = H5Fopen(chunk.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  for (const auto& p : tables) {
    unsigned level = 0;
    const auto filters = filters_of(f, p, &level);
    EXPECT_TRUE(filters.count(H5Z_FILTER_SHUFFLE)) << p;
    EXPECT_TRUE(filters.count(H5Z_FILTER_DEFLATE)) << p;
    EXPECT_EQ(level, 1u) << p;
    EXPECT_TRUE(filters_of(plain, p, nullptr).empty()) << p;
    const auto compressed = doubles(f, p), stored_plain = doubles(plain, p);
    ASSERT_EQ(compressed.size(), stored_plain.size()) << p;
    EXPECT_EQ(
        std::memcmp(compressed.data(), stored_plain.data(), compressed.size() * sizeof(double)), 0)
        << p << ": not the same values once inflated";
  }
  H5Fclose(plain);
  // Every dataset described; the inputs' units one per column.
  for (const auto& p : dataset_paths(f)) {
    const hid_t d = H5Dopen2(f, p.c_str(), H5P_DEFAULT);
    EXPECT_TRUE(has_attr(d, "units")) << p;
    EXPECT_TRUE(has_attr(d, "description")) << p;
    const bool text = dataset_class(f, p) == H5T_STRING;
    if (has_attr(d, "units") && !text && p != "/samples/inputs") {
      EXPECT_FALSE(string_attribute(d, "units").empty()) << p;
    }
    H5Dclose(d);
  }
  {
    const hid_t d = H5Dopen2(f, "/samples/inputs", H5P_DEFAULT);
    const hid_t a = H5Aopen(d, "units", H5P_DEFAULT);
    const hid_t space = H5Aget_space(a);
    EXPECT_EQ(H5Sget_simple_extent_npoints(space), 1);
    char* units = nullptr;
    const hid_t st = H5Tcopy(H5T_C_S1);
    H5Tset_size(st, H5T_VARIABLE);
    H5Tset_cset(st, H5T_CSET_UTF8);
    H5Aread(a, st, &units);
    EXPECT_STREQ(units, "m/s");
    H5free_memory(units);
    H5Tclose(st);
    H5Sclose(space);
    H5Aclose(a);
    H5Dclose(d);
  }
  EXPECT_EQ(dataset_string_attribute(f, "/samples/empirical/peak_force", "units"), "N/m");
  EXPECT_EQ(dataset_string_attribute(f, "/samples/analytical/final_displacement", "units"), "m");
  // Typed root attributes, the scene as run.
  EXPECT_EQ(attribute_class(f, "planned_samples"), H5T_INTEGER);
  EXPECT_EQ(attribute_class(f, "samples_done"), H5T_INTEGER);
  EXPECT_EQ(attribute_class(f, "complete"), H5T_ENUM);
  EXPECT_EQ(nlohmann::json::parse(string_attribute(f, "scene_resolved")), h.scene_resolved);
  // The statistics as datasets, the same numbers as the JSON record.
  EXPECT_EQ(scalar(f, "/statistics/samples_ok"), n - 1);
  EXPECT_EQ(scalar(f, "/statistics/confidence"), study.confidence);  // in double precision
  EXPECT_EQ(scalar(f, "/statistics/samples_failed/failed"), 1);
  for (const auto& [column, o] : statistics["outputs"].items()) {
    const std::string g = "/statistics/" + column + "/";
    EXPECT_EQ(scalar(f, g + "count"), o["count"].get<double>()) << column;
    EXPECT_EQ(scalar(f, g + "mean"), o["mean"].get<double>()) << column;
    EXPECT_EQ(scalar(f, g + "standard_deviation"), o["standard_deviation"].get<double>());
    EXPECT_EQ(scalar(f, g + "mean_ci_low"), o["mean_ci"][0].get<double>()) << column;
    EXPECT_EQ(scalar(f, g + "mean_ci_high"), o["mean_ci"][1].get<double>()) << column;
    EXPECT_EQ(doubles(f, g + "quantile_level"), (std::vector<double>{0.05, 0.5, 0.95}));
    EXPECT_EQ(doubles(f, g + "quantile"), (std::vector<double>{o["q05"], o["q50"], o["q95"]}))
        << column;
    EXPECT_EQ(doubles(f, g + "quantile_ci_low"),
              (std::vector<double>{o["q05_ci"][0], o["q50_ci"][0], o["q95_ci"][0]}));
    EXPECT_EQ(doubles(f, g + "quantile_ci_high"),
              (std::vector<double>{o["q05_ci"][1], o["q50_ci"][1], o["q95_ci"][1]}));
    EXPECT_EQ(dataset_string_attribute(f, g + "mean", "units"),
              column.find("peak_force") != std::string::npos ? "N/m" : "m");
    const hid_t level = H5Dopen2(f, (g + "quantile_level").c_str(), H5P_DEFAULT);
    const hid_t q = H5Dopen2(f, (g + "quantile").c_str(), H5P_DEFAULT);
    EXPECT_GT(H5DSis_attached(q, level, 0), 0) << column;
    H5Dclose(q);
    H5Dclose(level);
  }
  int exceedances = 0;
  for (const auto& e : statistics["exceedance"]) {
    const std::string g = "/statistics/" + e["column"].get<std::string>() + "/";
    EXPECT_EQ(doubles(f, g + "exceedance_threshold"), std::vector<double>{2.0e5});
    EXPECT_EQ(doubles(f, g + "exceedance_probability"),
              std::vector<double>{e["probability"].get<double>()});
    EXPECT_EQ(doubles(f, g + "exceedance_probability_ci_low"),
              std::vector<double>{e["ci"][0].get<double>()});
    EXPECT_EQ(doubles(f, g + "exceedance_probability_ci_high"),
              std::vector<double>{e["ci"][1].get<double>()});
    EXPECT_EQ(doubles(f, g + "exceedance_count"),
              std::vector<double>{e["count_above"].get<double>()});
    ++exceedances;
  }
  EXPECT_EQ(exceedances, 2);  // peak_force of both methods
  const std::string q = "/statistics/mpm_at_quantiles/";
  EXPECT_EQ(doubles(f, q + "quantile_level"), std::vector<double>{0.5});
  EXPECT_EQ(doubles(f, q + "sample"), std::vector<double>{42});
  EXPECT_EQ(doubles(f, q + "mpm/peak_force"), std::vector<double>{1.9e5});
  EXPECT_EQ(doubles(f, q + "closed_form/analytical/peak_force"), std::vector<double>{2.1e5});
  EXPECT_EQ(doubles(f, q + "relative_error/analytical/peak_force"), std::vector<double>{0.105});
  EXPECT_TRUE(std::isnan(doubles(f, q + "relative_error/empirical/peak_force").at(0)));
  EXPECT_EQ(strings(f, q + "mpm_status"), std::vector<std::string>{"finished"});
  EXPECT_EQ(dataset_string_attribute(f, q + "mpm/peak_force", "units"), "N/m");
  H5Fclose(f);

  // Both files read back exactly (NaN where a sample failed).
  for (const auto& file : {path, chunk}) {
    const lsi::SweepFile back = lsi::read_sweep_file(file);
    EXPECT_EQ(back.table.index, t.index);
    EXPECT_EQ(back.table.status, t.status);
    EXPECT_EQ(back.table.inputs, t.inputs);
    for (std::size_t c = 0; c < t.outputs.size(); ++c)
      for (std::size_t i = 0; i < n; ++i)
        if (i == 3) {
          EXPECT_TRUE(std::isnan(back.table.outputs[c][i]));
        } else {
          ASSERT_EQ(back.table.outputs[c][i], t.outputs[c][i]) << c << " " << i;
        }
    EXPECT_EQ(back.table.failure_reason, t.failure_reason);
    EXPECT_EQ(back.header.planned_samples, n);
    EXPECT_EQ(back.header.chunk_samples, 1000u);
    EXPECT_TRUE(back.header.complete);
    EXPECT_EQ(back.header.scene_resolved, h.scene_resolved);
  }
  EXPECT_EQ(lsi::read_sweep_file(path).statistics, statistics);
  EXPECT_TRUE(lsi::read_sweep_file(chunk).statistics.is_null());
}

// The units of a sweep's inputs are those their scene keys name, array indices skipped.
TEST_F(hdf5_results, SweepInputsCarryTheUnitsTheirKeysName) {
  const std::vector<std::pair<std::string, std::string>> inputs = {
      {"/landslide/velocity_m_s", "m/s"},
      {"/landslide/density_kg_m3", "kg/m^3"},
      {"/landslide/material/cohesion_kpa", "kPa"},
      {"/landslide/material/liquid_viscosity_kpa_s", "kPa s"},
      {"/landslide/material/young_modulus_mpa", "MPa"},
      {"/barrier/mass_kg_per_m", "kg/m"},
      {"/barrier/face_angle_deg", "deg"},
      {"/barrier/base_friction", "1"},
      {"/landslide/shape/body_squares", "1"},
      {"/methods/mpm/end_time_s", "s"},
      {"/mpm_case/gravity_m_s2", "m/s^2"},
      {"/mpm_case/bodies/0/position_m/1", "m"},
      {"/landslide/material/inertial_friction/grain_diameter_mm", "mm"}};
  std::vector<std::string> paths;
  for (const auto& [p, u] : inputs) paths.push_back(p);
  lsi::SweepTable t = lsi::SweepTable::with_columns(paths, {"empirical/peak_force"});
  t.index = {0, 1};
  t.status = {0, 0};
  t.wall_time = {0.0f, 0.0f};
  for (auto& column : t.inputs) column = {1.0, 2.0};
  t.outputs[0] = {1.0e5, 2.0e5};
  lsi::SweepHeader h;
  h.study = {{"name", "units"}};
  const auto path = (dir_ / "units.h5").string();
  lsi::write_sweep_file(path, h, t);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, "/samples/inputs", H5P_DEFAULT);
  const hid_t a = H5Aopen(d, "units", H5P_DEFAULT);
  const hid_t space = H5Aget_space(a);
  std::vector<char*> units(static_cast<size_t>(H5Sget_simple_extent_npoints(space)), nullptr);
  ASSERT_EQ(units.size(), inputs.size());
  const hid_t st = H5Tcopy(H5T_C_S1);
  H5Tset_size(st, H5T_VARIABLE);
  H5Tset_cset(st, H5T_CSET_UTF8);
  H5Aread(a, st, units.data());
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    EXPECT_EQ(std::string(units[k]), inputs[k].second) << inputs[k].first;
    H5free_memory(units[k]);
  }
  H5Tclose(st);
  H5Sclose(space);
  H5Aclose(a);
  H5Dclose(d);
  H5Fclose(f);
}
