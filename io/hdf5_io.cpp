// HDF5 plumbing; see hdf5_io.hpp.
#include "io/hdf5_io.hpp"
#include "io/output_paths.hpp"
#include "io/temporary_files.hpp"

#include <hdf5_hl.h>  // dimension scales (H5DS)
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace lsi::hdf5 {

namespace fs = std::filesystem;

namespace {
// HDF5 closes what is still open in an exit handler of its own. After a write that failed (a
// full disk) the file's close fails half-way, and that handler then crashes on it (SIGSEGV
// instead of the exit code and message). Every file lsi writes is closed explicitly, so the
// handler is not needed: it is switched off before the library is first used.
const bool kNoExitHandler = [] {
  H5dont_atexit();
  return true;
}();
}  // namespace

// The innermost messages of the current HDF5 error stack (which is then cleared), e.g.
// "unable to open file: file does not exist".
std::string error_detail() {
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
  // One line: the driver's messages carry a line break (e.g. after the time of a failed write).
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  return s;
}

[[noreturn]] void fail(const std::string& what) {
  const std::string detail = error_detail();
  throw std::runtime_error(detail.empty() ? what : what + " (HDF5: " + detail + ")");
}

void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

Handle vlen_string_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create the string type");
  check(H5Tset_size(t, H5T_VARIABLE), "cannot make the string type variable-length");
  check(H5Tset_cset(t, H5T_CSET_UTF8), "cannot set the string type to UTF-8");
  return t;
}

Handle bool_type() {
  Handle t(H5Tenum_create(H5T_NATIVE_INT8), H5Tclose, "cannot create the boolean type");
  const std::int8_t no = 0, yes = 1;
  check(H5Tenum_insert(t, "FALSE", &no), "cannot define the boolean type");
  check(H5Tenum_insert(t, "TRUE", &yes), "cannot define the boolean type");
  return t;
}

// ---------------------------------------------------------------------------------------------
// Attributes and datasets.

