// A sweep result file written as its rows arrive; see sweep_table_stream.hpp.
#include "io/sweep_table_stream.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "io/compressed_chunks.hpp"
#include "sweeps/huge_pages.hpp"

namespace lsi {

using namespace hdf5;

namespace {

// Rows [from, to) of `t` (no failures).
SweepTable rows_of(const SweepTable& t, std::uint64_t from, std::uint64_t to) {
  SweepTable s = SweepTable::with_columns(t.input_paths, t.output_columns);
  auto take = [&](auto& into, const auto& v) { into.assign(v.begin() + from, v.begin() + to); };
  take(s.index, t.index);
  take(s.status, t.status);
  take(s.wall_time, t.wall_time);
  for (std::size_t k = 0; k < t.inputs.size(); ++k) take(s.inputs[k], t.inputs[k]);
  for (std::size_t c = 0; c < t.outputs.size(); ++c) take(s.outputs[c], t.outputs[c]);
  return s;
}

}  // namespace

std::uint64_t SweepTableStream::chunk_rows_for(std::size_t inputs, std::uint64_t rows,
                                               std::uint64_t rows_at_once) {
  constexpr std::uint64_t kChunkBytes = std::uint64_t(1) << 18,
                          kLargestChunkBytes = kChunkBytes << 2;
  const std::uint64_t widest = 8 * std::max<std::uint64_t>(inputs, 1);
  std::uint64_t r = 1;
  while (2 * r * widest <= kChunkBytes) r *= 2;
  while (2 * r * widest <= kLargestChunkBytes && r < rows_at_once) r *= 2;
  return std::max<std::uint64_t>(1, std::min(r, rows));
}

SweepTableStream::SweepTableStream(const std::string& path, std::vector<std::string> input_paths,
                                   std::vector<std::string> output_columns, std::uint64_t rows,
                                   std::uint64_t chunk_rows, bool whole_input_rows)
    : path_(path),
      input_paths_(std::move(input_paths)),
      output_columns_(std::move(output_columns)),
      layout_(sweep_layout::sample_datasets(input_paths_.size(), output_columns_)),
      planned_rows_(rows),
      chunk_rows_(chunk_rows),
      whole_input_rows_(whole_input_rows),
      pending_(SweepTable::with_columns(input_paths_, output_columns_)) {
  if (rows == 0 || chunk_rows == 0 || input_paths_.empty())
    throw std::invalid_argument("SweepTableStream: no rows, no chunk rows or no inputs");
  file_ = sweep_layout::create_file(path);
  addresses_ = std::make_unique<hdf5::WrittenChunkAddress>(path);
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "cannot create a link-creation property list");
  check(H5Pset_create_intermediate_group(lcpl, 1), "cannot set intermediate group creation");
  for (const auto& d : layout_) {
    const int rank = d.name == "/samples/inputs" ? 2 : 1;
    const hsize_t dims[2] = {rows, d.columns};
    const hsize_t most[2] = {H5S_UNLIMITED, d.columns};
    Handle space(H5Screate_simple(rank, dims, most), H5Sclose,
                 "cannot create the dataspace of '" + d.name + "'");
    Handle dcpl = compressed_table_properties(rank, dims, d.element_size, chunk_rows,
                                              whole_input_rows ? d.columns : 1);
    const int level = shuffle_deflate_level(dcpl);
    if (level < 0)
      throw std::runtime_error(path + ": '" + d.name +
                               "': this HDF5 library has no deflate filter to compress the table");
    if (!compression_) compression_ = std::make_unique<hdf5::ChunkCompression>(level);
    datasets_.emplace_back(
        H5Dcreate2(file_, d.name.c_str(), d.file_type, space, lcpl, dcpl, H5P_DEFAULT), H5Dclose,
        "cannot create dataset '" + d.name + "'");
  }
}

