// Writing a large compressed dataset with its chunks compressed on several threads: the shuffle
// and deflate filters that the dataset declares are applied here, chunk by chunk in parallel, and
// the compressed chunks written in order with H5Dwrite_chunk. The file is the one HDF5's own
// filter pipeline writes (any HDF5 reader inflates it), only the compression no longer runs on one
// thread. Used for the tables of sweep result files, whose compression dominates their writing.
#pragma once
#include <hdf5.h>

#include <cstddef>

namespace lsi::hdf5 {

// Writes `data` (the whole dataset, row-major, in the file's element layout: native numbers of
// `element_size` bytes, `rows` rows of `row_elements` elements) into `dataset`, created with
// compressed_table_properties (hdf5_io.hpp). Returns false, having written nothing, when the
// dataset is not chunked along its rows with shuffle + deflate and nothing else (the caller then
// writes it with H5Dwrite). Threads: OMP_NUM_THREADS when set, else the hardware's.
bool write_compressed_chunks(hid_t dataset, hid_t creation_properties, const void* data,
                             std::size_t rows, std::size_t row_elements, std::size_t element_size);

}  // namespace lsi::hdf5
