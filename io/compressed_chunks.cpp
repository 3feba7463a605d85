// Parallel chunk compression; see compressed_chunks.hpp.
#include "io/compressed_chunks.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "io/hdf5_io.hpp"

namespace lsi::hdf5 {
namespace {

std::size_t compression_threads() {
  std::size_t n = std::max(1u, std::thread::hardware_concurrency());
  if (const char* env = std::getenv("OMP_NUM_THREADS")) {
    const long k = std::strtol(env, nullptr, 10);
    if (k > 0) n = static_cast<std::size_t>(k);
  }
  return n;
}

// One chunk as HDF5's pipeline makes it: the rows copied (the last chunk padded with zeros, the
// fill value, to the full chunk), the bytes shuffled (byte j of element i to j * count + i), then
// deflated (zlib format, as H5Z's deflate filter).
void compress_chunk(const unsigned char* rows, std::size_t bytes, std::size_t chunk_bytes,
                    std::size_t element_size, int level, std::vector<unsigned char>& plain,
                    std::vector<unsigned char>& out) {
  plain.assign(chunk_bytes, 0);
  const std::size_t count = chunk_bytes / element_size;
  for (std::size_t i = 0; i < bytes / element_size; ++i)
    for (std::size_t j = 0; j < element_size; ++j)
      plain[j * count + i] = rows[i * element_size + j];
  uLongf size = compressBound(static_cast<uLong>(chunk_bytes));
  out.resize(size);
  if (compress2(out.data(), &size, plain.data(), static_cast<uLong>(chunk_bytes), level) != Z_OK)
    throw std::runtime_error("zlib could not compress a chunk");
  out.resize(size);
}

}  // namespace

int shuffle_deflate_level(hid_t dcpl) {
  if (H5Pget_layout(dcpl) != H5D_CHUNKED || H5Pget_nfilters(dcpl) != 2) return -1;
  unsigned flags = 0, cd[8] = {};
  std::size_t n = 8;
  if (H5Pget_filter2(dcpl, 0, &flags, &n, cd, 0, nullptr, nullptr) != H5Z_FILTER_SHUFFLE) return -1;
  n = 8;
  if (H5Pget_filter2(dcpl, 1, &flags, &n, cd, 0, nullptr, nullptr) != H5Z_FILTER_DEFLATE || n < 1)
    return -1;
  return static_cast<int>(cd[0]);
}

std::vector<std::vector<unsigned char>> compress_chunks(const std::vector<ChunkRows>& chunks,
                                                        int level) {
  std::vector<std::vector<unsigned char>> out(chunks.size());
  if (chunks.empty()) return out;
  const std::size_t threads = std::min(compression_threads(), chunks.size());
  std::vector<std::string> errors(threads);
  auto work = [&](std::size_t t) {
    std::vector<unsigned char> plain;
    try {
      for (std::size_t c = t; c < chunks.size(); c += threads) {
        const ChunkRows& k = chunks[c];
        compress_chunk(static_cast<const unsigned char*>(k.rows), k.bytes, k.chunk_bytes,
                       k.element_size, level, plain, out[c]);
      }
    } catch (const std::exception& e) {
      errors[t] = e.what();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (const auto& e : errors)
    if (!e.empty()) throw std::runtime_error(e);
  return out;
}

bool write_compressed_chunks(hid_t dataset, hid_t dcpl, const void* data, std::size_t rows,
                             std::size_t row_elements, std::size_t element_size) {
  const int level = shuffle_deflate_level(dcpl);
  if (level < 0 || rows == 0) return false;
  hsize_t chunk_dims[2] = {0, 0};
  const int rank = H5Pget_chunk(dcpl, 2, chunk_dims);
  if (rank < 1 || rank > 2 || (rank == 2 && chunk_dims[1] != row_elements)) return false;
  const std::size_t chunk_rows = chunk_dims[0];
  const std::size_t row_bytes = row_elements * element_size;
  const std::size_t chunk_bytes = chunk_rows * row_bytes;
  const std::size_t chunks = (rows + chunk_rows - 1) / chunk_rows;
  const auto* bytes = static_cast<const unsigned char*>(data);
  // Batches of a few chunks per thread: compressed in parallel, then written in order, so that
  // only a batch of compressed chunks is held at a time.
  const std::size_t batch = 8 * compression_threads();
  for (std::size_t first = 0; first < chunks; first += batch) {
    const std::size_t last = std::min(chunks, first + batch);
    std::vector<ChunkRows> rows_of;
    for (std::size_t c = first; c < last; ++c) {
      const std::size_t begin = c * chunk_rows, end = std::min(rows, begin + chunk_rows);
      rows_of.push_back(
          {bytes + begin * row_bytes, (end - begin) * row_bytes, chunk_bytes, element_size});
    }
    const auto out = compress_chunks(rows_of, level);
    for (std::size_t c = first; c < last; ++c) {
      const hsize_t offset[2] = {static_cast<hsize_t>(c * chunk_rows), 0};
      check(H5Dwrite_chunk(dataset, H5P_DEFAULT, 0, offset, out[c - first].size(),
                           out[c - first].data()),
            "cannot write a compressed chunk");
    }
  }
  return true;
}

}  // namespace lsi::hdf5
