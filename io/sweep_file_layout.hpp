// The parts of a sweep file's layout (io/sweep_file.hpp) that a file written as a whole and one
// written as its rows arrive (io/sweep_table_stream.hpp) share: the root attributes, the /samples
// datasets with their attributes, and /failures with /statistics.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/hdf5_io.hpp"
#include "io/sweep_file.hpp"

namespace lsi::sweep_layout {

// Creates (truncates) a sweep file, with strong close semantics.
hdf5::Handle create_file(const std::string& path);

// The root attributes of a sweep file of `rows` rows.
void write_header(hid_t file, const SweepHeader& header, std::uint64_t rows);

// One /samples dataset: its path, file and memory types, values per row and bytes per value.
struct SampleDataset {
  std::string name;
  hid_t file_type, mem_type;
  hsize_t columns;
  std::size_t element_size;
};
// The /samples datasets in file order: index, status, wall_time, inputs (a column per input),
// then one per output column.
std::vector<SampleDataset> sample_datasets(std::size_t inputs,
                                           const std::vector<std::string>& output_columns);

// The attributes of the /samples datasets (units, description, the inputs' paths) and group.
void describe_samples(hid_t file, const std::vector<std::string>& input_paths,
                      const std::vector<std::string>& output_columns);

// /failures/index, /failures/reason and, where given, /statistics.
void write_failures_and_statistics(hid_t file, const std::vector<std::uint64_t>& index,
                                   const std::vector<std::string>& reason,
                                   const nlohmann::json* statistics);

}  // namespace lsi::sweep_layout
