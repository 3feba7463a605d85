// The scrambled Sobol sequence, evaluated at any index without state (so sample i is the same point
// whatever the batch or thread that draws it).
//
// * Direction numbers: Joe & Kuo new-joe-kuo-6.21201 (sobol_directions.hpp), 32 dimensions, in 64-bit
//   words: V_k = m_k 2^(64-k), k = 1..64, with the recurrence
//     V_k = V_{k-s} ^ (V_{k-s} >> s) ^ a_1 V_{k-1} ^ ... ^ a_{s-1} V_{k-s+1}   (k > s).
// * Point i: x = XOR of V_{b+1} over the set bits b of the Gray code g = i ^ (i >> 1). This is the
//   order of Antonov & Saleev used by Joe & Kuo's generator (and by scipy's unscrambled Sobol), so
//   that the unscrambled points are the published sequence (0, 1/2, 3/4, 1/4, ... in dimension 1);
//   the first 2^m points are the same set as in natural order. 64-bit words: any index < 2^64.
// * Scrambling: nested uniform (Owen) scrambling keyed by the seed, with the hash-based construction
//   of Burley ("Practical hash-based Owen scrambling", JCGT 9(4), 2020): reverse the bits, apply a
//   hash built only from operations in which output bit k depends on input bit k XORed with bits
//   below k (adding the seed, x ^= x * even, x *= odd), reverse back. Every digit of the point is
//   then flipped by a function of the digits above it and of the seed - the form of an Owen scramble
//   - so the (t,m,s)-net properties of the sequence are kept (tested: (0,m,2)-nets in dimensions
//   1-2), while the point set becomes a randomised, unbiased QMC estimator. Each dimension gets its
//   own 64-bit scrambling seed from Philox (seed, stream = dimension, domain 2). The 64-bit hash is
//   our own instance of that structure (four rounds of x ^= x * even, then x *= odd), not Burley's
//   32-bit constants.
// * To double: the top 52 bits k of the scrambled word, u = (k + 1/2) 2^-52, the middle of its cell:
//   in [2^-53, 1 - 2^-53], never 0 or 1 (the quantile of 0 or 1 would be infinite), exact in double.
//   52-bit precision.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sweeps/counter_rng.hpp"
#include "sweeps/sobol_directions.hpp"

namespace lsi::sweeps {

constexpr int sobol_bits = 64;  // direction numbers per dimension

// The direction numbers of the first `dims` dimensions, row-major [dim][k-1], 64 per dimension.
inline std::vector<std::uint64_t> sobol_direction_numbers(int dims) {
  if (dims < 0 || dims > sobol_max_dimensions)
    throw std::invalid_argument("Sobol design: " + std::to_string(dims) +
                                " dimensions: the direction numbers "
                                "shipped (Joe & Kuo new-joe-kuo-6.21201) cover at most " +
                                std::to_string(sobol_max_dimensions));
  std::vector<std::uint64_t> v(static_cast<std::size_t>(dims) * sobol_bits, 0);
  for (int d = 0; d < dims; ++d) {
    std::uint64_t* V = v.data() + static_cast<std::size_t>(d) * sobol_bits;  // V[k-1] = V_k
    if (d == 0) {
      for (int k = 1; k <= sobol_bits; ++k) V[k - 1] = std::uint64_t{1} << (sobol_bits - k);
      continue;
    }
    const SobolPolynomial& p = sobol_joe_kuo_6_21201[d - 1];
    const int s = p.s;
    for (int k = 1; k <= s; ++k)
      V[k - 1] = static_cast<std::uint64_t>(p.m[k - 1]) << (sobol_bits - k);
    for (int k = s + 1; k <= sobol_bits; ++k) {
      std::uint64_t x = V[k - s - 1] ^ (V[k - s - 1] >> s);
      for (int j = 1; j <= s - 1; ++j)
        if ((p.a >> (s - 1 - j)) & 1u) x ^= V[k - j - 1];
      V[k - 1] = x;
    }
  }
  return v;
}

// The unscrambled 64-bit Sobol word of point `index` in one dimension (V: that dimension's 64 numbers).
KOKKOS_INLINE_FUNCTION std::uint64_t sobol_word(const std::uint64_t* V, std::uint64_t index) {
  std::uint64_t g = index ^ (index >> 1), x = 0;
  for (int b = 0; g != 0; ++b, g >>= 1)
    if (g & 1u) x ^= V[b];
  return x;
}

KOKKOS_INLINE_FUNCTION std::uint64_t reverse_bits64(std::uint64_t x) {
  x = ((x >> 1) & 0x5555555555555555ull) | ((x & 0x5555555555555555ull) << 1);
  x = ((x >> 2) & 0x3333333333333333ull) | ((x & 0x3333333333333333ull) << 2);
  x = ((x >> 4) & 0x0F0F0F0F0F0F0F0Full) | ((x & 0x0F0F0F0F0F0F0F0Full) << 4);
  x = ((x >> 8) & 0x00FF00FF00FF00FFull) | ((x & 0x00FF00FF00FF00FFull) << 8);
  x = ((x >> 16) & 0x0000FFFF0000FFFFull) | ((x & 0x0000FFFF0000FFFFull) << 16);
  return (x >> 32) | (x << 32);
}

// Owen scrambling of a 64-bit Sobol word (bit 63 is the first binary digit) with a 64-bit seed.
KOKKOS_INLINE_FUNCTION std::uint64_t owen_scramble64(std::uint64_t x, std::uint64_t seed) {
  x = reverse_bits64(x);
  // In reversed order digit k of the point is bit k from the least significant end: every operation
  // below changes bit k only by a function of the bits below it (and of the seed).
  x += seed;
  x ^= x * 0x6C50B47CDB5A3F12ull;
  x ^= x * 0xB82F1E52A7C94D36ull;
  x ^= x * 0xC7AFE638E1D2B5A4ull;
  x ^= x * 0x8D22F6E6F0C3A59Eull;
  x *= 0x9E3779B97F4A7C15ull | 1u;
  x += seed >> 29 | seed << 35;
  x ^= x * 0xA0761D6478BD642Eull;
  return reverse_bits64(x);
}

// A 64-bit Sobol word to a double in the open interval (0,1): (top 52 bits + 1/2) 2^-52.
KOKKOS_INLINE_FUNCTION double sobol_word_to_open01(std::uint64_t x) {
  constexpr double two_m52 = 1.0 / 4503599627370496.0;
  return (static_cast<double>(x >> 12) + 0.5) * two_m52;
}

// The per-dimension scrambling seed.
KOKKOS_INLINE_FUNCTION std::uint64_t sobol_scramble_seed(std::uint64_t seed, int dim) {
  return random_bits64(seed, 0, static_cast<std::uint32_t>(dim), 2);
}

// Host helper for tests: coordinate `dim` of unscrambled point `index` as a double in [0,1)
// (k 2^-64 rounded; exact for the first 2^53 points).
inline double sobol_unscrambled(std::uint64_t index, int dim) {
  const auto v = sobol_direction_numbers(dim + 1);
  const std::uint64_t x = sobol_word(v.data() + static_cast<std::size_t>(dim) * sobol_bits, index);
  return static_cast<double>(x >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace lsi::sweeps
