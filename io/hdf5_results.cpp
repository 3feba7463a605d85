// HDF5 result files; layout in hdf5_results.hpp.
#include "io/hdf5_results.hpp"
#include "io/hdf5_io.hpp"
#include "io/provenance.hpp"

#include <cmath>
#include <limits>

#include <hdf5.h>

#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <utility>

namespace lsi {
namespace {

namespace fs = std::filesystem;
using namespace hdf5;

// ---------------------------------------------------------------------------------------------
// Datasets.

void write_dataset(hid_t group, const std::string& name, const std::vector<double>& data,
                   const std::string& units, const std::string& description) {
  write_double_array(group, name, data, {static_cast<hsize_t>(data.size())}, units, description);
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

const std::vector<SummaryField>& kSummaries = summary_fields();

// The group of a method's scalars, one 0-d dataset each.
constexpr const char* kScalarsGroup = "scalars";

// Deprecated: the attribute of earlier versions listing the units of the four summaries.
constexpr const char* kLegacyScalarUnits =
    "peak_force N/m; rise_time s; impact_duration s; final_displacement m";

void write_scalars(hid_t method_group, const MethodResult& r) {
  Handle g(H5Gcreate2(method_group, kScalarsGroup, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
           "cannot create group 'scalars'");
  // NaN means "not given by this method" (e.g. no impact duration from a peak-force-only
  // family): described_scalars leaves such scalars out rather than storing NaN.
  for (const DescribedScalar& s : described_scalars(r)) {
    switch (s.kind) {
      case ScalarKind::Count:
        write_scalar_int64(g, s.name, static_cast<std::int64_t>(s.value), s.units, s.description);
        break;
      case ScalarKind::Flag:
        write_scalar_bool(g, s.name, s.value != 0.0, s.description);
        break;
      case ScalarKind::Real:
        write_scalar_double(g, s.name, s.value, s.units, s.description);
        break;
    }
    // Deprecated copy, as earlier versions stored it.
    write_double_attribute(method_group, s.name, s.value);
  }
  write_string_attribute(method_group, "units", kLegacyScalarUnits);
  g.close("cannot close group 'scalars'");
}

// `time` becomes the dimension scale of every other history of the group (all have its length:
// validate checks it).
void attach_time_scale(hid_t group, const MethodResult& r) {
  if (r.time.empty()) return;
  Handle time(H5Dopen2(group, "time", H5P_DEFAULT), H5Dclose, "cannot open dataset 'time'");
  make_dimension_scale(time, "time");
  const auto attach = [&](const std::string& name) {
    Handle d(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose,
             "cannot open dataset '" + name + "'");
    attach_dimension_scale(d, time, 0);
  };
  for (const auto& h : kHistories)
    if (std::string(h.name) != "time" && !(r.*(h.member)).empty()) attach(h.name);
  for (const auto& [name, sr] : r.series) attach(name);
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
      bool clash = name.empty() || name.find('/') != std::string::npos || name == kScalarsGroup;
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
                const std::string& resolved_text, const std::vector<MethodResult>& results,
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
  if (!resolved_text.empty()) write_string_attribute(f, "scene_resolved", resolved_text);
  write_provenance(f);

  for (const auto& r : results) {
    Handle g(H5Gcreate2(f, r.method.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
             "cannot create group '" + r.method + "'");
    try {
      for (const auto& h : kHistories) {
        const auto& v = r.*(h.member);
        if (!v.empty()) write_dataset(g, h.name, v, h.units, h.description);
      }
      for (const auto& [name, sr] : r.series)
        write_dataset(g, name, sr.values, sr.units.empty() ? "1" : sr.units, sr.description);
      attach_time_scale(g, r);
      write_scalars(g, r);
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

// The names of a group's links (H5_INDEX_NAME order).
std::vector<std::string> link_names(hid_t group, const std::string& what) {
  std::vector<std::string> names;
  check(H5Literate(
            group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
            [](hid_t, const char* link_name, const H5L_info_t*, void* data) -> herr_t {
              try {
                static_cast<std::vector<std::string>*>(data)->emplace_back(link_name);
                return 0;
              } catch (...) {
                return -1;
              }
            },
            &names),
        "cannot list " + what);
  return names;
}

// Sets the scalar of that name: one of the four summaries or a named one (a name this version
// does not know, a newer writer's, is left out).
void set_scalar(MethodResult& r, const std::string& name, double value) {
  for (const auto& f : kSummaries)
    if (name == f.name) {
      r.*(f.member) = value;
      return;
    }
  set_named_scalar(r, name, value);
}

// The scalars of files without /<method>/scalars (earlier versions): the group's single double
// attributes.
void read_attribute_scalars(hid_t g, const std::string& name, MethodResult& r) {
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
  for (const auto& a : attr_names) {
    if (a == "units" || a == "end_state" || a == "status" || a == "barrier_model") continue;
    Handle attr(H5Aopen(g, a.c_str(), H5P_DEFAULT), H5Aclose, "cannot open attribute '" + a + "'");
    Handle type(H5Aget_type(attr), H5Tclose, "cannot get the type of attribute '" + a + "'");
    Handle space(H5Aget_space(attr), H5Sclose, "cannot get the dataspace of attribute '" + a + "'");
    if (H5Tget_class(type) != H5T_FLOAT || H5Sget_simple_extent_npoints(space) != 1) continue;
    set_scalar(r, a, read_double_attribute(g, a));
  }
}

MethodResult read_group(hid_t file, const std::string& name) {
  Handle g(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group '" + name + "'");
  MethodResult r;
  r.method = name;
  for (const auto& h : kHistories)
    if (has_link(g, h.name)) r.*(h.member) = read_dataset(g, h.name);
  // Every other dataset is a further series.
  for (const auto& l : link_names(g, "the datasets of group '" + name + "'")) {
    bool known = false;
    for (const auto& h : kHistories) known = known || l == h.name;
    if (known) continue;
    // Only datasets are histories; subgroups (the scalars, the MPM particle snapshots) are not.
    Handle obj(H5Oopen(g, l.c_str(), H5P_DEFAULT), H5Oclose, "cannot open '" + l + "'");
    if (H5Iget_type(obj) != H5I_DATASET) continue;
    auto& series = r.series[l];
    series.values = read_dataset(g, l);
    if (has_attribute(obj, "units")) series.units = read_string_attribute(obj, "units");
    if (has_attribute(obj, "description"))
      series.description = read_string_attribute(obj, "description");
  }
  for (const auto& s : kSummaries) r.*(s.member) = std::numeric_limits<double>::quiet_NaN();
  if (has_link(g, kScalarsGroup)) {
    Handle sg(H5Gopen2(g, kScalarsGroup, H5P_DEFAULT), H5Gclose,
              "cannot open group '" + name + "/scalars'");
    for (const auto& s : link_names(sg, "the scalars of group '" + name + "'"))
      set_scalar(r, s, read_scalar_number(sg, s));
  } else {
    read_attribute_scalars(g, name, r);
  }
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
  return r;
}

}  // namespace

void write_results(const std::string& path, const nlohmann::json& scene,
                   const std::vector<MethodResult>& results,
                   const std::function<void(long long file_id)>& extra,
                   const nlohmann::json& scene_resolved) {
  validate(results);
  std::string scene_text, resolved_text;
  try {
    scene_text = scene.dump(2);
    if (!scene_resolved.is_null()) resolved_text = scene_resolved.dump(2);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("write_results: cannot serialise the scene: ") +
                                e.what());
  }

  write_atomically(path, "write_results", [&](const std::string& tmp) {
    write_file(tmp, scene_text, resolved_text, results, extra);
  });
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
    if (has_attribute(f, "scene_resolved")) {
      try {
        out.scene_resolved = nlohmann::json::parse(read_string_attribute(f, "scene_resolved"));
      } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(std::string("attribute 'scene_resolved' is not valid JSON: ") +
                                 e.what());
      }
    }
    if (has_attribute(f, "lsi_version")) out.lsi_version = read_string_attribute(f, "lsi_version");
    if (has_attribute(f, "git_revision"))
      out.git_revision = read_string_attribute(f, "git_revision");
    if (has_attribute(f, "argv")) out.argv = read_string_array_attribute(f, "argv");

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
