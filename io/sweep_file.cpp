// Sweep tables in HDF5; layout in sweep_table.hpp.
#include "io/sweep_file.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "io/hdf5_io.hpp"
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

#ifndef LSI_VERSION
#define LSI_VERSION "unknown"
#endif

namespace lsi {
namespace {

using namespace hdf5;
constexpr const char* kKind = "lsi sweep";

const char* units_of(const std::string& column) {
  const std::string out = column.substr(column.find('/') + 1);
  if (out == "peak_force") return "N/m";
  if (out == "final_displacement") return "m";
  return "s";
}

Handle intermediate_groups() {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "cannot create a link-creation property list");
  check(H5Pset_create_intermediate_group(lcpl, 1), "cannot set intermediate group creation");
  return lcpl;
}

template <class T>
void write_array(hid_t file, const std::string& name, hid_t file_type, hid_t mem_type,
                 const std::vector<T>& data, int rank = 1, hsize_t columns = 1) {
  const hsize_t dims[2] = {static_cast<hsize_t>(rank == 1 ? data.size() : data.size() / columns),
                           columns};
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose,
               "cannot create dataspace for '" + name + "'");
  Handle lcpl = intermediate_groups();
  Handle dset(H5Dcreate2(file, name.c_str(), file_type, space, lcpl, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose, "cannot create dataset '" + name + "'");
  if (!data.empty())
    check(H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          "cannot write dataset '" + name + "'");
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

void write_strings(hid_t file, const std::string& name, const std::vector<std::string>& s) {
  std::vector<const char*> ptr;
  for (const auto& x : s) ptr.push_back(x.c_str());
  Handle type = vlen_string_type();
  write_array(file, name, type, type, ptr);
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

void write_file(const std::string& file, const SweepHeader& h, const SweepTable& t,
                const nlohmann::json* statistics) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a file-access property list");
  check(H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG), "cannot set the file close degree");
  Handle f(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose,
           "cannot create the file");
  write_string_attribute(f, "kind", kKind);
  write_string_attribute(f, "study", h.study.dump(2));
  write_string_attribute(f, "fingerprint", h.fingerprint);
  write_string_attribute(f, "lsi_version", LSI_VERSION);
  write_string_attribute(f, "git_revision", LSI_GIT_REVISION);
  write_double_attribute(f, "planned_samples", static_cast<double>(h.planned_samples));
  write_double_attribute(f, "chunk_samples", static_cast<double>(h.chunk_samples));
  write_string_attribute(f, "shard", std::to_string(h.shard) + "/" + std::to_string(h.shard_count));
  write_double_attribute(f, "samples_done", static_cast<double>(t.rows()));
  write_double_attribute(f, "complete", h.complete ? 1.0 : 0.0);
  write_string_attribute(f, "stopped_by", h.stopped_by);
  write_double_attribute(f, "wall_seconds", h.wall_seconds);

  const std::size_t n = t.rows();
  write_array(f, "/samples/index", H5T_STD_U64LE, H5T_NATIVE_UINT64, t.index);
  write_array(f, "/samples/status", H5T_STD_I8LE, H5T_NATIVE_INT8, t.status);
  write_array(f, "/samples/wall_time", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, t.wall_time);
  const std::size_t d = t.input_paths.size();
  std::vector<double> rows(n * d);
  for (std::size_t k = 0; k < d; ++k)
    for (std::size_t i = 0; i < n; ++i) rows[i * d + k] = t.inputs[k][i];
  write_array(f, "/samples/inputs", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows, 2, d);
  {
    Handle ds(H5Dopen2(f, "/samples/inputs", H5P_DEFAULT), H5Dclose, "cannot open /samples/inputs");
    write_string_attribute(ds, "paths", nlohmann::json(t.input_paths).dump());
  }
  nlohmann::json columns = t.output_columns;
  {
    Handle g(H5Gopen2(f, "/samples", H5P_DEFAULT), H5Gclose, "cannot open /samples");
    write_string_attribute(g, "output_columns", columns.dump());
    write_string_attribute(g, "status_meaning",
                           "0 ok, 1 invalid input, 2 MPM unstable, 3 failed, 4 MPM cut short "
                           "while the barrier slid (end time or end of the domain); reasons in "
                           "/failures");
  }
  for (std::size_t c = 0; c < t.output_columns.size(); ++c) {
    const std::string name = "/samples/" + t.output_columns[c];
    write_array(f, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, t.outputs[c]);
    Handle ds(H5Dopen2(f, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open " + name);
    write_string_attribute(ds, "units", units_of(t.output_columns[c]));
  }
  write_array(f, "/failures/index", H5T_STD_U64LE, H5T_NATIVE_UINT64, t.failure_index);
  write_strings(f, "/failures/reason", t.failure_reason);
  if (statistics) {
    Handle g(H5Gcreate2(f, "/statistics", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
             "cannot create /statistics");
    write_string_attribute(g, "json", statistics->dump(2));
  }
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

void write_sweep_file(const std::string& path, const SweepHeader& header, const SweepTable& table,
                      const nlohmann::json* statistics) {
  const std::size_t n = table.rows();
  bool ok = table.status.size() == n && table.wall_time.size() == n &&
            table.inputs.size() == table.input_paths.size() &&
            table.outputs.size() == table.output_columns.size() &&
            table.failure_index.size() == table.failure_reason.size();
  for (const auto& c : table.inputs) ok = ok && c.size() == n;
  for (const auto& c : table.outputs) ok = ok && c.size() == n;
  if (!ok) throw std::invalid_argument("write_sweep_file: columns of different lengths");
  write_atomically(path, "write_sweep_file",
                   [&](const std::string& tmp) { write_file(tmp, header, table, statistics); });
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
    h.planned_samples = static_cast<std::uint64_t>(read_double_attribute(f, "planned_samples"));
    h.chunk_samples = static_cast<std::uint64_t>(read_double_attribute(f, "chunk_samples"));
    const std::string shard = read_string_attribute(f, "shard");
    if (std::sscanf(shard.c_str(), "%d/%d", &h.shard, &h.shard_count) != 2)
      throw std::runtime_error("attribute shard = \"" + shard + "\" is not i/N");
    h.complete = read_double_attribute(f, "complete") != 0.0;
    h.stopped_by = read_string_attribute(f, "stopped_by");
    h.wall_seconds = read_double_attribute(f, "wall_seconds");

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
