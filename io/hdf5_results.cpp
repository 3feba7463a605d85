// HDF5 result files; layout in hdf5_results.hpp.
#include "io/hdf5_results.hpp"
#include "io/hdf5_io.hpp"

#include <cmath>
#include <limits>

#include <hdf5.h>

#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <utility>
#include "lsi_git_revision.hpp"  // LSI_GIT_REVISION, generated at build time

#ifndef LSI_VERSION
#define LSI_VERSION "unknown"
#endif

namespace lsi {
namespace {

namespace fs = std::filesystem;
using namespace hdf5;

// ---------------------------------------------------------------------------------------------
// Datasets.

void write_dataset(hid_t group, const std::string& name, const std::vector<double>& data,
                   const std::string& units, const std::string& description) {
  const hsize_t dims[1] = {static_cast<hsize_t>(data.size())};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose,
               "cannot create dataspace for '" + name + "'");
  Handle dset(
      H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose, "cannot create dataset '" + name + "'");
  check(H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
        "cannot write dataset '" + name + "'");
  write_string_attribute(dset, "units", units);
  write_string_attribute(dset, "description", description);
}

std::vector<double> read_dataset(hid_t group, const std::string& name) {
  Handle dset(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose,
              "cannot open dataset '" + name + "'");
  Handle space(H5Dget_space(dset), H5Sclose, "cannot get the dataspace of '" + name + "'");
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) fail("cannot get the rank of '" + name + "'");
  if (rank != 1) throw std::runtime_error("dataset '" + name + "' is not one-dimensional");
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 0) fail("cannot get the size of '" + name + "'");
  std::vector<double> data(static_cast<size_t>(n));
  if (n > 0)
    check(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          "cannot read dataset '" + name + "'");
  return data;
}

// ---------------------------------------------------------------------------------------------
// The layout.

const std::vector<HistoryField>& kHistories = history_fields();

struct ScalarSpec {
  const char* name;
  double MethodResult::*member;
};

const ScalarSpec kScalars[] = {
    {"peak_force", &MethodResult::peak_force},
    {"rise_time", &MethodResult::rise_time},
    {"impact_duration", &MethodResult::impact_duration},
    {"final_displacement", &MethodResult::final_displacement},
};

constexpr const char* kScalarUnits =
    "peak_force N/m; rise_time s; impact_duration s; final_displacement m";

bool is_reserved_attribute(const std::string& name) {
  if (name == "units" || name == "end_state" || name == "status" || name == "barrier_model")
    return true;
  for (const auto& s : kScalars)
    if (name == s.name) return true;
  return false;
}

void validate(const std::vector<MethodResult>& results) {
  std::set<std::string> seen;
  for (const auto& r : results) {
    if (r.method.empty()) throw std::invalid_argument("write_results: empty method name");
    if (r.method.find('/') != std::string::npos || r.method == "." || r.method == "..")
      throw std::invalid_argument("write_results: invalid method name '" + r.method + "'");
    if (!seen.insert(r.method).second)
      throw std::invalid_argument("write_results: duplicate method '" + r.method + "'");
    const size_t n = r.time.size();
    for (const auto& h : kHistories) {
      const auto& v = r.*(h.member);
      if (!v.empty() && v.size() != n)
        throw std::invalid_argument("write_results: method '" + r.method + "': dataset '" + h.name +
                                    "' has " + std::to_string(v.size()) +
                                    " samples but 'time' has " + std::to_string(n));
    }
    for (const auto& [name, sr] : r.series) {
      bool clash = name.empty() || name.find('/') != std::string::npos;
      for (const auto& h : kHistories) clash = clash || name == h.name;
      if (clash)
        throw std::invalid_argument("write_results: method '" + r.method + "': series '" + name +
                                    "' has an invalid or reserved name");
      if (sr.values.size() != n)
        throw std::invalid_argument("write_results: method '" + r.method + "': series '" + name +
                                    "' has " + std::to_string(sr.values.size()) +
                                    " samples but 'time' has " + std::to_string(n));
    }
  }
}

