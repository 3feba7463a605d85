// Studies of design "points" (io/study_parser.cpp, io/points_file.cpp, io/study_points.cpp): the
// points file read as CSV or HDF5, its columns as the inputs, every value checked as a scene
// value, and every malformed file refused with one line naming the file, the row, the column,
// the value and what is allowed.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/study_parser.hpp"
#include "model/input_error.hpp"
#include "support/temp_files.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;
const fs::path source_dir = LSI_SOURCE_DIR;

fs::path temp_dir() { return lsi::testing::process_temp_dir("lsi_study_points"); }
fs::path write_text(const std::string& name, const std::string& text) {
  return lsi::testing::write_text(temp_dir() / name, text);
}

// A study of the former reference case L1-B1 (a free barrier) over the points of `points_file`
// (relative to the study's folder), with `extra` keys merged in.
fs::path write_study(const std::string& points_file, json extra = {}) {
  json s = {{"name", "points"},
            {"scene", (source_dir / "scenes/former-reference/L1-B1.json").string()},
            {"design", "points"},
            {"points", {{"file", points_file}}},
            {"methods", {"empirical", "analytical"}}};
  if (!extra.is_null()) s.merge_patch(extra);
  const fs::path p = temp_dir() / "study.json";
  std::ofstream(p) << s.dump(2);
  return p;
}

