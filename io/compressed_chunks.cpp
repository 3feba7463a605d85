// Parallel chunk compression; see compressed_chunks.hpp.
#include "io/compressed_chunks.hpp"

#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "io/deflate_planes.hpp"
#include "io/hdf5_io.hpp"
#include "model/host_threads.hpp"

namespace lsi::hdf5 {
namespace {

// Byte j of element i to j * count + i (HDF5's shuffle filter), for the first n elements: a
// block of 64 elements at a time transposed into a local block, each of its planes then copied
// whole (a form the compiler vectorises with byte shuffles; the bytes scattered one at a time
// took 4 to 10 times as long).
template <std::size_t E>
void shuffle_fixed(const unsigned char* rows, std::size_t n, std::size_t count,
                   unsigned char* plain) {
  constexpr std::size_t B = 64;
  std::size_t i = 0;
  for (; i + B <= n; i += B) {
    unsigned char block[E][B];
    const unsigned char* r = rows + i * E;
    for (std::size_t b = 0; b < B; ++b)
      for (std::size_t j = 0; j < E; ++j) block[j][b] = r[b * E + j];
    for (std::size_t j = 0; j < E; ++j) std::memcpy(plain + j * count + i, block[j], B);
  }
  for (; i < n; ++i)
    for (std::size_t j = 0; j < E; ++j) plain[j * count + i] = rows[i * E + j];
}

void shuffle(const unsigned char* rows, std::size_t n, std::size_t count, std::size_t size,
             unsigned char* plain) {
  switch (size) {
    case 1:
      return shuffle_fixed<1>(rows, n, count, plain);
    case 2:
      return shuffle_fixed<2>(rows, n, count, plain);
    case 4:
      return shuffle_fixed<4>(rows, n, count, plain);
    case 8:
      return shuffle_fixed<8>(rows, n, count, plain);
    default:
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < size; ++j) plain[j * count + i] = rows[i * size + j];
  }
}

// How a byte plane of a floating-point column may be coded (deflate_planes.hpp), from the
// order-0 entropy h of every fourth byte: stored above 7.5 bits, where a Huffman code would save
// at most 6 % of its size and cost more time than the rest of the chunk's compression (random
// bytes read about 7.8 bits on a sample of a thousand); a Huffman code above 4 bits, where runs
// are rare; runs below (the sign and exponent bytes of a column of numbers). The sampled
// histogram is the cheap test that spares the random planes a histogram and a code:
// h = log2(N) - sum(c log2 c) / N over the N sampled bytes and their counts c, c log2 c from a
// table for the counts of planes up to 32 KiB (a call to log2 per count cost more than the
// sampling). The sampled bytes go into four tallies in turn, added at the end: a plane of one
// byte (a run) would otherwise make each count wait for the one before it.
PlaneCoding plane_coding(const unsigned char* bytes, std::size_t n) {
  constexpr std::size_t stride = 4, tabulated = 8192;
  static const std::vector<double> c_log2_c = [] {
    std::vector<double> t(tabulated + 1, 0.0);
    for (std::size_t c = 1; c <= tabulated; ++c) t[c] = double(c) * std::log2(double(c));
    return t;
  }();
  std::uint32_t tally[4][256] = {};
  std::size_t i = 0;
  for (; i + 3 * stride < n; i += 4 * stride) {
    ++tally[0][bytes[i]];
    ++tally[1][bytes[i + stride]];
    ++tally[2][bytes[i + 2 * stride]];
    ++tally[3][bytes[i + 3 * stride]];
  }
  for (; i < n; i += stride) ++tally[0][bytes[i]];
  const std::size_t sampled = (n + stride - 1) / stride;
  double sum = 0.0;
  for (std::size_t b = 0; b < 256; ++b) {
    const std::uint32_t c = tally[0][b] + tally[1][b] + tally[2][b] + tally[3][b];
    sum += c <= tabulated ? c_log2_c[c] : double(c) * std::log2(double(c));
  }
  const double h = std::log2(double(sampled)) - sum / double(sampled);
  return h > 7.5 ? PlaneCoding::stored : h > 4.0 ? PlaneCoding::huffman : PlaneCoding::runs;
}

// A compressed chunk: its bytes the first `size` of `bytes` (a buffer kept from chunk to chunk).
struct CompressedChunk {
  std::vector<unsigned char> bytes;
  std::size_t size = 0;
};

// One thread's compressor: its buffers, its zlib stream (integer chunks) and its plane deflater
// (floating-point chunks), kept from chunk to chunk.
class ChunkCompressor {
 public:
  explicit ChunkCompressor(int level) : level_(level) {}
  ChunkCompressor(const ChunkCompressor&) = delete;
  ChunkCompressor& operator=(const ChunkCompressor&) = delete;
  ~ChunkCompressor() {
    if (stream_.started) deflateEnd(&stream_.z);
  }

