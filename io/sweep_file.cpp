// Sweep tables in HDF5; layout in sweep_file.hpp.
#include "io/sweep_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "io/compressed_chunks.hpp"
#include "io/hdf5_io.hpp"
#include "io/sweep_file_layout.hpp"
#include "io/provenance.hpp"
#include "model/result_scalars.hpp"

namespace lsi {
namespace {

using namespace hdf5;
using nlohmann::json;
constexpr const char* kKind = "lsi sweep";

// The units of an output column "<method>/<output>".
std::string units_of(const std::string& column) {
  const std::string u = scalar_units(column.substr(column.find('/') + 1));
  return u.empty() ? "1" : u;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The units of a scene input by its JSON pointer: the unit its key names (velocity_m_s: m/s),
// "1" for a key without one (frictions, ratios, counts).
std::string input_units(const std::string& path) {
  // The last key of the pointer that is not an array index.
  std::string key;
  std::size_t end = path.size();
  while (end > 0) {
    const std::size_t slash = path.rfind('/', end - 1);
    const std::size_t from = slash == std::string::npos ? 0 : slash + 1;
    key = path.substr(from, end - from);
    if (!key.empty() && key.find_first_not_of("0123456789") != std::string::npos) break;
    if (slash == std::string::npos) break;
    end = slash;
  }
  static const std::pair<const char*, const char*> kSuffixes[] = {
      {"_kg_per_m", "kg/m"}, {"_kg_m3", "kg/m^3"}, {"_m_s2", "m/s^2"}, {"_m_s", "m/s"},
      {"_kpa_s", "kPa s"},   {"_kpa", "kPa"},      {"_mpa", "MPa"},    {"_deg", "deg"},
      {"_mm", "mm"},         {"_m", "m"},          {"_s", "s"}};
  for (const auto& [suffix, units] : kSuffixes)
    if (ends_with(key, suffix)) return units;
  return "1";
}

Handle intermediate_groups() {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "cannot create a link-creation property list");
  check(H5Pset_create_intermediate_group(lcpl, 1), "cannot set intermediate group creation");
  return lcpl;
}

// Writes a dataset of `columns` (each of the same length n): 1-D of n values (rank 1, one
// column) or 2-D of n rows; returns it open, to be described.
template <class T>
Handle write_columns(hid_t file, const std::string& name, hid_t file_type, hid_t mem_type,
                     const std::vector<const std::vector<T>*>& columns, SweepStorage storage,
                     int rank) {
  const std::size_t n = columns.empty() ? 0 : columns.front()->size();
  const hsize_t dims[2] = {static_cast<hsize_t>(n), static_cast<hsize_t>(columns.size())};
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose,
               "cannot create dataspace for '" + name + "'");
  Handle lcpl = intermediate_groups();
  Handle dcpl = storage == SweepStorage::Compressed
                    ? compressed_table_properties(rank, dims, H5Tget_size(file_type))
                    : Handle(H5Pcreate(H5P_DATASET_CREATE), H5Pclose,
                             "cannot create a dataset-creation property list");
  Handle dset(H5Dcreate2(file, name.c_str(), file_type, space, lcpl, dcpl, H5P_DEFAULT), H5Dclose,
              "cannot create dataset '" + name + "'");
  if (n == 0) return dset;
  // Compressed tables: their chunks (a column's rows each) compressed on several threads.
  const bool same_layout = H5Tequal(file_type, mem_type) > 0;
  if (storage == SweepStorage::Compressed && same_layout) {
    std::vector<const void*> data;
    for (const auto* c : columns) data.push_back(c->data());
    if (write_compressed_chunks(dset, dcpl, data, n, H5Tget_size(file_type))) return dset;
  }
  std::vector<T> rows;  // row-major, as H5Dwrite takes a 2-D dataset
  if (rank == 2) {
    const std::size_t d = columns.size();
    rows.resize(n * d);
    for (std::size_t k = 0; k < d; ++k)
      for (std::size_t i = 0; i < n; ++i) rows[i * d + k] = (*columns[k])[i];
  }
  check(H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                 rank == 2 ? rows.data() : columns.front()->data()),
        "cannot write dataset '" + name + "'");
  return dset;
}

