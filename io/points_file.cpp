#include "io/points_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "io/hdf5_io.hpp"
#include "model/input_error.hpp"
#include "model/messages.hpp"

namespace lsi {
namespace {

const char* const kDefaultDataset = "points";
const char* const kColumnsAttribute = "columns";

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// A token as messages show it: quoted, at most 40 characters, control characters escaped.
std::string shown_token(std::string_view s) {
  std::string out = "\"";
  for (char c : s.substr(0, 40)) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '"' || c == '\\') {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned char>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + (s.size() > 40 ? "...\"" : "\"");
}

// The header's names: comma-separated, spaces around them and a pair of enclosing double quotes
// dropped. Every name must be non-empty and given once.
std::vector<std::string> column_names(std::string_view header, const std::string& where) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = header.find(',', start);
    std::string_view name = trimmed(header.substr(start, comma - start));
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
      name = name.substr(1, name.size() - 2);
    const std::string column = "column " + std::to_string(names.size() + 1);
    if (name.empty())
      fail(where + ": " + column +
           " has no name (the header names each column by its scene key, e.g. "
           "/landslide/velocity_m_s)");
    for (std::size_t k = 0; k < names.size(); ++k)
      if (names[k] == name)
        fail(where + ": " + column + " " + shown_token(name) + ": named twice (also column " +
             std::to_string(k + 1) + ")");
    names.emplace_back(name);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return names;
}

std::string column_label(const PointsTable& t, std::size_t c) { return "column " + t.columns[c]; }

double parse_value(std::string_view token, const PointsTable& t, std::size_t row, std::size_t c) {
  const std::string_view v = trimmed(token);
  const std::string at = t.shown + ": " + t.where(row) + ", " + column_label(t, c);
  if (v.empty()) fail(at + ": no value (every row gives a number in every column)");
  std::string_view digits = v;
  if (digits.front() == '+') digits.remove_prefix(1);
  double x = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
  if (ec == std::errc::result_out_of_range)
    fail(at + " = " + std::string(v) + ": must be finite (the number overflows a double)");
  if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty())
    fail(at + " = " + shown_token(v) + ": not a number");
  if (!std::isfinite(x)) fail(at + " = " + std::string(v) + ": must be a finite number");
  return x;
}

std::string read_text(const std::string& path, const std::string& shown) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(shown + ": cannot open the points file: " + std::strerror(errno));
  std::string text;
  char block[1 << 16];
  while (in.read(block, sizeof block).gcount() > 0)
    text.append(block, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) fail(shown + ": cannot read the points file");
  return text;
}

PointsTable read_csv(const std::string& path, const std::string& shown) {
  PointsTable t;
  t.shown = shown;
  t.text = true;
  std::string text = read_text(path, shown);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // a UTF-8 byte-order mark
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.emplace_back(text.data() + start, end - start);
    start = end + 1;
  }
  while (!lines.empty() && trimmed(lines.back()).empty()) lines.pop_back();  // trailing blanks
  if (lines.empty())
    fail(shown +
         ": empty (a points file's first line names its columns, e.g. "
         "/landslide/velocity_m_s,/barrier/base_friction, and each line after it gives a point)");
  t.columns = column_names(lines[0], shown + ": line 1");
  const std::size_t n = t.columns.size();
  t.rows = lines.size() - 1;
  if (t.rows == 0) fail(shown + ": no points after the header (at least one row is needed)");
  t.value.resize(t.rows * n);
  for (std::size_t r = 0; r < t.rows; ++r) {
    const std::string_view line = lines[r + 1];
    if (trimmed(line).empty())
      fail(shown + ": " + t.where(r) + " is empty (every row gives a number in every column)");
    const std::size_t count =
        1 + static_cast<std::size_t>(std::count(line.begin(), line.end(), ','));
    if (count != n)
      fail(shown + ": " + t.where(r) + " has " + std::to_string(count) +
           " values, the header names " + std::to_string(n) + " columns");
    std::size_t start = 0;
    for (std::size_t c = 0; c < n; ++c) {
      const std::size_t comma = line.find(',', start);
      t.value[r * n + c] = parse_value(line.substr(start, comma - start), t, r, c);
      start = comma + 1;
    }
  }
  return t;
}

