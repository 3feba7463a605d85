// Addresses of written chunks; see written_chunk_address.hpp.
#include "io/written_chunk_address.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstring>

#include "io/hdf5_io.hpp"

namespace lsi::hdf5 {

WrittenChunkAddress::WrittenChunkAddress(const std::string& path)
    : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {}

WrittenChunkAddress::~WrittenChunkAddress() {
  if (fd_ >= 0) ::close(fd_);
}

void WrittenChunkAddress::before_write(hid_t file) {
  hsize_t end = 0;
  file_end_ = H5Fget_filesize(file, &end) >= 0 ? end : 0;
}

bool WrittenChunkAddress::holds(std::uint64_t address, const void* bytes, std::size_t size) {
  if (fd_ < 0 || address == 0) return false;
  read_.resize(size);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t r =
        ::pread(fd_, read_.data() + done, size - done, static_cast<off_t>(address + done));
    if (r <= 0) return false;
    done += static_cast<std::size_t>(r);
  }
  return std::memcmp(read_.data(), bytes, size) == 0;
}

std::uint64_t WrittenChunkAddress::after_write(hid_t dataset, const hsize_t* offset,
                                               const void* bytes, std::size_t size) {
  std::uint64_t address = 0;
  if (holds(file_end_, bytes, size)) {
    address = file_end_;
  } else if (holds(previous_end_, bytes, size)) {
    address = previous_end_;
  } else {
    unsigned mask = 0;
    haddr_t where = 0;
    hsize_t stored = 0;
    check(H5Dget_chunk_info_by_coord(dataset, offset, &mask, &where, &stored),
          "cannot locate a chunk just written");
    address = where;
  }
  previous_end_ = address + size;
  return address;
}

}  // namespace lsi::hdf5