// A 1-D dataset; returns it open, to be described.
template <class T>
Handle write_array(hid_t file, const std::string& name, hid_t file_type, hid_t mem_type,
                   const std::vector<T>& data, SweepStorage storage) {
  return write_columns<T>(file, name, file_type, mem_type, {&data}, storage, 1);
}

// A 1-D dataset with its units and description.
template <class T>
void write_column(hid_t file, const std::string& name, hid_t file_type, hid_t mem_type,
                  const std::vector<T>& data, const std::string& units,
                  const std::string& description, SweepStorage storage) {
  describe(write_array(file, name, file_type, mem_type, data, storage), units, description);
}

template <class T>
std::vector<T> read_array(hid_t file, const std::string& name, hid_t mem_type,
                          hsize_t* columns = nullptr) {
  Handle dset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose,
              "cannot open dataset '" + name + "'");
  Handle space(H5Dget_space(dset), H5Sclose, "cannot get the dataspace of '" + name + "'");
  hsize_t dims[2] = {0, 1};
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 1 || rank > 2)
    throw std::runtime_error("dataset '" + name + "' has rank " + std::to_string(rank));
  H5Sget_simple_extent_dims(space, dims, nullptr);
  if (columns) *columns = rank == 2 ? dims[1] : 1;
  std::vector<T> data(static_cast<std::size_t>(dims[0] * (rank == 2 ? dims[1] : 1)));
  if (!data.empty())
    check(H5Dread(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          "cannot read dataset '" + name + "'");
  return data;
}

void write_strings(hid_t file, const std::string& name, const std::vector<std::string>& s,
                   const std::string& description) {
  std::vector<const char*> ptr;
  for (const auto& x : s) ptr.push_back(x.c_str());
  Handle type = vlen_string_type();
  write_column(file, name, type, type, ptr, "", description, SweepStorage::Plain);
}

std::vector<std::string> read_strings(hid_t file, const std::string& name) {
  Handle type = vlen_string_type();
  std::vector<char*> ptr = read_array<char*>(file, name, type);
  std::vector<std::string> out;
  for (char* p : ptr) {
    out.emplace_back(p ? p : "");
    H5free_memory(p);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// The statistics as datasets: what the `json` attribute of /statistics holds (sweep_statistics),
// each number with its units.

double number_of(const json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s == "inf") return INFINITY;
    if (s == "-inf") return -INFINITY;
  }
  return NAN;  // "nan" or null (no value)
}