PointsTable read_hdf5(const std::string& path, const std::string& shown,
                      const std::string& dataset) {
  PointsTable t;
  t.shown = shown;
  t.text = false;
  const std::string name = dataset.empty() ? kDefaultDataset : dataset;
  const std::string at = shown + ": dataset " + shown_token(name);
  try {
    hdf5::SilenceHdf5Errors quiet;
    const hdf5::Handle file = hdf5::open_read_only(path);
    if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
      fail(at + ": not in the file (points.dataset names the dataset of the points)");
    const hdf5::Handle ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open " + at);
    const hdf5::Handle type(H5Dget_type(ds), H5Tclose, "cannot get the type of " + at);
    const H5T_class_t kind = H5Tget_class(type);
    if (kind != H5T_FLOAT && kind != H5T_INTEGER)
      fail(at + ": not a matrix of numbers (a 2-D dataset of floats, a row per point)");
    const hdf5::Handle space(H5Dget_space(ds), H5Sclose, "cannot get the shape of " + at);
    if (H5Sget_simple_extent_ndims(space) != 2)
      fail(at + ": has " + std::to_string(H5Sget_simple_extent_ndims(space)) +
           " dimensions (allowed: 2, a row per point and a column per input)");
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(space, dims, nullptr);
    if (!hdf5::has_attribute(ds, kColumnsAttribute))
      fail(at +
           ": no attribute \"columns\" (a string naming the columns, comma-separated, e.g. "
           "\"/landslide/velocity_m_s,/barrier/base_friction\")");
    std::string header;
    try {
      header = hdf5::read_string_attribute(ds, kColumnsAttribute);
    } catch (const std::runtime_error& e) {  // not a string, or not one
      fail(at + ": attribute \"columns\": " + e.what() +
           " (allowed: one string naming the columns, comma-separated)");
    }
    t.columns = column_names(header, at + ", attribute \"columns\"");
    if (dims[1] != t.columns.size())
      fail(at + ": " + std::to_string(dims[1]) + " columns, its attribute \"columns\" names " +
           std::to_string(t.columns.size()));
    if (dims[0] == 0) fail(at + ": no rows (at least one point is needed)");
    t.rows = static_cast<std::size_t>(dims[0]);
    t.value.resize(t.rows * t.columns.size());
    hdf5::check(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.value.data()),
                "cannot read " + at);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {  // HDF5's failures
    fail(shown + ": cannot read the points: " + e.what());
  }
  const std::size_t n = t.columns.size();
  for (std::size_t k = 0; k < t.value.size(); ++k)
    if (!std::isfinite(t.value[k]))
      fail(shown + ": " + t.where(k / n) + ", " + column_label(t, k % n) + " = " +
           format_number(t.value[k]) + ": must be a finite number");
  return t;
}

}  // namespace

std::string PointsTable::where(std::size_t row) const {
  std::string w = "row " + std::to_string(row + 1);
  if (text) w += " (line " + std::to_string(row + 2) + ")";
  return w;
}

PointsTable read_points_file(const std::string& path, const std::string& shown,
                             const std::string& dataset) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(shown + ": points file not found");
  // A regular file only: a device or a pipe (/dev/zero) would be read without end.
  if (!fs::is_regular_file(path, ec)) fail(shown + ": not a regular file (a CSV or HDF5 file)");
  htri_t hdf5_file = 0;
  {
    hdf5::SilenceHdf5Errors quiet;
    hdf5_file = H5Fis_hdf5(path.c_str());
  }
  if (hdf5_file > 0) return read_hdf5(path, shown, dataset);
  if (!dataset.empty())
    fail(shown + ": points.dataset = " + shown_token(dataset) +
         ": a CSV file has no datasets (dataset names the points of an HDF5 file)");
  return read_csv(path, shown);
}

}  // namespace lsi