  // One chunk as HDF5's pipeline makes it, into out.bytes (grown to the worst case where it is
  // smaller, never shrunk; out.size its compressed bytes): the rows copied (the last chunk padded
  // with zeros, the fill value, to the full chunk), the bytes shuffled, then deflated (zlib
  // format, as H5Z's deflate filter) as the chunk's numbers call for (compressed_chunks.hpp).
  void compress(const ChunkRows& k, CompressedChunk& out) {
    const std::size_t count = k.chunk_bytes / k.element_size;
    const std::size_t n = k.bytes / k.element_size;
    plain_.resize(k.chunk_bytes);
    for (std::size_t j = 0; j < k.element_size; ++j)  // the padding
      std::fill(plain_.begin() + j * count + n, plain_.begin() + (j + 1) * count, 0);
    shuffle(static_cast<const unsigned char*>(k.rows), n, count, k.element_size, plain_.data());
    if (k.floating) {
      // Byte plane by byte plane (plane_coding), in blocks lsi writes itself (deflate_planes.hpp).
      const std::size_t planes = k.element_size;
      coding_.resize(planes);
      for (std::size_t j = 0; j < planes; ++j)
        coding_[j] = plane_coding(plain_.data() + j * count, count);
      const std::size_t bound = PlaneDeflater::bound(count, planes);
      if (out.bytes.size() < bound) out.bytes.resize(bound);
      out.size = planes_.deflate(plain_.data(), count, planes, coding_.data(), out.bytes.data());
      return;
    }
    Stream& s = stream_;
    if (!s.started) {
      if (deflateInit2(&s.z, level_, Z_DEFLATED, 15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw std::runtime_error("zlib could not start compressing a chunk");
      s.started = true;
    } else if (deflateReset(&s.z) != Z_OK) {
      throw std::runtime_error("zlib could not start compressing a chunk");
    }
    // Room for deflate's bound.
    const std::size_t bound = deflateBound(&s.z, static_cast<uLong>(k.chunk_bytes));
    if (out.bytes.size() < bound) out.bytes.resize(bound);
    s.z.next_out = out.bytes.data();
    s.z.avail_out = static_cast<uInt>(bound);
    s.z.next_in = plain_.data();
    s.z.avail_in = static_cast<uInt>(k.chunk_bytes);
    if (deflate(&s.z, Z_FINISH) != Z_STREAM_END)
      throw std::runtime_error("zlib could not compress a chunk");
    out.size = s.z.total_out;
  }

 private:
  struct Stream {
    z_stream z{};
    bool started = false;
  };
  int level_;
  Stream stream_;         // integer chunks
  PlaneDeflater planes_;  // floating-point chunks
  std::vector<unsigned char> plain_;
  std::vector<PlaneCoding> coding_;  // how each byte plane of the chunk is coded
};

}  // namespace

struct ChunkCompression::Threads {
  std::vector<std::unique_ptr<ChunkCompressor>> compressors;
  std::vector<CompressedChunk> ring;  // the compressed chunks in flight
};

ChunkCompression::ChunkCompression(int level) : level_(level), threads_(new Threads) {}
ChunkCompression::~ChunkCompression() = default;

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

bool floating_type(hid_t type) { return H5Tget_class(type) == H5T_FLOAT; }

const std::vector<std::vector<unsigned char>>& ChunkCompression::compress(
    const std::vector<ChunkRows>& chunks) {
  out_.resize(chunks.size());
  compress_each(chunks, [&](std::size_t c, const unsigned char* bytes, std::size_t size) {
    out_[c].assign(bytes, bytes + size);
  });
  return out_;
}

void ChunkCompression::compress_each(
    const std::vector<ChunkRows>& chunks,
    const std::function<void(std::size_t, const unsigned char*, std::size_t)>& ready) {
  const std::size_t n = chunks.size();
  if (n == 0) return;
  const std::size_t threads = std::min(host_thread_count(), n);
  auto& compressors = threads_->compressors;
  while (compressors.size() < threads)
    compressors.push_back(std::make_unique<ChunkCompressor>(level_));
  // Chunk c is compressed into slot c % slots of a ring, once chunk c - slots has been handed
  // over: a few chunks a thread in flight, their buffers kept from call to call.
  const std::size_t slots = 4 * threads;
  auto& ring = threads_->ring;
  if (ring.size() < slots) ring.resize(slots);
  // Each chunk's state: 0 not compressed yet, 1 compressed, 2 failed. The chunks are taken in
  // order, so that the ones before a failed one are all taken, and finish.
  const std::unique_ptr<std::atomic<int>[]> state(new std::atomic<int>[n]);
  for (std::size_t c = 0; c < n; ++c) state[c].store(0, std::memory_order_relaxed);
  std::atomic<std::size_t> next{0}, handed{0};
  std::atomic<bool> stop{false};
  std::vector<std::exception_ptr> errors(threads);
  auto compress = [&](std::size_t t, std::size_t c) {
    try {
      compressors[t]->compress(chunks[c], ring[c % slots]);
      state[c].store(1, std::memory_order_release);
    } catch (...) {  // marked failed first: the thread handing the chunks over stops there
      state[c].store(2, std::memory_order_release);
      stop = true;
      errors[t] = std::current_exception();
    }
  };
  // The calling thread (t = 0) hands over each chunk as soon as it and those before it are
  // compressed, and compresses the next chunk when none is ready and its slot is free (it never
  // waits for a slot: only it frees them); the others take the next chunk and wait for its slot.
  std::exception_ptr failure;
  on_host_threads(threads, [&](std::size_t t) {
    if (t != 0) {
      while (!stop.load(std::memory_order_relaxed)) {
        const std::size_t c = next.fetch_add(1);
        if (c >= n) return;
        while (c >= handed.load(std::memory_order_acquire) + slots) {
          if (stop.load(std::memory_order_relaxed)) {
            // Left uncompressed: marked failed, so that the thread handing the chunks over
            // stops there instead of waiting for it.
            state[c].store(2, std::memory_order_release);
            return;
          }
          std::this_thread::yield();
        }
        compress(t, c);
      }
      return;
    }
    try {
      for (std::size_t written = 0; written < n;) {
        const int s = state[written].load(std::memory_order_acquire);
        if (s == 1) {
          const CompressedChunk& k = ring[written % slots];
          ready(written, k.bytes.data(), k.size);
          handed.store(++written, std::memory_order_release);
          continue;
        }
        if (s == 2) break;
        std::size_t c = next.load(std::memory_order_relaxed);
        if (c < n && c < written + slots && next.compare_exchange_strong(c, c + 1))
          compress(0, c);
        else
          std::this_thread::yield();  // the chunk is another thread's, still being compressed
      }
    } catch (...) {
      failure = std::current_exception();
    }
    stop = true;
  });
  if (failure) std::rethrow_exception(failure);
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

bool write_compressed_chunks(hid_t dataset, hid_t dcpl, const std::vector<const void*>& columns,
                             std::size_t rows, std::size_t element_size) {
  const int level = shuffle_deflate_level(dcpl);
  if (level < 0 || rows == 0 || columns.empty()) return false;
  hsize_t chunk_dims[2] = {0, 0};
  const int rank = H5Pget_chunk(dcpl, 2, chunk_dims);
  if (rank < 1 || rank > 2 || (rank == 1 && columns.size() != 1) ||
      (rank == 2 && chunk_dims[1] != 1))
    return false;
  const std::size_t chunk_rows = chunk_dims[0];
  const std::size_t chunk_bytes = chunk_rows * element_size;
  const std::size_t chunks = (rows + chunk_rows - 1) / chunk_rows;
  const Handle type(H5Dget_type(dataset), H5Tclose, "cannot get the type of a dataset");
  const bool floating = floating_type(type);
  std::vector<ChunkRows> rows_of;
  for (const void* column : columns)
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::size_t begin = c * chunk_rows, end = std::min(rows, begin + chunk_rows);
      rows_of.push_back({static_cast<const unsigned char*>(column) + begin * element_size,
                         (end - begin) * element_size, chunk_bytes, element_size, floating});
    }
  ChunkCompression compression(level);
  compression.compress_each(
      rows_of, [&](std::size_t k, const unsigned char* out, std::size_t size) {
        const hsize_t offset[2] = {static_cast<hsize_t>(k % chunks * chunk_rows),
                                   static_cast<hsize_t>(k / chunks)};
        check(H5Dwrite_chunk(dataset, H5P_DEFAULT, 0, offset, size, out),
              "cannot write a compressed chunk");
      });
  return true;
}

}  // namespace lsi::hdf5
