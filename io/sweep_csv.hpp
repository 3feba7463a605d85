// A sweep's per-sample table as CSV (`lsi sweep --table-csv FILE`), for tools that read text:
// one row per sample in sample order (for given points, the order of the points file), the
// columns
//   index,<input path>...,<method>/<output>...,status
// index the sample index, the inputs and outputs in their shortest form that reads back to the
// same double (nan where a sample has no value), status as in the HDF5 file (0 ok, 1 invalid
// input, 2 MPM unstable, 3 failed, 4 MPM cut short).
#pragma once
#include <string>

#include "model/sweep_table.hpp"

namespace lsi {

// Writes atomically (io/text_file.hpp); throws std::runtime_error when it cannot.
void write_sweep_table_csv(const std::string& path, const SweepTable& table);

}  // namespace lsi
