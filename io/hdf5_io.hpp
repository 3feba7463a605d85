// HDF5 plumbing shared by the result files (hdf5_results), the sweep tables (sweep_table) and
// the calibration file: HDF5 failures become exceptions with HDF5's own reason, handles close
// themselves, scalar attributes, and the atomic write (temporary file, fsync, rename).
#pragma once
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace lsi::hdf5 {

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
std::string error_detail();
// Throws std::runtime_error(what + " (HDF5: <detail>)").
[[noreturn]] void fail(const std::string& what);
void check(herr_t status, const std::string& what);

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

Handle vlen_string_type();
// Booleans are stored as h5py stores numpy's bool (which it reads back as bool): an enum of a
// signed 8-bit integer with the members FALSE = 0 and TRUE = 1.
Handle bool_type();
void write_string_attribute(hid_t obj, const std::string& name, const std::string& value);
// A 1-D attribute of variable-length UTF-8 strings (h5py reads it as an array of str).
void write_string_array_attribute(hid_t obj, const std::string& name,
                                  const std::vector<std::string>& values);
void write_double_attribute(hid_t obj, const std::string& name, double value);
void write_int64_attribute(hid_t obj, const std::string& name, std::int64_t value);
void write_bool_attribute(hid_t obj, const std::string& name, bool value);
std::string read_string_attribute(hid_t obj, const std::string& name);
std::vector<std::string> read_string_array_attribute(hid_t obj, const std::string& name);
// Numeric attributes of any integer or floating type, converted; booleans also from an enum
// (bool_type) and from a number (not 0: true), as files of earlier versions store them.
double read_double_attribute(hid_t obj, const std::string& name);
std::int64_t read_int64_attribute(hid_t obj, const std::string& name);
bool read_bool_attribute(hid_t obj, const std::string& name);
bool has_attribute(hid_t obj, const std::string& name);
bool has_link(hid_t group, const std::string& name);

// Self-describing datasets: every one carries the string attributes `units` ("1" for a pure
// number) and `description`.
void describe(hid_t obj, const std::string& units, const std::string& description);
// 0-d (scalar) datasets.
void write_scalar_double(hid_t group, const std::string& name, double value,
                         const std::string& units, const std::string& description);
void write_scalar_int64(hid_t group, const std::string& name, std::int64_t value,
                        const std::string& units, const std::string& description);
void write_scalar_bool(hid_t group, const std::string& name, bool value,
                       const std::string& description);
// A 0-d dataset's value as a double (floating, integer or boolean type).
double read_scalar_number(hid_t group, const std::string& name);
// A 1-D (dims = {n}) or 2-D (dims = {n, m}) dataset of doubles, described; `name` may be a
// path, whose missing groups are created.
void write_double_array(hid_t group, const std::string& name, const std::vector<double>& values,
                        const std::vector<hsize_t>& dims, const std::string& units,
                        const std::string& description);

// Dataset-creation properties for a table that may be large: chunked along its first dimension
// and compressed (shuffle, then deflate at level 1) where the library has deflate; the default
// (contiguous) layout for an empty dataset. A chunk of a 2-D table holds `chunk_columns` of its
// columns (one by default: the shuffle then puts each column's bytes in planes of their own,
// which compress as that column's numbers allow; a chunk across columns of different kinds
// mixes them), of `chunk_rows` rows where given (> 0), else of about 256 KiB.
Handle compressed_table_properties(int rank, const hsize_t* dims, std::size_t element_size,
                                   hsize_t chunk_rows = 0, hsize_t chunk_columns = 1);

// Dimension scales (HDF5's H5DS): makes `scale` a scale named `name`, and attaches it to
// dimension `dim` of `dataset`, labelling that dimension with the scale's name, so that h5py
// (`dataset.dims[dim][0]`, `dataset.dims[dim].label`) and netCDF-aware tools find the axis.
void make_dimension_scale(hid_t scale, const std::string& name);
void attach_dimension_scale(hid_t dataset, hid_t scale, unsigned dim);

void fsync_file(const std::string& file);
// Best effort: makes a rename durable. Failure is not an error (the file is complete).
void fsync_directory(const std::filesystem::path& dir);
// Removes a temporary file after a failure; leaves anything that is not a regular file alone.
void remove_temporary(const std::string& tmp) noexcept;

// Writes `path` atomically: `write(tmp)` creates the complete file at `<path>.tmp.<pid>` (same
// directory), which is then fsync'ed and renamed onto `path`; missing parent directories are
// created. On any failure the temporary file is removed, `path` is left as it was, and
// std::runtime_error("<who>: cannot write '<path>': <reason>") is thrown. HDF5's error printing
// is silenced meanwhile.
void write_atomically(const std::string& path, const std::string& who,
                      const std::function<void(const std::string& tmp)>& write);
// Opens an HDF5 file read-only with strong close semantics.
Handle open_read_only(const std::string& path);

}  // namespace lsi::hdf5
