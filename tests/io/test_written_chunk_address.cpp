// Where a chunk just written lies (io/written_chunk_address.hpp): the address found for every
// chunk of two datasets written in turn, one of small chunks (which share HDF5's small-data
// blocks) and one of large ones (at the file's end), and of chunks of identical bytes, is the
// address HDF5 itself gives.
#include "io/written_chunk_address.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "io/hdf5_io.hpp"

namespace {

using lsi::hdf5::Handle;

TEST(WrittenChunkAddress, EveryChunkIsWhereHdf5PutIt) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("lsi_written_chunk_address_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  {
    Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                "cannot create " + path);
    // Chunks of 64 and 8192 bytes; the chunks are written as they are (no filter), their bytes
    // random but for every fifth small chunk, which repeats the one before it.
    const hsize_t rows = 64 * 1024, small_rows = 64, large_rows = 8192;
    Handle space(H5Screate_simple(1, &rows, nullptr), H5Sclose, "cannot create a dataspace");
    auto dataset = [&](const char* name, hsize_t chunk) {
      Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "cannot create a dcpl");
      H5Pset_chunk(dcpl, 1, &chunk);
      return Handle(H5Dcreate2(file, name, H5T_NATIVE_UCHAR, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                    H5Dclose, std::string("cannot create ") + name);
    };
    Handle small = dataset("small", small_rows), large = dataset("large", large_rows);
    lsi::hdf5::WrittenChunkAddress addresses(path);
    std::mt19937 g(1);
    std::vector<unsigned char> bytes(large_rows);
    int checked = 0;
    auto write = [&](hid_t d, hsize_t chunk, hsize_t size, bool repeat) {
      if (!repeat)
        for (hsize_t i = 0; i < size; ++i) bytes[i] = static_cast<unsigned char>(g());
      const hsize_t offset = chunk * size;
      addresses.before_write(file);
      ASSERT_GE(H5Dwrite_chunk(d, H5P_DEFAULT, 0, &offset, size, bytes.data()), 0);
      const std::uint64_t found = addresses.after_write(d, &offset, bytes.data(), size);
      unsigned mask = 0;
      haddr_t address = 0;
      hsize_t stored = 0;
      ASSERT_GE(H5Dget_chunk_info_by_coord(d, &offset, &mask, &address, &stored), 0);
      EXPECT_EQ(found, address) << "chunk " << chunk << " of " << size << " bytes";
      EXPECT_EQ(stored, size);
      ++checked;
    };
    for (hsize_t c = 0; c < 8; ++c) {
      for (hsize_t s = 0; s < 128; ++s) write(small, 128 * c + s, small_rows, s % 5 == 4);
      write(large, c, large_rows, false);
    }
    EXPECT_EQ(checked, 8 * 129);
  }
  std::filesystem::remove(path);
}

}  // namespace