Handle create_group(hid_t parent, const std::string& name) {
  Handle lcpl = intermediate_groups();
  return Handle(H5Gcreate2(parent, name.c_str(), lcpl, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                "cannot create group '" + name + "'");
}

Handle open_dataset(hid_t group, const std::string& name) {
  return Handle(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose,
                "cannot open dataset '" + name + "'");
}

void write_int64_array(hid_t group, const std::string& name, const std::vector<std::int64_t>& v,
                       const std::string& description) {
  write_column(group, name, H5T_STD_I64LE, H5T_NATIVE_INT64, v, "1", description,
               SweepStorage::Plain);
}

// Makes `scale` the dimension scale of the first dimension of `datasets`.
void attach_scale(hid_t group, const std::string& scale, const std::vector<std::string>& datasets) {
  Handle s = open_dataset(group, scale);
  make_dimension_scale(s, scale);
  for (const auto& d : datasets) attach_dimension_scale(open_dataset(group, d), s, 0);
}

// One output column's statistics: /statistics/<method>/<output>.
void write_output_statistics(hid_t statistics, const std::string& column, const json& o,
                             const json& exceedance) {
  Handle g = create_group(statistics, column);
  const std::string units = units_of(column);
  if (o.contains("error")) write_string_attribute(g, "error", o["error"].get<std::string>());
  if (o.contains("count"))
    write_scalar_int64(g, "count", o["count"].get<std::int64_t>(), "1",
                       "ok samples (those the statistics describe)");
  if (!o.contains("mean")) return;  // no ok samples, or an error
  write_scalar_int64(g, "infinite_count", o.value("infinite_count", std::int64_t{0}), "1",
                     "ok samples whose value is infinite (a barrier that never stops)");
  write_scalar_double(g, "mean", number_of(o["mean"]), units, "mean over the ok samples");
  write_scalar_double(g, "mean_ci_low", number_of(o["mean_ci"][0]), units,
                      "lower end of the confidence interval of the mean");
  write_scalar_double(g, "mean_ci_high", number_of(o["mean_ci"][1]), units,
                      "upper end of the confidence interval of the mean");
  write_scalar_double(g, "standard_deviation", number_of(o["standard_deviation"]), units,
                      "sample standard deviation");
  write_scalar_double(g, "min", number_of(o["min"]), units, "smallest value");
  write_scalar_double(g, "max", number_of(o["max"]), units, "largest value");
  // The quantiles the JSON names qNN (q05, q50, q95), in increasing order.
  std::vector<double> levels, values, low, high;
  for (const auto& [key, v] : o.items()) {
    if (key.size() != 3 || key[0] != 'q' || key.find_first_not_of("0123456789", 1) != key.npos)
      continue;
    levels.push_back(std::stoi(key.substr(1)) / 100.0);
    values.push_back(number_of(v));
    const json ci = o.value(key + "_ci", json::array({nullptr, nullptr}));
    low.push_back(number_of(ci[0]));
    high.push_back(number_of(ci[1]));
  }
  if (!levels.empty()) {
    const hsize_t k = levels.size();
    write_double_array(g, "quantile_level", levels, {k}, "1",
                       "probability p of each quantile (dimension scale of quantile)");
    write_double_array(g, "quantile", values, {k}, units,
                       "p-quantile of the ok samples (type 7: linear interpolation)");
    write_double_array(g, "quantile_ci_low", low, {k}, units,
                       "lower end of the distribution-free confidence interval of each quantile");
    write_double_array(g, "quantile_ci_high", high, {k}, units,
                       "upper end of the distribution-free confidence interval of each quantile");
    attach_scale(g, "quantile_level", {"quantile", "quantile_ci_low", "quantile_ci_high"});
  }
  std::vector<double> thresholds, probabilities, probability_low, probability_high;
  std::vector<std::int64_t> above, counted;
  for (const auto& e : exceedance) {
    if (e.value("column", std::string()) != column) continue;
    thresholds.push_back(number_of(e["above"]));
    probabilities.push_back(number_of(e["probability"]));
    probability_low.push_back(number_of(e["ci"][0]));
    probability_high.push_back(number_of(e["ci"][1]));
    above.push_back(e.value("count_above", std::int64_t{0}));
    counted.push_back(e.value("count", std::int64_t{0}));
  }
  if (!thresholds.empty()) {
    const hsize_t k = thresholds.size();
    write_double_array(g, "exceedance_threshold", thresholds, {k}, units,
                       "threshold of each exceedance probability (dimension scale)");
    write_double_array(g, "exceedance_probability", probabilities, {k}, "1",
                       "fraction of the ok samples above the threshold");
    write_double_array(g, "exceedance_probability_ci_low", probability_low, {k}, "1",
                       "lower end of the Wilson confidence interval of the exceedance probability");
    write_double_array(g, "exceedance_probability_ci_high", probability_high, {k}, "1",
                       "upper end of the Wilson confidence interval of the exceedance probability");
    write_int64_array(g, "exceedance_count", above, "ok samples above the threshold");
    write_int64_array(g, "exceedance_samples", counted, "ok samples counted");
    attach_scale(g, "exceedance_threshold",
                 {"exceedance_probability", "exceedance_probability_ci_low",
                  "exceedance_probability_ci_high", "exceedance_count", "exceedance_samples"});
  }
}

// The MPM runs at quantiles of a closed form (app/sweep_quantile_mpm.hpp), one row per quantile.
void write_mpm_at_quantiles(hid_t statistics, const json& runs) {
  if (!runs.is_array() || runs.empty()) return;
  Handle g = create_group(statistics, "mpm_at_quantiles");
  const std::string column = runs[0].value("column", std::string());
  write_string_attribute(g, "column", column);
  const hsize_t k = runs.size();
  std::vector<double> levels, values, seconds;
  std::vector<std::uint64_t> samples;
  std::vector<std::string> status, end_state;
  std::map<std::string, std::vector<double>> mpm, closed, errors;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const json& e = runs[i];
    levels.push_back(number_of(e["quantile"]));
    values.push_back(number_of(e["quantile_value"]));
    samples.push_back(e.value("sample", std::uint64_t{0}));
    status.push_back(e.value("mpm_status", std::string()));
    end_state.push_back(e.value("mpm_end_state", std::string()));
    seconds.push_back(number_of(e.value("mpm_seconds", json(nullptr))));
    const auto collect = [&](const char* key, std::map<std::string, std::vector<double>>& into) {
      const json values = e.value(key, json::object());
      for (const auto& [name, v] : values.items()) {
        auto& c = into[name];
        c.resize(runs.size(), NAN);
        c[i] = number_of(v);
      }
    };
    collect("mpm", mpm);
    collect("closed_form", closed);
    collect("relative_error", errors);
  }
  write_double_array(g, "quantile_level", levels, {k}, "1",
                     "probability p of each quantile (dimension scale)");
  write_double_array(g, "quantile", values, {k}, units_of(column),
                     "p-quantile of " + column + " over the ok samples");
  write_column(g, "sample", H5T_STD_U64LE, H5T_NATIVE_UINT64, samples, "1",
               "index of the ok sample nearest the quantile, the one the MPM ran",
               SweepStorage::Plain);
  write_strings(g, "mpm_status", status, "the MPM solver's status");
  write_strings(g, "mpm_end_state", end_state, "how the MPM run ended (at_rest, ...)");
  write_double_array(g, "mpm_seconds", seconds, {k}, "s", "wall time of the MPM run");
  std::vector<std::string> rows = {"quantile", "sample", "mpm_status", "mpm_end_state",
                                   "mpm_seconds"};
  for (auto& [name, v] : mpm) {
    v.resize(runs.size(), NAN);
    write_double_array(g, "mpm/" + name, v, {k}, units_of("mpm/" + name),
                       "the MPM's " + name + " at the sample");
    rows.push_back("mpm/" + name);
  }
  for (auto& [name, v] : closed) {
    v.resize(runs.size(), NAN);
    write_double_array(g, "closed_form/" + name, v, {k}, units_of(name),
                       name + " of the closed form at the sample");
    rows.push_back("closed_form/" + name);
  }
  for (auto& [name, v] : errors) {
    v.resize(runs.size(), NAN);
    write_double_array(g, "relative_error/" + name, v, {k}, "1",
                       "(closed form - MPM) / MPM of " + name + "; NaN where it has none");
    rows.push_back("relative_error/" + name);
  }
  attach_scale(g, "quantile_level", rows);
}