// The message of the InputError that loading `study` throws ("" if it loads).
std::string load_error(const fs::path& study) {
  try {
    lsi::load_study(study.string());
  } catch (const lsi::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(StudyPoints, ColumnsBecomeTheInputsAndRowsTheSamplesInFileOrder) {
  write_text("good.csv",
             "/landslide/velocity_m_s, /barrier/base_friction\n"
             "6.5,0.4\n"
             "+4,5e-1\r\n"
             "7.25,0.3\n"
             "\n");
  const lsi::Study s = lsi::load_study(write_study("good.csv").string());
  EXPECT_EQ(s.design, lsi::sweeps::Design::Points);
  ASSERT_EQ(s.inputs.size(), 2u);
  EXPECT_EQ(s.inputs[0].path, "/landslide/velocity_m_s");
  EXPECT_EQ(s.inputs[1].path, "/barrier/base_friction");
  EXPECT_EQ(s.samples, 3u);
  // Read as written (std::from_chars: the correctly rounded double of each text).
  EXPECT_EQ(s.points.value, (std::vector<double>{6.5, 0.4, 4.0, 0.5, 7.25, 0.3}));
  // The file is resolved against the study's folder and stored by its absolute path.
  EXPECT_EQ(fs::path(s.points.file), fs::absolute(temp_dir() / "good.csv").lexically_normal());
  EXPECT_EQ(s.source["points"]["file"], s.points.file);
  // The sampler hands back row i as sample i.
  const auto sampler = s.sampler<Kokkos::HostSpace>();
  double x[2];
  sampler.sample(1, x);
  EXPECT_EQ(x[0], 4.0);
  EXPECT_EQ(x[1], 0.5);

  // Listed inputs fix the columns' order in the study, whatever the file's.
  const lsi::Study listed = lsi::load_study(
      write_study("good.csv",
                  {{"inputs",
                    {{{"path", "/barrier/base_friction"}}, {{"path", "/landslide/velocity_m_s"}}}}})
          .string());
  EXPECT_EQ(listed.inputs[0].path, "/barrier/base_friction");
  EXPECT_EQ(listed.points.value, (std::vector<double>{0.4, 6.5, 0.5, 4.0, 0.3, 7.25}));

  // Another value is another study (resume and merge refuse each other's files).
  write_text("other.csv",
             "/landslide/velocity_m_s,/barrier/base_friction\n6.5,0.4\n4,0.5\n7.25,0.31\n");
  EXPECT_NE(lsi::load_study(write_study("other.csv").string()).fingerprint, s.fingerprint);
}

TEST(StudyPoints, MalformedFilesAndBadValuesAreRefusedInOneLine) {
  const std::string v = "/landslide/velocity_m_s", mu = "/barrier/base_friction";
  struct Case {
    std::string name, text;
    json extra;
    std::string expected;
  };
  const Case cases[] = {
      {"empty.csv", "", {}, "empty.csv: empty"},
      {"blank.csv", "\n\n", {}, "blank.csv: empty"},
      {"header.csv", v + "\n", {}, "header.csv: no points after the header"},
      {"unknown.csv",
       v + ",/landslide/speed\n6,1\n",
       {},
       "unknown.csv: column \"/landslide/speed\": not a numeric scene key a study can sample"},
      {"twice.csv", v + "," + v + "\n6,6\n", {}, "column 2 \"" + v + "\": named twice"},
      {"noname.csv", v + ",\n6,1\n", {}, "noname.csv: line 1: column 2 has no name"},
      {"ragged.csv",
       v + "," + mu + "\n6,0.4\n7\n",
       {},
       "ragged.csv: row 2 (line 3) has 1 values, the header names 2 columns"},
      {"long.csv",
       v + "," + mu + "\n6,0.4,1\n",
       {},
       "long.csv: row 1 (line 2) has 3 values, the header names 2 columns"},
      {"hole.csv", v + "," + mu + "\n6,0.4\n\n7,0.5\n", {}, "hole.csv: row 2 (line 3) is empty"},
      {"nan.csv",
       v + "," + mu + "\n6,0.4\n7,nan\n",
       {},
       "nan.csv: row 2 (line 3), column " + mu + " = nan: must be a finite number"},
      {"inf.csv", v + "\n-inf\n", {}, "column " + v + " = -inf: must be a finite number"},
      {"overflow.csv", v + "\n1e999\n", {}, "column " + v + " = 1e999: must be finite"},
      {"text.csv",
       v + "," + mu + "\n6,0.4x\n",
       {},
       "text.csv: row 1 (line 2), column " + mu + " = \"0.4x\": not a number"},
      {"novalue.csv", v + "," + mu + "\n6,\n", {}, "row 1 (line 2), column " + mu + ": no value"},
      // The scene's own range of each key, as the scene parser has it.
      {"range.csv",
       v + "," + mu + "\n6,0.4\n5,0.5\n-1,0.5\n",
       {},
       "range.csv: row 3 (line 4), column " + v + " = -1: must be > 0"},
      {"integer.csv",
       "/landslide/shape/body_squares\n4\n4.5\n",
       {},
       "integer.csv: row 2 (line 3), column /landslide/shape/body_squares = 4.5: must be an "
       "integer in [0, 1000000]"},
      // A value only the checks across keys refuse: the scene parser's message.
      {"across.csv",
       "/barrier/top_width_m\n1\n2.5\n",
       {},
       "across.csv: row 2 (line 3): the scene with this row is invalid: barrier.top_width_m = "
       "2.5: must be in [0, base_width_m = 2]"},
      // A key the base scene cannot take (it gives the barrier's density, not its mass).
      {"mass.csv",
       "/barrier/mass_kg_per_m\n20000\n",
       {},
       "mass.csv: row 1 (line 2): the scene with this row is invalid"},
      {"reader.csv",
       "/methods/empirical/tau\n0.5\n",
       {{"methods", {"analytical"}}},
       "column \"/methods/empirical/tau\": only the empirical method reads it"},
      // Listed inputs and the file's columns must be the same set.
      {"missing.csv",
       v + "\n6\n",
       {{"inputs", {{{"path", v}}, {{"path", mu}}}}},
       "missing.csv: no column " + mu + " for inputs[1]"},
      {"extra.csv",
       v + "," + mu + "\n6,0.4\n",
       {{"inputs", {{{"path", v}}}}},
       "extra.csv: column \"" + mu + "\": not one of the study's inputs"},
      {"dist.csv",
       v + "\n6\n",
       {{"inputs", {{{"path", v}, {"distribution", "uniform"}, {"min", 1}, {"max", 2}}}}},
       "inputs[0].distribution: not used by the points design"},
      // The drawn designs' keys.
      {"seed.csv", v + "\n6\n", {{"seed", 3}}, "seed = 3: not used by the points design"},
      {"corr.csv",
       v + "\n6\n",
       {{"correlation", json::array()}},
       "correlation = []: not used by the points design"},
      {"samples.csv", v + "\n6\n7\n", {{"samples", 3}}, "samples = 3: the points file has 2 rows"},
  };
  for (const Case& c : cases) {
    write_text(c.name, c.text);
    const std::string e = load_error(write_study(c.name, c.extra));
    EXPECT_NE(e.find(c.expected), std::string::npos)
        << c.name << ": expected '" << c.expected << "' in:\n"
        << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
  }
  // The file itself.
  EXPECT_NE(load_error(write_study("no-such.csv")).find("no-such.csv: points file not found"),
            std::string::npos);
  EXPECT_NE(load_error(write_study("/dev/zero")).find("/dev/zero: not a regular file"),
            std::string::npos);
  const std::string no_points = load_error(write_study("x.csv", {{"points", nullptr}}));
  EXPECT_NE(no_points.find("points: missing"), std::string::npos) << no_points;
  // `points` belongs to the points design only.
  json drawn = {{"design", "monte-carlo"},
                {"samples", 10},
                {"inputs",
                 {{{"path", "/landslide/velocity_m_s"},
                   {"distribution", "uniform"},
                   {"min", 4},
                   {"max", 8}}}}};
  const std::string stray = load_error(write_study("x.csv", drawn));
  EXPECT_NE(stray.find("points = {\"file\":\"x.csv\"}: used only by design \"points\""),
            std::string::npos)
      << stray;
}

// An HDF5 points file: a 2-D dataset (float64 here; any numbers are read as doubles) with its
// columns named by a string attribute.
void write_hdf5_points(const fs::path& file, const std::string& dataset, const std::string& columns,
                       const std::vector<double>& values, hsize_t rows, hsize_t cols) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {rows, cols};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t ds =
      H5Dcreate2(f, dataset.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  if (!columns.empty()) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t scalar = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(ds, "columns", type, scalar, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = columns.c_str();
    H5Awrite(attr, type, &text);
    H5Aclose(attr);
    H5Sclose(scalar);
    H5Tclose(type);
  }
  H5Dclose(ds);
  H5Sclose(space);
  H5Fclose(f);
}

TEST(StudyPoints, Hdf5DatasetWithItsColumnsAttribute) {
  const std::string columns = "/landslide/velocity_m_s,/barrier/base_friction";
  write_hdf5_points(temp_dir() / "good.h5", "points", columns, {6.5, 0.4, 4.0, 0.5, 7.25, 0.3}, 3,
                    2);
  const lsi::Study s = lsi::load_study(write_study("good.h5").string());
  EXPECT_EQ(s.samples, 3u);
  EXPECT_EQ(s.inputs[1].path, "/barrier/base_friction");
  EXPECT_EQ(s.points.value, (std::vector<double>{6.5, 0.4, 4.0, 0.5, 7.25, 0.3}));
  // Another dataset, named by points.dataset.
  write_hdf5_points(temp_dir() / "named.h5", "x", columns, {6.5, 0.4}, 1, 2);
  EXPECT_EQ(
      lsi::load_study(write_study("named.h5", {{"points", {{"dataset", "x"}}}}).string()).samples,
      1u);

  write_hdf5_points(temp_dir() / "nan.h5", "points", columns, {6.5, 0.4, 4.0, NAN}, 2, 2);
  write_hdf5_points(temp_dir() / "bare.h5", "points", "", {6.5, 0.4}, 1, 2);
  write_hdf5_points(temp_dir() / "wide.h5", "points", "/landslide/velocity_m_s", {6.5, 0.4}, 1, 2);
  write_hdf5_points(temp_dir() / "range.h5", "points", columns, {6.5, 0.4, 4.0, -0.5}, 2, 2);
  const std::pair<std::string, std::string> cases[] = {
      {"nan.h5", "nan.h5: row 2, column /barrier/base_friction = nan: must be a finite number"},
      {"bare.h5", "bare.h5: dataset \"points\": no attribute \"columns\""},
      {"wide.h5", "wide.h5: dataset \"points\": 2 columns, its attribute \"columns\" names 1"},
      {"range.h5", "range.h5: row 2, column /barrier/base_friction = -0.5: must be >= 0"},
      {"named.h5", "named.h5: dataset \"points\": not in the file"},
  };
  for (const auto& [name, expected] : cases) {
    const std::string e = load_error(write_study(name));
    EXPECT_NE(e.find(expected), std::string::npos) << "expected '" << expected << "' in:\n" << e;
  }
  write_text("plain.csv", "/landslide/velocity_m_s\n6\n");
  EXPECT_NE(load_error(write_study("plain.csv", {{"points", {{"dataset", "x"}}}}))
                .find("plain.csv: points.dataset = \"x\": a CSV file has no datasets"),
            std::string::npos);
}

}  // namespace
