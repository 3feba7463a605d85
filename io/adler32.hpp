// The Adler-32 checksum of RFC 1950 (8.2), which ends a zlib stream: s1 = 1 + the sum of the
// bytes, s2 = the sum of s1 after each byte, both modulo 65521, s2 in the upper 16 bits. The
// same value as zlib's adler32, computed in a form the compiler vectorises: rows of 64 bytes are
// added lane by lane into 64 running sums A, and A after each row into 64 sums W; over a block
// of R rows (L = 64 R bytes) the weight of byte k = 64 r + i in s2 is L - k = 64 (R - r) - i,
// so s2 gains L s1 + 64 sum(W) - sum(i A_i) and s1 gains sum(A). A block of at most 1024 rows
// keeps every lane's sums below 2^32 (W <= 255 R (R + 1) / 2). zlib's adler32 adds the bytes
// one after another; a sweep table's every chunk is summed once (deflate_planes.hpp).
#pragma once
#include <cstddef>
#include <cstdint>

namespace lsi::hdf5 {

// The checksum of n bytes at p continued from `adler` (1 for a new stream).
std::uint32_t adler32(std::uint32_t adler, const unsigned char* p, std::size_t n);

}  // namespace lsi::hdf5