namespace {

// Creates a scalar attribute of `file_type` and writes `value` (of `mem_type`) to it.
void write_scalar_attribute(hid_t obj, const std::string& name, hid_t file_type, hid_t mem_type,
                            const void* value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  Handle attr(H5Acreate2(obj, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute '" + name + "'");
  check(H5Awrite(attr, mem_type, value), "cannot write attribute '" + name + "'");
}

// A scalar dataset of `file_type` with `value` (of `mem_type`).
Handle create_scalar_dataset(hid_t group, const std::string& name, hid_t file_type, hid_t mem_type,
                             const void* value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  Handle dset(
      H5Dcreate2(group, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose, "cannot create dataset '" + name + "'");
  check(H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value),
        "cannot write dataset '" + name + "'");
  return dset;
}

// Reads a single value of an attribute (is_attribute) or dataset as a double: floating and
// integer types converted, booleans (an enum with members FALSE and TRUE) as 0 or 1.
double read_single_number(hid_t obj, bool is_attribute, const std::string& name) {
  Handle type(is_attribute ? H5Aget_type(obj) : H5Dget_type(obj), H5Tclose,
              "cannot get the type of '" + name + "'");
  Handle space(is_attribute ? H5Aget_space(obj) : H5Dget_space(obj), H5Sclose,
               "cannot get the dataspace of '" + name + "'");
  if (H5Sget_simple_extent_npoints(space) != 1)
    throw std::runtime_error("'" + name + "' is not a single value");
  const H5T_class_t cls = H5Tget_class(type);
  const auto read = [&](hid_t mem_type, void* buf) {
    const herr_t status = is_attribute ? H5Aread(obj, mem_type, buf)
                                       : H5Dread(obj, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
    check(status, "cannot read '" + name + "'");
  };
  if (cls == H5T_ENUM) {
    Handle b = bool_type();
    std::int8_t v = 0;
    read(b, &v);  // converted by member name: fails for an enum that is not a boolean
    return v != 0 ? 1.0 : 0.0;
  }
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw std::runtime_error("'" + name + "' is not a number");
  double v = 0.0;
  read(H5T_NATIVE_DOUBLE, &v);
  return v;
}

Handle open_attribute(hid_t obj, const std::string& name) {
  return Handle(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose,
                "cannot open attribute '" + name + "'");
}

}  // namespace

void write_string_attribute(hid_t obj, const std::string& name, const std::string& value) {
  Handle type = vlen_string_type();
  const char* ptr = value.c_str();
  write_scalar_attribute(obj, name, type, type, &ptr);
}

void write_string_array_attribute(hid_t obj, const std::string& name,
                                  const std::vector<std::string>& values) {
  Handle type = vlen_string_type();
  std::vector<const char*> ptr;
  for (const auto& v : values) ptr.push_back(v.c_str());
  const hsize_t n = ptr.size();
  Handle space(n > 0 ? H5Screate_simple(1, &n, nullptr) : H5Screate(H5S_NULL), H5Sclose,
               "cannot create a dataspace for attribute '" + name + "'");
  Handle attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "cannot create attribute '" + name + "'");
  if (n > 0) check(H5Awrite(attr, type, ptr.data()), "cannot write attribute '" + name + "'");
}

void write_double_attribute(hid_t obj, const std::string& name, double value) {
  write_scalar_attribute(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void write_int64_attribute(hid_t obj, const std::string& name, std::int64_t value) {
  write_scalar_attribute(obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void write_bool_attribute(hid_t obj, const std::string& name, bool value) {
  Handle type = bool_type();
  const std::int8_t v = value ? 1 : 0;
  write_scalar_attribute(obj, name, type, type, &v);
}

void describe(hid_t obj, const std::string& units, const std::string& description) {
  write_string_attribute(obj, "units", units);
  write_string_attribute(obj, "description", description);
}

void write_scalar_double(hid_t group, const std::string& name, double value,
                         const std::string& units, const std::string& description) {
  Handle d = create_scalar_dataset(group, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
  describe(d, units, description);
}

void write_scalar_int64(hid_t group, const std::string& name, std::int64_t value,
                        const std::string& units, const std::string& description) {
  Handle d = create_scalar_dataset(group, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
  describe(d, units, description);
}

void write_scalar_bool(hid_t group, const std::string& name, bool value,
                       const std::string& description) {
  Handle type = bool_type();
  const std::int8_t v = value ? 1 : 0;
  Handle d = create_scalar_dataset(group, name, type, type, &v);
  describe(d, "1", description);
}

double read_scalar_number(hid_t group, const std::string& name) {
  Handle d(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose,
           "cannot open dataset '" + name + "'");
  return read_single_number(d, false, name);
}

void write_double_array(hid_t group, const std::string& name, const std::vector<double>& values,
                        const std::vector<hsize_t>& dims, const std::string& units,
                        const std::string& description) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               "cannot create dataspace for '" + name + "'");
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "cannot create a link-creation property list");
  check(H5Pset_create_intermediate_group(lcpl, 1), "cannot set intermediate group creation");
  Handle d(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, lcpl, H5P_DEFAULT, H5P_DEFAULT),
           H5Dclose, "cannot create dataset '" + name + "'");
  if (!values.empty())
    check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "cannot write dataset '" + name + "'");
  describe(d, units, description);
}

Handle compressed_table_properties(int rank, const hsize_t* dims, std::size_t element_size,
                                   hsize_t chunk_rows, hsize_t chunk_columns) {
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose,
              "cannot create a dataset-creation property list");
  hsize_t row = 1;
  for (int k = 1; k < rank; ++k) row *= dims[k];
  if (dims[0] == 0 || row == 0) return dcpl;
  std::vector<hsize_t> chunk(dims, dims + rank);
  if (rank == 2) chunk[1] = std::clamp<hsize_t>(chunk_columns, 1, dims[1]);
  hsize_t chunk_row = 1;
  for (int k = 1; k < rank; ++k) chunk_row *= chunk[k];
  // Chunks of about 256 KiB: large enough for the filters, small enough that reading a few rows
  // does not inflate much.
  constexpr hsize_t kChunkBytes = hsize_t(1) << 18;
  chunk[0] = chunk_rows > 0
                 ? chunk_rows
                 : std::clamp<hsize_t>(kChunkBytes / (chunk_row * element_size), 1, dims[0]);
  check(H5Pset_chunk(dcpl, rank, chunk.data()), "cannot set the chunk size");
  if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    check(H5Pset_shuffle(dcpl), "cannot set the shuffle filter");
    check(H5Pset_deflate(dcpl, 1), "cannot set the deflate filter");
  }
  return dcpl;
}

void make_dimension_scale(hid_t scale, const std::string& name) {
  check(H5DSset_scale(scale, name.c_str()), "cannot make '" + name + "' a dimension scale");
}

void attach_dimension_scale(hid_t dataset, hid_t scale, unsigned dim) {
  check(H5DSattach_scale(dataset, scale, dim), "cannot attach a dimension scale");
  char name[256] = {};
  if (H5DSget_scale_name(scale, name, sizeof name) > 0)
    check(H5DSset_label(dataset, dim, name), "cannot label a dimension");
}

std::string read_string_attribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose,
              "cannot open attribute '" + name + "'");
  Handle file_type(H5Aget_type(attr), H5Tclose, "cannot get the type of attribute '" + name + "'");
  if (H5Tget_class(file_type) != H5T_STRING)
    throw std::runtime_error("attribute '" + name + "' is not a string");
  Handle space(H5Aget_space(attr), H5Sclose,
               "cannot get the dataspace of attribute '" + name + "'");
  if (H5Sget_simple_extent_npoints(space) != 1)
    throw std::runtime_error("attribute '" + name + "' is not a scalar string");

  const htri_t is_vlen = H5Tis_variable_str(file_type);
  if (is_vlen < 0) fail("cannot inspect the type of attribute '" + name + "'");
  if (is_vlen > 0) {
    Handle mem_type = vlen_string_type();
    // ASCII or UTF-8 as written (HDF5 converts between variable-length strings of one set only).
    check(H5Tset_cset(mem_type, H5Tget_cset(file_type)), "cannot set the string type's set");
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

std::vector<std::string> read_string_array_attribute(hid_t obj, const std::string& name) {
  Handle attr = open_attribute(obj, name);
  Handle file_type(H5Aget_type(attr), H5Tclose, "cannot get the type of attribute '" + name + "'");
  if (H5Tget_class(file_type) != H5T_STRING || H5Tis_variable_str(file_type) <= 0)
    throw std::runtime_error("attribute '" + name + "' is not of variable-length strings");
  Handle space(H5Aget_space(attr), H5Sclose,
               "cannot get the dataspace of attribute '" + name + "'");
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 0) fail("cannot get the size of attribute '" + name + "'");
  std::vector<std::string> out;
  if (n == 0) return out;
  Handle mem_type = vlen_string_type();
  check(H5Tset_cset(mem_type, H5Tget_cset(file_type)), "cannot set the string type's set");
  std::vector<char*> buf(static_cast<std::size_t>(n), nullptr);
  check(H5Aread(attr, mem_type, buf.data()), "cannot read attribute '" + name + "'");
  for (char* p : buf) {
    out.emplace_back(p != nullptr ? p : "");
    H5free_memory(p);
  }
  return out;
}

