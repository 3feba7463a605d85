// Writing a large compressed dataset with its chunks compressed on several threads: the shuffle
// and deflate filters that the dataset declares are applied here, chunk by chunk in parallel, and
// the compressed chunks written in order with H5Dwrite_chunk. The file is the one HDF5's own
// filter pipeline writes (any HDF5 reader inflates it), only the compression no longer runs on one
// thread. Used for the tables of sweep result files, whose compression dominates their writing.
#pragma once
#include <hdf5.h>

#include <cstddef>
#include <vector>

namespace lsi::hdf5 {

// One chunk to compress: `bytes` bytes of rows (native numbers of `element_size` bytes) at
// `rows`, padded with zeros (the fill value) to `chunk_bytes`, as HDF5 stores an edge chunk.
struct ChunkRows {
  const void* rows;
  std::size_t bytes, chunk_bytes, element_size;
};

// The chunks as HDF5's shuffle + deflate (at `level`) pipeline stores them, compressed on
// several threads (OMP_NUM_THREADS when set, else the hardware's); in the order given.
std::vector<std::vector<unsigned char>> compress_chunks(const std::vector<ChunkRows>& chunks,
                                                        int level);

// The deflate level of a dataset's filters when they are exactly shuffle then deflate; else -1.
int shuffle_deflate_level(hid_t creation_properties);

// Writes `data` (the whole dataset, row-major, in the file's element layout: native numbers of
// `element_size` bytes, `rows` rows of `row_elements` elements) into `dataset`, created with
// compressed_table_properties (hdf5_io.hpp). Returns false, having written nothing, when the
// dataset is not chunked along its rows with shuffle + deflate and nothing else (the caller then
// writes it with H5Dwrite). Threads: OMP_NUM_THREADS when set, else the hardware's.
bool write_compressed_chunks(hid_t dataset, hid_t creation_properties, const void* data,
                             std::size_t rows, std::size_t row_elements, std::size_t element_size);

}  // namespace lsi::hdf5
