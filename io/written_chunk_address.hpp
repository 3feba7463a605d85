// Where HDF5 put a chunk that H5Dwrite_chunk just wrote. HDF5's own answer
// (H5Dget_chunk_info_by_coord) walks every chunk of the dataset before the one asked for in the
// HDF5 1.10 library: asked after each write, its time grows with the square of the table's
// chunks, on the thread that hands the compressed chunks to HDF5. A new chunk lands in one of
// two places in practice: at the file's end before the write (a large chunk), or right after the
// chunk written before it (small chunks share HDF5's small-data blocks). Each candidate is
// confirmed by reading the chunk's bytes back there, so a wrong guess costs a read; HDF5 is asked
// where neither holds them. The address returned holds the chunk's bytes: the chunk itself, or,
// where an earlier chunk has the same bytes (a constant column), that one, which is as good, since
// the chunks of a sweep table are written once and never moved or freed. A chunk's address is what
// lets a killed sweep copy its chunks into a new file (io/sweep_table_stream.hpp), so it must
// hold exactly those bytes.
#pragma once
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lsi::hdf5 {

class WrittenChunkAddress {
 public:
  // For the file at `path` (read through a descriptor of its own; where it cannot be opened,
  // every address is HDF5's lookup).
  explicit WrittenChunkAddress(const std::string& path);
  ~WrittenChunkAddress();
  WrittenChunkAddress(const WrittenChunkAddress&) = delete;
  WrittenChunkAddress& operator=(const WrittenChunkAddress&) = delete;

  // Before each H5Dwrite_chunk into `file`: notes the file's end.
  void before_write(hid_t file);
  // After it: an address of the file that holds the `size` bytes written as the chunk at
  // `offset` of `dataset` (see the file comment).
  std::uint64_t after_write(hid_t dataset, const hsize_t* offset, const void* bytes,
                            std::size_t size);

 private:
  bool holds(std::uint64_t address, const void* bytes, std::size_t size);

  int fd_ = -1;
  std::uint64_t file_end_ = 0, previous_end_ = 0;
  std::vector<unsigned char> read_;
};

}  // namespace lsi::hdf5
