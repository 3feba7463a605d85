// Adler-32 (io/adler32.hpp) against zlib's adler32: exact, so no tolerance.
#include "io/adler32.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <random>
#include <vector>

namespace {

std::uint32_t zlib_adler(std::uint32_t start, const std::vector<unsigned char>& b, std::size_t n) {
  return static_cast<std::uint32_t>(adler32_z(start, b.data(), n));
}

// Lengths around the 64-byte rows and the blocks of 1024 rows (65536 bytes), and zlib's own
// block of 5552 bytes.
const std::size_t kLengths[] = {0,    1,    2,     63,    64,    65,     127,    128,    5551,
                                5552, 5553, 65535, 65536, 65537, 131072, 131135, 200003, 1 << 20};

TEST(Adler32, RandomBytesGiveZlibsChecksum) {
  std::mt19937 g(7);
  std::vector<unsigned char> b(1 << 20);
  for (auto& x : b) x = static_cast<unsigned char>(g());
  for (const std::size_t n : kLengths)
    EXPECT_EQ(lsi::hdf5::adler32(1, b.data(), n), zlib_adler(1, b, n)) << n << " bytes";
}

// Every byte 255: the largest sums each lane can hold (W = 255 R (R + 1) / 2 at R = 1024 rows).
TEST(Adler32, AllOnesBytesStayWithinTheLanes) {
  const std::vector<unsigned char> b(1 << 20, 255);
  for (const std::size_t n : kLengths)
    EXPECT_EQ(lsi::hdf5::adler32(1, b.data(), n), zlib_adler(1, b, n)) << n << " bytes";
}

// Continued from a checksum whose sums are near the modulus, as a stream summed in pieces.
TEST(Adler32, ContinuesFromAnyChecksum) {
  std::mt19937 g(11);
  std::vector<unsigned char> b(300000);
  for (auto& x : b) x = static_cast<unsigned char>(g());
  for (const std::uint32_t start : {0u, 65520u << 16 | 65520u, 12345u << 16 | 54321u})
    for (const std::size_t n : kLengths)
      if (n <= b.size()) {
        EXPECT_EQ(lsi::hdf5::adler32(start, b.data(), n), zlib_adler(start, b, n))
            << n << " bytes from " << start;
      }
  const std::size_t cut = 70001;
  EXPECT_EQ(
      lsi::hdf5::adler32(lsi::hdf5::adler32(1, b.data(), cut), b.data() + cut, b.size() - cut),
      zlib_adler(1, b, b.size()));
}

}  // namespace
