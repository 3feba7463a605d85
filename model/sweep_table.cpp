#include "model/sweep_table.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "sweeps/huge_pages.hpp"

namespace lsi {

const char* describe(SampleStatus s) {
  switch (s) {
    case SampleStatus::ok:
      return "ok";
    case SampleStatus::invalid_input:
      return "invalid input";
    case SampleStatus::unstable:
      return "MPM unstable";
    case SampleStatus::failed:
      return "failed";
    case SampleStatus::truncated:
      return "MPM cut short";
  }
  return "unknown";
}

SweepTable SweepTable::with_columns(std::vector<std::string> input_paths,
                                    std::vector<std::string> output_columns) {
  SweepTable t;
  t.inputs.resize(input_paths.size());
  t.outputs.resize(output_columns.size());
  t.input_paths = std::move(input_paths);
  t.output_columns = std::move(output_columns);
  return t;
}

void SweepTable::append(const SweepTable& o) {
  append_results(o);
  index.insert(index.end(), o.index.begin(), o.index.end());
  wall_time.insert(wall_time.end(), o.wall_time.begin(), o.wall_time.end());
  for (std::size_t k = 0; k < inputs.size(); ++k)
    inputs[k].insert(inputs[k].end(), o.inputs[k].begin(), o.inputs[k].end());
}

void SweepTable::append_results(const SweepTable& o) {
  if (o.input_paths != input_paths || o.output_columns != output_columns)
    throw std::invalid_argument("sweep tables with different columns cannot be joined");
  status.insert(status.end(), o.status.begin(), o.status.end());
  for (std::size_t c = 0; c < outputs.size(); ++c)
    outputs[c].insert(outputs[c].end(), o.outputs[c].begin(), o.outputs[c].end());
  failure_index.insert(failure_index.end(), o.failure_index.begin(), o.failure_index.end());
  failure_reason.insert(failure_reason.end(), o.failure_reason.begin(), o.failure_reason.end());
}

void SweepTable::reserve(std::size_t n) {
  reserve_results(n);
  sweeps::reserve_on_huge_pages(index, n);
  sweeps::reserve_on_huge_pages(wall_time, n);
  for (auto& c : inputs) sweeps::reserve_on_huge_pages(c, n);
}

void SweepTable::reserve_results(std::size_t n) {
  sweeps::reserve_on_huge_pages(status, n);
  for (auto& c : outputs) sweeps::reserve_on_huge_pages(c, n);
}

void SweepTable::sort_by_index() {
  const std::size_t n = index.size();  // 0 where the index was left out
  if (!std::is_sorted(index.begin(), index.end())) {
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return index[a] < index[b]; });
    auto permute = [&](auto& v) {
      if (v.empty()) return;  // a column left out (append_results)
      auto copy = v;
      for (std::size_t i = 0; i < n; ++i) v[i] = copy[order[i]];
    };
    permute(index);
    permute(status);
    permute(wall_time);
    for (auto& c : inputs) permute(c);
    for (auto& c : outputs) permute(c);
  }
  for (std::size_t i = 1; i < n; ++i)
    if (index[i] == index[i - 1])
      throw std::runtime_error("sample " + std::to_string(index[i]) + " appears twice");
  std::vector<std::size_t> f(failure_index.size());
  std::iota(f.begin(), f.end(), 0);
  std::sort(f.begin(), f.end(),
            [&](std::size_t a, std::size_t b) { return failure_index[a] < failure_index[b]; });
  std::vector<std::uint64_t> fi;
  std::vector<std::string> fr;
  for (std::size_t k : f) {
    fi.push_back(failure_index[k]);
    fr.push_back(std::move(failure_reason[k]));
  }
  failure_index = std::move(fi);
  failure_reason = std::move(fr);
}

}  // namespace lsi
