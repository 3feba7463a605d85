// A points file: the given samples of a study of design "points" (docs/reference/scene_schema.md,
// "Given points"). Either a CSV file whose first line names the columns, one point per line
// after it, or an HDF5 file with a 2-D dataset of numbers (a row per point) whose string
// attribute `columns` is that same header line. Only the file's form is checked here; what the
// columns and values mean is the study parser's (io/study_parser.cpp).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace lsi {

struct PointsTable {
  std::string shown;                 // the file as messages name it
  std::vector<std::string> columns;  // as the header names them
  std::vector<double> value;         // rows x columns, row-major
  std::size_t rows = 0;
  bool text = true;  // a CSV file: each row is a line (its header is line 1)

  // Where row `row` (0-based) is, for messages: "row 3 (line 4)" in a CSV file, "row 3" in HDF5
  // (rows count from 1).
  std::string where(std::size_t row) const;
};

// Reads `path` (`shown` in messages): HDF5 when the file starts with HDF5's signature, else CSV.
// `dataset` is the HDF5 dataset's name ("" for the default "points"); a CSV file takes none.
// Throws InputError, one line naming the file and, where it applies, the row (and line), the
// column and the value: a missing or unreadable file, an empty file, a header without a name or
// with a name twice, a row with more or fewer values than the header names columns, a value that
// is not a number or not finite (nan, inf, 1e999), no rows, a dataset that is not a 2-D matrix of
// numbers or whose `columns` do not match its width.
PointsTable read_points_file(const std::string& path, const std::string& shown,
                             const std::string& dataset);

}  // namespace lsi
