// HDF5 result files; layout in hdf5_results.hpp.
#include "drivers/hdf5_results.hpp"

#include <cmath>
#include <limits>

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <utility>

#ifndef LSI_VERSION
#define LSI_VERSION "unknown"
#endif
#ifndef LSI_GIT_REVISION
#define LSI_GIT_REVISION "unknown"
#endif

namespace lsi {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// HDF5 plumbing: error capture, RAII handles.

// Silences HDF5's automatic error-stack printing for the lifetime of the guard (failures are turned
// into exceptions instead) and restores the previous handler afterwards.
class SilenceHdf5Errors {
 public:
  SilenceHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  SilenceHdf5Errors(const SilenceHdf5Errors&) = delete;
  SilenceHdf5Errors& operator=(const SilenceHdf5Errors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// The innermost messages of the current HDF5 error stack (which is then cleared), e.g.
// "unable to open file: file does not exist".
std::string hdf5_error_detail() {
  std::vector<std::string> descs;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* err, void* data) -> herr_t {
        auto* out = static_cast<std::vector<std::string>*>(data);
        if (err != nullptr && err->desc != nullptr && out->size() < 2) out->emplace_back(err->desc);
        return 0;
      },
      &descs);
  H5Eclear2(H5E_DEFAULT);
  std::string s;
  for (auto it = descs.rbegin(); it != descs.rend(); ++it) {
    if (!s.empty()) s += ": ";
    s += *it;
  }
  return s;
}

[[noreturn]] void fail(const std::string& what) {
  const std::string detail = hdf5_error_detail();
  throw std::runtime_error(detail.empty() ? what : what + " (HDF5: " + detail + ")");
}

void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

// Owns one hid_t and closes it with the matching H5?close. Move-only.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer, const std::string& what) : id_(id), closer_(closer) {
    if (id_ < 0) fail(what);
  }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
      closer_ = o.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: handles pass straight into the C API

  // Closes now and reports failure (the destructor ignores it).
  void close(const std::string& what) {
    if (id_ < 0) return;
    const herr_t status = closer_(std::exchange(id_, H5I_INVALID_HID));
    check(status, what);
  }

 private:
  void reset() noexcept {
    if (id_ >= 0) {
      closer_(id_);
      id_ = H5I_INVALID_HID;
    }
  }
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

Handle vlen_string_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create the string type");
  check(H5Tset_size(t, H5T_VARIABLE), "cannot make the string type variable-length");
  check(H5Tset_cset(t, H5T_CSET_UTF8), "cannot set the string type to UTF-8");
  return t;
}

// ---------------------------------------------------------------------------------------------
// Attributes and datasets.

void write_string_attribute(hid_t obj, const std::string& name, const std::string& value) {
  Handle type = vlen_string_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  Handle attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute '" + name + "'");
  const char* ptr = value.c_str();
  check(H5Awrite(attr, type, &ptr), "cannot write attribute '" + name + "'");
}

void write_double_attribute(hid_t obj, const std::string& name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  Handle attr(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose, "cannot create attribute '" + name + "'");
  check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "cannot write attribute '" + name + "'");
}

std::string read_string_attribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose,
              "cannot open attribute '" + name + "'");
  Handle file_type(H5Aget_type(attr), H5Tclose, "cannot get the type of attribute '" + name + "'");
  if (H5Tget_class(file_type) != H5T_STRING)
    throw std::runtime_error("attribute '" + name + "' is not a string");
  Handle space(H5Aget_space(attr), H5Sclose, "cannot get the dataspace of attribute '" + name + "'");
  if (H5Sget_simple_extent_npoints(space) != 1)
    throw std::runtime_error("attribute '" + name + "' is not a scalar string");

  const htri_t is_vlen = H5Tis_variable_str(file_type);
  if (is_vlen < 0) fail("cannot inspect the type of attribute '" + name + "'");
  if (is_vlen > 0) {
    Handle mem_type = vlen_string_type();
    char* buf = nullptr;
    check(H5Aread(attr, mem_type, &buf), "cannot read attribute '" + name + "'");
    std::string value = buf != nullptr ? std::string(buf) : std::string();
    H5free_memory(buf);
    return value;
  }
  // Fixed-length string (files written by other tools).
  const size_t size = H5Tget_size(file_type);
  if (size == 0) fail("cannot get the size of attribute '" + name + "'");
  Handle mem_type(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create the string type");
  check(H5Tset_size(mem_type, size), "cannot size the string type");
  std::string value(size, '\0');
  check(H5Aread(attr, mem_type, value.data()), "cannot read attribute '" + name + "'");
  value.resize(std::strlen(value.c_str()));
  return value;
}

double read_double_attribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose,
              "cannot open attribute '" + name + "'");
  double value = 0.0;
  check(H5Aread(attr, H5T_NATIVE_DOUBLE, &value), "cannot read attribute '" + name + "'");
  return value;
}