void write_statistics(hid_t file, const json& statistics) {
  Handle g = create_group(file, "statistics");
  write_string_attribute(g, "json", statistics.dump(2));
  if (!statistics.is_object()) return;
  write_string_attribute(g, "design", statistics.value("design", std::string()));
  write_scalar_double(g, "confidence", statistics.value("confidence", std::nan("")), "1",
                      "confidence level of every interval of the statistics");
  if (statistics.contains("note"))
    write_string_attribute(g, "note", statistics["note"].get<std::string>());
  const std::pair<const char*, const char*> counts[] = {
      {"samples_planned", "samples the study plans"},
      {"samples_done", "samples done"},
      {"samples_ok", "samples with status ok (those the statistics describe)"}};
  for (const auto& [key, description] : counts)
    if (statistics.contains(key))
      write_scalar_int64(g, key, statistics[key].get<std::int64_t>(), "1", description);
  {
    Handle failed = create_group(g, "samples_failed");
    const json failures = statistics.value("samples_failed", json::object());
    for (const auto& [why, count] : failures.items())
      write_scalar_int64(failed, why, count.get<std::int64_t>(), "1",
                         "samples that ended so: " + why);
  }
  const json exceedance = statistics.value("exceedance", json::array());
  const json outputs = statistics.value("outputs", json::object());
  for (const auto& [column, o] : outputs.items()) write_output_statistics(g, column, o, exceedance);
  if (statistics.contains("mpm_at_quantiles"))
    write_mpm_at_quantiles(g, statistics["mpm_at_quantiles"]);
}

