// Latin hypercube sampling without stored permutations: the stratum of sample i in dimension d is
// pi_d(i), where pi_d is a pseudo-random permutation of [0, N) keyed by (seed, d) and evaluated at i
// alone, and the point is u = (pi_d(i) + j) / N with a Philox jitter j = uniform_open01(seed, i, d).
// Every dimension therefore hits each of its N strata exactly once, sample i is the same whatever
// the batch or thread that draws it, and nothing of size N is stored.
//
// The permutation follows the idea of Kensler ("Correlated multi-jittered sampling", Pixar technical
// memo 13-01, 2013): a keyed hash that is a bijection of [0, 2^b) (2^b the smallest power of two
// >= N), made from steps each invertible modulo 2^b (xor with a key, multiplication by an odd
// constant, xor with its own right shift, addition of a key), and "cycle walking": apply it again
// while the value is >= N. Since the hash permutes [0, 2^b), walking from i < N ends on a value < N and
// the map i -> result is a bijection of [0, N); on average fewer than two passes (2^b < 2N). The
// round structure and constants are our own (64-bit, four rounds with per-round keys from mix64).
//
// With a correlation matrix the sampler applies the Gaussian copula to these uniforms; the
// correlated dimensions then keep the correlation but lose the exact stratification of their
// marginals (the independent normal scores stay stratified). See sampler.hpp.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>

#include "sweeps/counter_rng.hpp"

namespace lsi::sweeps {

// Parameters of the permutation domain [0, n): the mask 2^b - 1 and the shift of the xorshift steps.
struct PermutationDomain {
  std::uint64_t n = 1, mask = 0;
  int shift = 1;
};

inline PermutationDomain make_permutation_domain(std::uint64_t n) {
  PermutationDomain p;
  p.n = n == 0 ? 1 : n;
  int bits = 0;
  while (bits < 64 && (std::uint64_t{1} << bits) < p.n) ++bits;
  p.mask = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
  p.shift = bits / 2 > 0 ? bits / 2 : 1;
  return p;
}

// One pass of the keyed bijection of [0, mask].
KOKKOS_INLINE_FUNCTION std::uint64_t permutation_hash(std::uint64_t x, std::uint64_t key,
                                                      const PermutationDomain& p) {
  const std::uint64_t m = p.mask;
  for (std::uint64_t r = 0; r < 4; ++r) {
    const std::uint64_t k = mix64(key + r * 0x9E3779B97F4A7C15ull);
    x = (x ^ k) & m;
    x = (x * (0xD1342543DE82EF95ull ^ (k >> 40 << 1))) & m;  // odd multiplier (bit 0 stays 1)
    x ^= x >> p.shift;
    x = (x + (k >> 32)) & m;
    x ^= x >> ((p.shift + 1) / 2 > 0 ? (p.shift + 1) / 2 : 1);
  }
  return x;
}

// pi(i): a keyed permutation of [0, n) evaluated at i < n.
KOKKOS_INLINE_FUNCTION std::uint64_t permute_index(std::uint64_t i, std::uint64_t key,
                                                   const PermutationDomain& p) {
  if (p.n <= 1) return 0;
  std::uint64_t x = i;
  do {
    x = permutation_hash(x, key, p);
  } while (x >= p.n);
  return x;
}

// The per-dimension permutation key.
KOKKOS_INLINE_FUNCTION std::uint64_t latin_hypercube_key(std::uint64_t seed, int dim) {
  return random_bits64(seed, 0, static_cast<std::uint32_t>(dim), 1);
}

// Coordinate `dim` of Latin-hypercube sample `index` (< n) in the open interval (0,1).
KOKKOS_INLINE_FUNCTION double latin_hypercube_uniform(std::uint64_t seed, std::uint64_t key,
                                                      const PermutationDomain& p,
                                                      std::uint64_t index, int dim) {
  const std::uint64_t stratum = permute_index(index % p.n, key, p);
  const double jitter = uniform_open01(seed, index, static_cast<std::uint32_t>(dim));
  double u = (static_cast<double>(stratum) + jitter) / static_cast<double>(p.n);
  // (stratum + jitter) rounds up to n only when jitter is within 2^-53 n of 1: keep u < 1.
  constexpr double below_one = 1.0 - 1.0 / 9007199254740992.0;
  return u < below_one ? u : below_one;
}

}  // namespace lsi::sweeps