bool has_attribute(hid_t obj, const std::string& name) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  if (exists < 0) fail("cannot check for attribute '" + name + "'");
  return exists > 0;
}

bool has_link(hid_t group, const std::string& name) {
  const htri_t exists = H5Lexists(group, name.c_str(), H5P_DEFAULT);
  if (exists < 0) fail("cannot check for '" + name + "'");
  return exists > 0;
}

void write_dataset(hid_t group, const std::string& name, const std::vector<double>& data,
                   const std::string& units, const std::string& description) {
  const hsize_t dims[1] = {static_cast<hsize_t>(data.size())};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose, "cannot create dataspace for '" + name + "'");
  Handle dset(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                         H5P_DEFAULT),
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

struct HistorySpec {
  const char* name;
  std::vector<double> MethodResult::*member;
  const char* units;
  const char* description;
};

const HistorySpec kHistories[] = {
    {"time", &MethodResult::time, "s", "time of each sample"},
    {"force", &MethodResult::force, "N/m",
     "impact force per metre of barrier width, normal to the impacted face"},
    {"force_horizontal", &MethodResult::force_horizontal, "N/m",
     "horizontal component of the impact force per metre of barrier width"},
    {"force_vertical", &MethodResult::force_vertical, "N/m",
     "vertical component of the impact force per metre of barrier width, positive downwards on "
     "the barrier"},
    {"landslide_kinetic_energy", &MethodResult::landslide_kinetic_energy, "J/m",
     "kinetic energy of the landslide per metre of width"},
    {"barrier_velocity", &MethodResult::barrier_velocity, "m/s", "velocity of the barrier"},
    {"barrier_displacement", &MethodResult::barrier_displacement, "m",
     "displacement of the barrier"},
};

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
  if (name == "units") return true;
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
        throw std::invalid_argument("write_results: method '" + r.method + "': dataset '" +
                                    h.name + "' has " + std::to_string(v.size()) +
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
    for (const auto& [name, value] : r.extra) {
      (void)value;
      if (name.empty())
        throw std::invalid_argument("write_results: method '" + r.method + "': empty extra name");
      if (is_reserved_attribute(name))
        throw std::invalid_argument("write_results: method '" + r.method + "': extra '" + name +
                                    "' clashes with a reserved attribute");
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
      for (const auto& [name, value] : r.extra)
        if (!std::isnan(value)) write_double_attribute(g, name, value);
      write_string_attribute(g, "units", kScalarUnits);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("group '" + r.method + "': " + e.what());
    }
    g.close("cannot close group '" + r.method + "'");
  }
  if (extra) extra(static_cast<long long>(f.get()));

  check(H5Fflush(f, H5F_SCOPE_GLOBAL), "cannot flush the file");
  f.close("cannot close the file");
}

void fsync_file(const std::string& file) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd < 0) throw std::runtime_error(std::string("cannot open for fsync: ") + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw std::runtime_error(std::string("fsync failed: ") + std::strerror(err));
}

// Best effort: makes the rename itself durable. Failure is not an error (the file is complete).
void fsync_directory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

// Removes our temporary file after a failure; leaves anything that is not a regular file alone (a
// directory of that name is not ours).
void remove_temporary(const std::string& tmp) noexcept {
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(tmp, ec))) fs::remove(tmp, ec);
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
    r.series[l].values = read_dataset(g, l);
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
  for (const auto& a : attr_names) {
    if (is_reserved_attribute(a)) continue;
    Handle attr(H5Aopen(g, a.c_str(), H5P_DEFAULT), H5Aclose, "cannot open attribute '" + a + "'");
    Handle type(H5Aget_type(attr), H5Tclose, "cannot get the type of attribute '" + a + "'");
    Handle space(H5Aget_space(attr), H5Sclose, "cannot get the dataspace of attribute '" + a + "'");
    if (H5Tget_class(type) != H5T_FLOAT || H5Sget_simple_extent_npoints(space) != 1) continue;
    r.extra[a] = read_double_attribute(g, a);
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

  const fs::path target(path);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const auto failure = [&](const std::string& what) {
    return std::runtime_error("write_results: cannot write '" + path + "': " + what);
  };

  if (target.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    if (ec)
      throw failure("cannot create directory '" + target.parent_path().string() +
                    "': " + ec.message());
  }

  SilenceHdf5Errors silence;
  try {
    write_file(tmp, scene_text, results, extra);
    fsync_file(tmp);
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw std::runtime_error("cannot rename '" + tmp + "' onto it: " + std::strerror(errno));
  } catch (const std::exception& e) {
    remove_temporary(tmp);
    throw failure(e.what());
  } catch (...) {
    remove_temporary(tmp);
    throw failure("unknown error");
  }
  fsync_directory(target.parent_path());
}

StoredResults read_results(const std::string& path) {
  SilenceHdf5Errors silence;
  try {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a file-access property list");
    check(H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG), "cannot set the file close degree");
    Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose, "cannot open the file");

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