void write_file(const std::string& file, const SweepHeader& h, const SweepTable& t,
                const nlohmann::json* statistics, SweepStorage storage) {
  Handle f = sweep_layout::create_file(file);
  sweep_layout::write_header(f, h, t.rows());
  write_array(f, "/samples/index", H5T_STD_U64LE, H5T_NATIVE_UINT64, t.index, storage);
  write_array(f, "/samples/status", H5T_STD_I8LE, H5T_NATIVE_INT8, t.status, storage);
  write_array(f, "/samples/wall_time", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, t.wall_time, storage);
  std::vector<const std::vector<double>*> inputs;
  for (const auto& c : t.inputs) inputs.push_back(&c);
  write_columns(f, "/samples/inputs", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, inputs, storage, 2);
  for (std::size_t c = 0; c < t.output_columns.size(); ++c)
    write_array(f, "/samples/" + t.output_columns[c], H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                t.outputs[c], storage);
  sweep_layout::describe_samples(f, t.input_paths, t.output_columns);
  sweep_layout::write_failures_and_statistics(f, t.failure_index, t.failure_reason, statistics);
  check(H5Fflush(f, H5F_SCOPE_GLOBAL), "cannot flush the file");
  f.close("cannot close the file");
}

nlohmann::json parse_json_attribute(hid_t obj, const std::string& name) {
  try {
    return nlohmann::json::parse(read_string_attribute(obj, name));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("attribute '" + name + "' is not valid JSON: " + e.what());
  }
}

}  // namespace

namespace sweep_layout {

Handle create_file(const std::string& path) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a file-access property list");
  check(H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG), "cannot set the file close degree");
  return Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose,
                "cannot create the file");
}

void write_header(hid_t f, const SweepHeader& h, std::uint64_t rows) {
  write_string_attribute(f, "kind", kKind);
  write_string_attribute(f, "study", h.study.dump(2));
  if (!h.scene_resolved.is_null())
    write_string_attribute(f, "scene_resolved", h.scene_resolved.dump(2));
  write_string_attribute(f, "fingerprint", h.fingerprint);
  write_provenance(f);
  write_int64_attribute(f, "planned_samples", static_cast<std::int64_t>(h.planned_samples));
  write_int64_attribute(f, "chunk_samples", static_cast<std::int64_t>(h.chunk_samples));
  write_string_attribute(f, "shard", std::to_string(h.shard) + "/" + std::to_string(h.shard_count));
  write_int64_attribute(f, "samples_done", static_cast<std::int64_t>(rows));
  write_bool_attribute(f, "complete", h.complete);
  write_string_attribute(f, "stopped_by", h.stopped_by);
  write_double_attribute(f, "wall_seconds", h.wall_seconds);
  if (!h.journal.is_null()) write_string_attribute(f, "journal", h.journal.dump());
}

