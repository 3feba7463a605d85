// HDF5 plumbing; see hdf5_io.hpp.
#include "io/hdf5_io.hpp"
#include "io/output_paths.hpp"
#include "io/temporary_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
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