void write_file(const std::string& file, const std::string& scene_text,
                const std::vector<MethodResult>& results,
                const std::function<void(long long file_id)>& extra) {
  // Track link creation order in the root group so that read_results returns the methods in the
  // order they were given.
  Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "cannot create a file-creation property list");
  check(H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
        "cannot set link creation order tracking");
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a file-access property list");
  check(H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG), "cannot set the file close degree");
  Handle f(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, fcpl, fapl), H5Fclose, "cannot create the file");

  write_string_attribute(f, "scene", scene_text);
  write_string_attribute(f, "lsi_version", LSI_VERSION);
  write_string_attribute(f, "git_revision", LSI_GIT_REVISION);

  for (const auto& r : results) {
    Handle g(H5Gcreate2(f, r.method.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
             "cannot create group '" + r.method + "'");
    try {
      for (const auto& h : kHistories) {
        const auto& v = r.*(h.member);
        if (!v.empty()) write_dataset(g, h.name, v, h.units, h.description);
      }
      for (const auto& [name, sr] : r.series)
        write_dataset(g, name.c_str(), sr.values, sr.units.c_str(), sr.description.c_str());
      // NaN means "not given by this method" (e.g. no impact duration from a peak-force-only
      // family): such scalars are left out rather than stored as NaN.
      for (const auto& s : kScalars)
        if (!std::isnan(r.*(s.member))) write_double_attribute(g, s.name, r.*(s.member));
      for (const auto& [name, value] : named_scalars(r))
        if (!std::isnan(value)) write_double_attribute(g, name, value);
      write_string_attribute(g, "units", kScalarUnits);
      if (r.end_state != EndState::None)
        write_string_attribute(g, "end_state", end_state_token(r.end_state));
      if (!r.status.empty()) write_string_attribute(g, "status", r.status);
      if (!r.barrier_model.empty()) write_string_attribute(g, "barrier_model", r.barrier_model);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("group '" + r.method + "': " + e.what());
    }
    g.close("cannot close group '" + r.method + "'");
  }
  if (extra) extra(static_cast<long long>(f.get()));

  check(H5Fflush(f, H5F_SCOPE_GLOBAL), "cannot flush the file");
  f.close("cannot close the file");
}

MethodResult read_group(hid_t file, const std::string& name) {
  Handle g(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group '" + name + "'");
  MethodResult r;
  r.method = name;
  for (const auto& h : kHistories)
    if (has_link(g, h.name)) r.*(h.member) = read_dataset(g, h.name);
  // Every other dataset is a further series.
  std::vector<std::string> links;
  check(H5Literate(
            g, H5_INDEX_NAME, H5_ITER_INC, nullptr,
            [](hid_t, const char* link_name, const H5L_info_t*, void* data) -> herr_t {
              try {
                static_cast<std::vector<std::string>*>(data)->emplace_back(link_name);
                return 0;
              } catch (...) {
                return -1;
              }
            },
            &links),
        "cannot list the datasets of group '" + name + "'");
  for (const auto& l : links) {
    bool known = false;
    for (const auto& h : kHistories) known = known || l == h.name;
    if (known) continue;
    // Only datasets are histories; subgroups (the MPM particle snapshots, /mpm/snapshots) are not.
    Handle obj(H5Oopen(g, l.c_str(), H5P_DEFAULT), H5Oclose, "cannot open '" + l + "'");
    if (H5Iget_type(obj) != H5I_DATASET) continue;
    auto& series = r.series[l];
    series.values = read_dataset(g, l);
    if (has_attribute(obj, "units")) series.units = read_string_attribute(obj, "units");
    if (has_attribute(obj, "description"))
      series.description = read_string_attribute(obj, "description");
  }
  for (const auto& s : kScalars)
    r.*(s.member) = has_attribute(g, s.name) ? read_double_attribute(g, s.name)
                                             : std::numeric_limits<double>::quiet_NaN();

  std::vector<std::string> attr_names;
  check(H5Aiterate2(
            g, H5_INDEX_NAME, H5_ITER_INC, nullptr,
            [](hid_t, const char* attr_name, const H5A_info_t*, void* data) -> herr_t {
              try {
                static_cast<std::vector<std::string>*>(data)->emplace_back(attr_name);
                return 0;
              } catch (...) {
                return -1;
              }
            },
            &attr_names),
        "cannot list the attributes of group '" + name + "'");
  if (has_attribute(g, "end_state")) {
    const std::string token = read_string_attribute(g, "end_state");
    try {
      r.end_state = end_state_from_token(token);
    } catch (const std::invalid_argument&) {
      throw std::runtime_error("group '" + name + "': attribute end_state = '" + token +
                               "' is not an end state");
    }
  }
  if (has_attribute(g, "status")) r.status = read_string_attribute(g, "status");
  if (has_attribute(g, "barrier_model"))
    r.barrier_model = read_string_attribute(g, "barrier_model");
  for (const auto& a : attr_names) {
    if (is_reserved_attribute(a)) continue;
    Handle attr(H5Aopen(g, a.c_str(), H5P_DEFAULT), H5Aclose, "cannot open attribute '" + a + "'");
    Handle type(H5Aget_type(attr), H5Tclose, "cannot get the type of attribute '" + a + "'");
    Handle space(H5Aget_space(attr), H5Sclose, "cannot get the dataspace of attribute '" + a + "'");
    if (H5Tget_class(type) != H5T_FLOAT || H5Sget_simple_extent_npoints(space) != 1) continue;
    // A scalar this version does not know (a newer writer's) is left out.
    set_named_scalar(r, a, read_double_attribute(g, a));
  }
  return r;
}

}  // namespace

