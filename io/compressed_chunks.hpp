// Writing a large compressed dataset with its chunks compressed on several threads: the shuffle
// and deflate filters that the dataset declares are applied here, chunk by chunk in parallel, and
// the compressed chunks written in order with H5Dwrite_chunk. The chunks are those HDF5's own
// filter pipeline reads (any HDF5 reader inflates them); the compression runs on several threads
// and picks zlib's strategy by the numbers' type (ChunkCompression). Used for the tables of sweep
// result files, whose compression dominates their writing.
#pragma once
#include <hdf5.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

namespace lsi::hdf5 {

// One chunk to compress: `bytes` bytes of rows (native numbers of `element_size` bytes) at
// `rows`, padded with zeros (the fill value) to `chunk_bytes`, as HDF5 stores an edge chunk;
// `floating`: the numbers are floating-point ones (see ChunkCompression).
struct ChunkRows {
  const void* rows;
  std::size_t bytes, chunk_bytes, element_size;
  bool floating;
};

// Compresses chunks as HDF5's shuffle + deflate pipeline stores them, on the host's threads
// (model/host_threads.hpp). Integer chunks are deflated by zlib at `level`.
// Floating-point ones are deflated byte plane by byte plane, in one deflate stream of blocks lsi
// writes itself (deflate_planes.hpp): after the shuffle their sign and exponent bytes come in
// long runs (a block of literals and repeats of the previous byte), the planes between, of few
// values but no runs, take a Huffman code of their own (a block of literals alone), and the low
// mantissa bytes, which look random, are stored: Huffman coding them would take most of the
// time of writing a large table and save nothing. The format leaves these choices to the
// writer: any HDF5 reader inflates the stream.
// The threads' zlib streams and buffers and the compressed bytes are kept from call to call: a
// table of millions of rows is thousands of chunks, and memory allocated anew for each costs a
// page fault per 4 KiB.
class ChunkCompression {
 public:
  explicit ChunkCompression(int level);
  ~ChunkCompression();
  ChunkCompression(const ChunkCompression&) = delete;
  ChunkCompression& operator=(const ChunkCompression&) = delete;

  // The chunks compressed, in the order given; valid until the next call.
  const std::vector<std::vector<unsigned char>>& compress(const std::vector<ChunkRows>& chunks);
  // The same, each compressed chunk handed to ready(index, bytes, size) on the calling thread,
  // in the order given, as soon as it and those before it are compressed: the caller writes a
  // chunk while the other threads compress the next ones (HDF5 calls stay on one thread). The
  // bytes are valid during the call to `ready` only (a few chunks a thread are in flight, in
  // buffers kept from call to call). An exception from `ready` or a compression ends the call
  // (after the threads) and propagates.
  void compress_each(
      const std::vector<ChunkRows>& chunks,
      const std::function<void(std::size_t, const unsigned char*, std::size_t)>& ready);

 private:
  struct Threads;
  int level_;
  std::unique_ptr<Threads> threads_;
  std::vector<std::vector<unsigned char>> out_;
};

// Whether a dataset type is a floating-point one: the `floating` of its datasets' chunks.
bool floating_type(hid_t type);

// The deflate level of a dataset's filters when they are exactly shuffle then deflate; else -1.
int shuffle_deflate_level(hid_t creation_properties);

// Writes the whole of `dataset`, created with compressed_table_properties (hdf5_io.hpp) in
// chunks of one column: `columns` holds each of its columns (one for a 1-D dataset), `rows`
// native numbers of `element_size` bytes each, in the file's element layout. Returns false,
// having written nothing, when the dataset is not chunked so (along its rows, a column a chunk)
// with shuffle + deflate and nothing else (the caller then writes it with H5Dwrite). Threads:
// the host's (model/host_threads.hpp).
bool write_compressed_chunks(hid_t dataset, hid_t creation_properties,
                             const std::vector<const void*>& columns, std::size_t rows,
                             std::size_t element_size);

}  // namespace lsi::hdf5