std::vector<StoredChunk> SweepTableStream::write_chunks(const SweepTable& t, std::uint64_t rows) {
  std::vector<StoredChunk> stored;
  if (rows == 0) return stored;
  // Each dataset's columns as its chunks hold them (sweep_layout::sample_datasets' order): a
  // column each, or the inputs' whole rows (row by row, as the file holds them).
  std::vector<std::vector<const void*>> columns = {
      {t.index.data()}, {t.status.data()}, {t.wall_time.data()}, {}};
  for (const auto& c : t.inputs) columns[3].push_back(c.data());
  if (whole_input_rows_) {
    const std::size_t d = input_paths_.size();
    std::vector<double>& inputs = row_major_inputs_;
    sweeps::reserve_on_huge_pages(inputs, rows * d);
    inputs.resize(rows * d);
    for (std::size_t k = 0; k < d; ++k)
      for (std::uint64_t i = 0; i < rows; ++i) inputs[i * d + k] = t.inputs[k][i];
    columns[3] = {inputs.data()};
  }
  for (const auto& c : t.outputs) columns.push_back({c.data()});
  std::vector<ChunkRows> chunks;
  for (std::size_t s = 0; s < layout_.size(); ++s) {
    const bool whole_rows = layout_[s].name == "/samples/inputs" && whole_input_rows_;
    const std::size_t row_bytes = (whole_rows ? layout_[s].columns : 1) * layout_[s].element_size;
    for (std::size_t col = 0; col < columns[s].size(); ++col) {
      const auto* bytes = static_cast<const unsigned char*>(columns[s][col]);
      for (std::uint64_t begin = 0; begin < rows; begin += chunk_rows_) {
        const std::uint64_t end = std::min(rows, begin + chunk_rows_);
        chunks.push_back({bytes + begin * row_bytes, (end - begin) * row_bytes,
                          chunk_rows_ * row_bytes, layout_[s].element_size,
                          floating_type(layout_[s].file_type)});
        stored.push_back({s, (stored_rows_ + begin) / chunk_rows_, 0, 0, col});
      }
    }
  }
  compression_->compress_each(chunks,
                              [&](std::size_t c, const unsigned char* bytes, std::size_t size) {
                                write_chunk(stored[c], bytes, size);
                              });
  return stored;
}

void SweepTableStream::write_chunk(StoredChunk& k, const void* bytes, const std::size_t size) {
  const hsize_t offset[2] = {k.chunk * chunk_rows_, k.column};
  const hid_t ds = datasets_[k.dataset];
  addresses_->before_write(file_);
  check(H5Dwrite_chunk(ds, H5P_DEFAULT, 0, offset, size, bytes),
        path_ + ": cannot write a chunk of '" + layout_[k.dataset].name + "'");
  k.address = addresses_->after_write(ds, offset, bytes, size);
  k.size = size;
}

std::vector<StoredChunk> SweepTableStream::append(const SweepTable& rows) {
  const bool direct = pending_.rows() == 0;
  if (!direct) pending_.append(rows);
  const SweepTable& source = direct ? rows : pending_;
  const std::uint64_t whole = source.rows() / chunk_rows_ * chunk_rows_;
  std::vector<StoredChunk> stored = write_chunks(source, whole);
  stored_rows_ += whole;
  pending_ = rows_of(source, whole, source.rows());
  return stored;
}

std::vector<StoredChunk> SweepTableStream::adopt(const std::string& from,
                                                 const std::vector<StoredChunk>& chunks) {
  std::ifstream in(from, std::ios::binary);
  if (!in) throw std::runtime_error(from + ": cannot open (the table of an earlier run)");
  std::vector<StoredChunk> stored;
  std::vector<char> bytes;
  for (const StoredChunk& k : chunks) {
    if (k.dataset >= datasets_.size())
      throw std::runtime_error(from + ": a chunk of dataset " + std::to_string(k.dataset) +
                               ", the table has " + std::to_string(datasets_.size()));
    const std::uint64_t chunk_columns =
        layout_[k.dataset].name == "/samples/inputs" && !whole_input_rows_
            ? layout_[k.dataset].columns
            : 1;
    if (k.column >= chunk_columns)
      throw std::runtime_error(from + ": a chunk of dataset " + std::to_string(k.dataset) +
                               " at column " + std::to_string(k.column) + ", its chunks have " +
                               std::to_string(chunk_columns) + " column(s)");
    bytes.resize(k.size);
    in.seekg(static_cast<std::streamoff>(k.address));
    if (!in.read(bytes.data(), static_cast<std::streamsize>(k.size)))
      throw std::runtime_error(from + ": lacks the chunk of " + std::to_string(k.size) +
                               " bytes at byte " + std::to_string(k.address) +
                               " (the file was cut short or replaced)");
    StoredChunk now = k;
    write_chunk(now, bytes.data(), bytes.size());
    stored.push_back(now);
  }
  return stored;
}