void write_results(const std::string& path, const nlohmann::json& scene,
                   const std::vector<MethodResult>& results,
                   const std::function<void(long long file_id)>& extra) {
  validate(results);
  std::string scene_text;
  try {
    scene_text = scene.dump(2);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("write_results: cannot serialise the scene: ") +
                                e.what());
  }

  write_atomically(path, "write_results",
                   [&](const std::string& tmp) { write_file(tmp, scene_text, results, extra); });
}

StoredResults read_results(const std::string& path) {
  SilenceHdf5Errors silence;
  try {
    Handle f = open_read_only(path);

    StoredResults out;
    if (has_attribute(f, "scene")) {
      const std::string text = read_string_attribute(f, "scene");
      try {
        out.scene = nlohmann::json::parse(text);
      } catch (const std::exception& e) {
        throw std::runtime_error(std::string("attribute 'scene' is not valid JSON: ") + e.what());
      }
    }
    if (has_attribute(f, "lsi_version")) out.lsi_version = read_string_attribute(f, "lsi_version");

    // Methods in creation order when the file tracks it (write_results does), else by name.
    H5_index_t index = H5_INDEX_NAME;
    {
      Handle root(H5Gopen2(f, "/", H5P_DEFAULT), H5Gclose, "cannot open the root group");
      Handle gcpl(H5Gget_create_plist(root), H5Pclose, "cannot get the root group properties");
      unsigned flags = 0;
      check(H5Pget_link_creation_order(gcpl, &flags), "cannot get the link creation order");
      if ((flags & H5P_CRT_ORDER_TRACKED) != 0 && (flags & H5P_CRT_ORDER_INDEXED) != 0)
        index = H5_INDEX_CRT_ORDER;
    }
    std::vector<std::string> names;
    check(H5Literate(
              f, index, H5_ITER_INC, nullptr,
              [](hid_t group, const char* name, const H5L_info_t* info, void* data) -> herr_t {
                try {
                  if (info->type != H5L_TYPE_HARD) return 0;
                  const hid_t obj = H5Oopen(group, name, H5P_DEFAULT);
                  if (obj < 0) return -1;
                  const bool is_group = H5Iget_type(obj) == H5I_GROUP;
                  H5Oclose(obj);
                  if (is_group) static_cast<std::vector<std::string>*>(data)->emplace_back(name);
                  return 0;
                } catch (...) {
                  return -1;
                }
              },
              &names),
          "cannot list the root group");
    for (const auto& name : names) out.results.push_back(read_group(f, name));
    f.close("cannot close the file");
    return out;
  } catch (const std::exception& e) {
    throw std::runtime_error("read_results: cannot read '" + path + "': " + e.what());
  }
}

}  // namespace lsi