double read_double_attribute(hid_t obj, const std::string& name) {
  Handle attr = open_attribute(obj, name);
  return read_single_number(attr, true, "attribute '" + name + "'");
}

std::int64_t read_int64_attribute(hid_t obj, const std::string& name) {
  {
    Handle attr = open_attribute(obj, name);
    Handle type(H5Aget_type(attr), H5Tclose, "cannot get the type of attribute '" + name + "'");
    Handle space(H5Aget_space(attr), H5Sclose,
                 "cannot get the dataspace of attribute '" + name + "'");
    if (H5Tget_class(type) == H5T_INTEGER && H5Sget_simple_extent_npoints(space) == 1) {
      std::int64_t v = 0;
      check(H5Aread(attr, H5T_NATIVE_INT64, &v), "cannot read attribute '" + name + "'");
      return v;
    }
  }
  const double v = read_double_attribute(obj, name);
  // Counts are exact in a double up to 2^53, which files of earlier versions relied on.
  if (!(std::isfinite(v) && v == std::floor(v) && std::fabs(v) <= 9007199254740992.0))
    throw std::runtime_error("attribute '" + name + "' is not an integer");
  return static_cast<std::int64_t>(v);
}

bool read_bool_attribute(hid_t obj, const std::string& name) {
  return read_double_attribute(obj, name) != 0.0;
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

void fsync_file(const std::string& file) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd < 0)
    throw std::runtime_error(std::string("cannot open for fsync: ") + std::strerror(errno));
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

void write_atomically(const std::string& path, const std::string& who,
                      const std::function<void(const std::string& tmp)>& write) {
  const fs::path target(path);
  const std::string tmp = temporary_path(path);
  const auto failure = [&](const std::string& what) {
    return std::runtime_error(who + ": cannot write '" + path + "': " + what);
  };
  if (const std::string why = unsafe_output_reason(path); !why.empty()) throw failure(why);
  if (target.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    if (ec)
      throw failure("cannot create directory '" + target.parent_path().string() +
                    "': " + ec.message());
  }
  remove_stale_temporaries(path);
  SilenceHdf5Errors silence;
  const TemporaryFileGuard guard(tmp);
  try {
    write(tmp);
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

Handle open_read_only(const std::string& path) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a file-access property list");
  check(H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG), "cannot set the file close degree");
  return Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose, "cannot open the file");
}

}  // namespace lsi::hdf5