void SweepTableStream::restore(std::uint64_t stored_rows, SweepTable pending) {
  if (stored_rows % chunk_rows_ != 0 || pending.rows() >= chunk_rows_ ||
      stored_rows + pending.rows() > planned_rows_)
    throw std::runtime_error(path_ + ": " + std::to_string(stored_rows) + " rows in chunks of " +
                             std::to_string(chunk_rows_) + " and " +
                             std::to_string(pending.rows()) + " after them do not fit the " +
                             std::to_string(planned_rows_) + " rows planned");
  stored_rows_ = stored_rows;
  pending_ = rows_of(pending, 0, pending.rows());
}

SweepTable SweepTableStream::read_stored() const {
  SweepTable t = SweepTable::with_columns(input_paths_, output_columns_);
  const std::uint64_t n = stored_rows_;
  const std::size_t d = input_paths_.size();
  std::vector<double> inputs(n * d);
  t.index.resize(n);
  t.status.resize(n);
  t.wall_time.resize(n);
  for (auto& c : t.outputs) c.resize(n);
  std::vector<void*> data = {t.index.data(), t.status.data(), t.wall_time.data(), inputs.data()};
  for (auto& c : t.outputs) data.push_back(c.data());
  if (n > 0)
    for (std::size_t s = 0; s < layout_.size(); ++s) {
      const hsize_t start[2] = {0, 0}, count[2] = {n, layout_[s].columns};
      const int rank = s == 3 ? 2 : 1;
      Handle file_space(H5Dget_space(datasets_[s]), H5Sclose, "cannot get a dataspace");
      check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr),
            "cannot select rows");
      Handle memory(H5Screate_simple(rank, count, nullptr), H5Sclose, "cannot create a dataspace");
      check(H5Dread(datasets_[s], layout_[s].mem_type, memory, file_space, H5P_DEFAULT, data[s]),
            path_ + ": cannot read back '" + layout_[s].name + "'");
    }
  for (std::size_t k = 0; k < d; ++k) {
    t.inputs[k].resize(n);
    for (std::uint64_t i = 0; i < n; ++i) t.inputs[k][i] = inputs[i * d + k];
  }
  return t;
}

void SweepTableStream::finish(const SweepHeader& header,
                              const std::vector<std::uint64_t>& failure_index,
                              const std::vector<std::string>& failure_reason,
                              const nlohmann::json* statistics) {
  const std::uint64_t n = rows();
  if (n != planned_rows_)
    for (std::size_t s = 0; s < layout_.size(); ++s) {
      const hsize_t dims[2] = {n, layout_[s].columns};
      check(H5Dset_extent(datasets_[s], dims),
            path_ + ": cannot end '" + layout_[s].name + "' at " + std::to_string(n) + " rows");
    }
  write_chunks(pending_, pending_.rows());
  sweep_layout::write_header(file_, header, n);
  sweep_layout::describe_samples(file_, input_paths_, output_columns_);
  sweep_layout::write_failures_and_statistics(file_, failure_index, failure_reason, statistics);
  datasets_.clear();
  check(H5Fflush(file_, H5F_SCOPE_GLOBAL), path_ + ": cannot flush the file");
  file_.close(path_ + ": cannot close the file");
}

}  // namespace lsi