std::vector<SampleDataset> sample_datasets(std::size_t inputs,
                                           const std::vector<std::string>& output_columns) {
  // The HDF5 types named first: each macro is a comma expression that calls H5open, and nvcc
  // (CUDA 13, when lsi_io is compiled through Kokkos' nvcc_wrapper) garbles braced lists of them.
  const hid_t u64_file = H5T_STD_U64LE, u64 = H5T_NATIVE_UINT64;
  const hid_t i8_file = H5T_STD_I8LE, i8 = H5T_NATIVE_INT8;
  const hid_t f32_file = H5T_IEEE_F32LE, f32 = H5T_NATIVE_FLOAT;
  const hid_t f64_file = H5T_IEEE_F64LE, f64 = H5T_NATIVE_DOUBLE;
  std::vector<SampleDataset> d = {
      {"/samples/index", u64_file, u64, 1, sizeof(std::uint64_t)},
      {"/samples/status", i8_file, i8, 1, sizeof(std::int8_t)},
      {"/samples/wall_time", f32_file, f32, 1, sizeof(float)},
      {"/samples/inputs", f64_file, f64, static_cast<hsize_t>(inputs), sizeof(double)}};
  for (const auto& c : output_columns)
    d.push_back({"/samples/" + c, f64_file, f64, 1, sizeof(double)});
  return d;
}

void describe_samples(hid_t f, const std::vector<std::string>& input_paths,
                      const std::vector<std::string>& output_columns) {
  describe(open_dataset(f, "/samples/index"), "1", "sample index in the study");
  describe(open_dataset(f, "/samples/status"), "1",
           "0 ok, 1 invalid input, 2 MPM unstable, 3 failed, 4 MPM cut short while the "
           "barrier slid");
  describe(open_dataset(f, "/samples/wall_time"), "s",
           "wall time spent on the sample (closed forms: their chunk's time shared)");
  {
    Handle ds = open_dataset(f, "/samples/inputs");
    write_string_attribute(ds, "paths", nlohmann::json(input_paths).dump());
    // One unit per column, in the scene's units (those its keys name).
    std::vector<std::string> units;
    for (const auto& p : input_paths) units.push_back(input_units(p));
    write_string_array_attribute(ds, "units", units);
    write_string_attribute(ds, "description",
                           "the sample's inputs, one column per scene path (attribute paths)");
  }
  {
    Handle g(H5Gopen2(f, "/samples", H5P_DEFAULT), H5Gclose, "cannot open /samples");
    write_string_attribute(g, "output_columns", nlohmann::json(output_columns).dump());
    write_string_attribute(g, "status_meaning",
                           "0 ok, 1 invalid input, 2 MPM unstable, 3 failed, 4 MPM cut short "
                           "while the barrier slid (end time or end of the domain); reasons in "
                           "/failures");
  }
  for (const std::string& column : output_columns) {
    const std::string output = column.substr(column.find('/') + 1);
    describe(open_dataset(f, "/samples/" + column), units_of(column),
             output + " of the method " + column.substr(0, column.find('/')) +
                 "; NaN where status is not 0");
  }
}

void write_failures_and_statistics(hid_t f, const std::vector<std::uint64_t>& index,
                                   const std::vector<std::string>& reason,
                                   const nlohmann::json* statistics) {
  write_column(f, "/failures/index", H5T_STD_U64LE, H5T_NATIVE_UINT64, index, "1",
               "index of each sample whose status is not 0", SweepStorage::Plain);
  write_strings(f, "/failures/reason", reason, "why the sample failed (one line)");
  if (statistics) write_statistics(f, *statistics);
}

}  // namespace sweep_layout

void write_sweep_file(const std::string& path, const SweepHeader& header, const SweepTable& table,
                      const nlohmann::json* statistics, SweepStorage storage) {
  const std::size_t n = table.rows();
  bool ok = table.status.size() == n && table.wall_time.size() == n &&
            table.inputs.size() == table.input_paths.size() &&
            table.outputs.size() == table.output_columns.size() &&
            table.failure_index.size() == table.failure_reason.size();
  for (const auto& c : table.inputs) ok = ok && c.size() == n;
  for (const auto& c : table.outputs) ok = ok && c.size() == n;
  if (!ok) throw std::invalid_argument("write_sweep_file: columns of different lengths");
  write_atomically(path, "write_sweep_file", [&](const std::string& tmp) {
    write_file(tmp, header, table, statistics, storage);
  });
}

