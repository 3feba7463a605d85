// The per-sample table of a sweep: sample index, status, wall time, the inputs and one column
// per method and output (io/sweep_file.hpp writes and reads it).
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lsi {

// truncated: an MPM run that reached its end time with the barrier still sliding (or at the end
// of the domain): its final displacement is not known (NaN), the sample is not an ok one.
enum class SampleStatus : std::int8_t {
  ok = 0,
  invalid_input = 1,
  unstable = 2,
  failed = 3,
  truncated = 4
};
const char* describe(SampleStatus s);

struct SweepTable {
  std::vector<std::string> input_paths;
  std::vector<std::string> output_columns;  // "<method>/<output>"
  std::vector<std::uint64_t> index;
  std::vector<std::int8_t> status;
  std::vector<float> wall_time;
  std::vector<std::vector<double>> inputs;   // [input][row]
  std::vector<std::vector<double>> outputs;  // [column][row]
  std::vector<std::uint64_t> failure_index;
  std::vector<std::string> failure_reason;

  // Every table has a status per row; the index, wall times and inputs may be left out
  // (append_results).
  std::size_t rows() const { return status.size(); }
  // An empty table with these columns.
  static SweepTable with_columns(std::vector<std::string> input_paths,
                                 std::vector<std::string> output_columns);
  // Appends `other`'s rows (same columns, else std::invalid_argument).
  void append(const SweepTable& other);
  // The statuses and outputs alone, the index, inputs and wall times left empty: a sweep's
  // table for its statistics (they read the statuses and outputs), the rows in the order
  // appended.
  void append_results(const SweepTable& other);
  void reserve(std::size_t rows);
  // The same for the columns append_results fills (the statuses and outputs) alone.
  void reserve_results(std::size_t rows);
  // Sorts the rows (and failures) by sample index (empty columns stay empty; a table without
  // its index keeps its rows' order); throws std::runtime_error on a duplicate.
  void sort_by_index();
};

}  // namespace lsi
