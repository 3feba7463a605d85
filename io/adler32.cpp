// Adler-32, vectorised; see adler32.hpp.
#include "io/adler32.hpp"

#include <algorithm>

namespace lsi::hdf5 {

std::uint32_t adler32(const std::uint32_t adler, const unsigned char* p, std::size_t n) {
  constexpr std::uint64_t mod = 65521;
  constexpr std::size_t lanes = 64, max_rows = 1024;
  std::uint64_t s1 = adler & 0xffff, s2 = adler >> 16;
  while (n >= lanes) {
    const std::size_t rows = std::min(n / lanes, max_rows);
    std::uint32_t a[lanes] = {}, w[lanes] = {};
    for (std::size_t r = 0; r < rows; ++r, p += lanes)
      for (std::size_t i = 0; i < lanes; ++i) {
        a[i] += p[i];
        w[i] += a[i];
      }
    std::uint64_t sum_a = 0, sum_w = 0, sum_ia = 0;
    for (std::size_t i = 0; i < lanes; ++i) {
      sum_a += a[i];
      sum_w += w[i];
      sum_ia += i * a[i];
    }
    const std::uint64_t bytes = rows * lanes;
    // 64 sum(W) >= sum(i A_i): every byte's weight 64 (R - r) - i is at least 1.
    s2 = (s2 + bytes % mod * s1 + lanes * sum_w - sum_ia) % mod;
    s1 = (s1 + sum_a) % mod;
    n -= bytes;
  }
  for (std::size_t k = 0; k < n; ++k) {  // fewer than 64: no overflow before the modulo
    s1 += p[k];
    s2 += s1;
  }
  return static_cast<std::uint32_t>((s2 % mod) << 16 | (s1 % mod));
}

}  // namespace lsi::hdf5