SweepFile read_sweep_file(const std::string& path) {
  SilenceHdf5Errors silence;
  try {
    Handle f = open_read_only(path);
    if (!has_attribute(f, "kind") || read_string_attribute(f, "kind") != kKind)
      throw std::runtime_error("not a sweep file (no attribute kind = \"lsi sweep\")");
    SweepFile out;
    SweepHeader& h = out.header;
    h.study = parse_json_attribute(f, "study");
    h.fingerprint = read_string_attribute(f, "fingerprint");
    if (has_attribute(f, "scene_resolved"))
      h.scene_resolved = parse_json_attribute(f, "scene_resolved");
    // Counts and flags: integers and booleans, or doubles in files of earlier versions.
    h.planned_samples = static_cast<std::uint64_t>(read_int64_attribute(f, "planned_samples"));
    h.chunk_samples = static_cast<std::uint64_t>(read_int64_attribute(f, "chunk_samples"));
    const std::string shard = read_string_attribute(f, "shard");
    if (std::sscanf(shard.c_str(), "%d/%d", &h.shard, &h.shard_count) != 2)
      throw std::runtime_error("attribute shard = \"" + shard + "\" is not i/N");
    h.complete = read_bool_attribute(f, "complete");
    h.stopped_by = read_string_attribute(f, "stopped_by");
    h.wall_seconds = read_double_attribute(f, "wall_seconds");
    if (has_attribute(f, "journal")) h.journal = parse_json_attribute(f, "journal");

    SweepTable& t = out.table;
    {
      Handle ds(H5Dopen2(f, "/samples/inputs", H5P_DEFAULT), H5Dclose,
                "cannot open /samples/inputs");
      t.input_paths = parse_json_attribute(ds, "paths").get<std::vector<std::string>>();
      Handle g(H5Gopen2(f, "/samples", H5P_DEFAULT), H5Gclose, "cannot open /samples");
      t.output_columns = parse_json_attribute(g, "output_columns").get<std::vector<std::string>>();
    }
    t.index = read_array<std::uint64_t>(f, "/samples/index", H5T_NATIVE_UINT64);
    t.status = read_array<std::int8_t>(f, "/samples/status", H5T_NATIVE_INT8);
    t.wall_time = read_array<float>(f, "/samples/wall_time", H5T_NATIVE_FLOAT);
    const std::size_t n = t.index.size(), d = t.input_paths.size();
    hsize_t cols = 0;
    const std::vector<double> rows =
        read_array<double>(f, "/samples/inputs", H5T_NATIVE_DOUBLE, &cols);
    if (t.status.size() != n || t.wall_time.size() != n ||
        (n > 0 && (cols != d || rows.size() != n * d)))
      throw std::runtime_error("the /samples datasets have different lengths");
    t.inputs.assign(d, std::vector<double>(n));
    for (std::size_t k = 0; k < d; ++k)
      for (std::size_t i = 0; i < n; ++i) t.inputs[k][i] = rows[i * d + k];
    for (const auto& c : t.output_columns) {
      t.outputs.push_back(read_array<double>(f, "/samples/" + c, H5T_NATIVE_DOUBLE));
      if (t.outputs.back().size() != n)
        throw std::runtime_error("/samples/" + c + " has " +
                                 std::to_string(t.outputs.back().size()) +
                                 " rows, /samples/index " + std::to_string(n));
    }
    t.failure_index = read_array<std::uint64_t>(f, "/failures/index", H5T_NATIVE_UINT64);
    t.failure_reason = read_strings(f, "/failures/reason");
    if (t.failure_index.size() != t.failure_reason.size())
      throw std::runtime_error("/failures/index and /failures/reason have different lengths");
    if (has_link(f, "statistics")) {
      Handle g(H5Gopen2(f, "/statistics", H5P_DEFAULT), H5Gclose, "cannot open /statistics");
      out.statistics = parse_json_attribute(g, "json");
    }
    f.close("cannot close the file");
    return out;
  } catch (const std::exception& e) {
    throw std::runtime_error("read_sweep_file: cannot read '" + path + "': " + e.what());
  }
}

}  // namespace lsi
