// Counter-based random numbers for the sweeps: Philox-4x32-10 (Salmon, Moraes, Dror & Shaw, "Parallel
// random numbers: as easy as 1, 2, 3", SC'11), written from the published algorithm.
//
// Why counter-based: a sweep draws the inputs of sample i inside a batched Kokkos kernel, and sample i
// must get the same inputs whatever the batch it falls in, the thread that runs it, the backend or
// the sharding of the study. A counter-based generator is a pure function (counter, key) -> bits, so
// the random numbers of sample i are keyed by (seed, i, stream) and nothing else: no state, no
// skip-ahead, nothing stored per thread.
//
// Philox-4x32-R: a 128-bit counter (4 x 32-bit words) and a 64-bit key (2 words); each round
// multiplies words 0 and 2 by the constants M0, M1 into 64-bit products (hi, lo) and permutes:
//   (c0, c1, c2, c3) <- (hi(M1 c2) ^ c1 ^ k0, lo(M1 c2), hi(M0 c0) ^ c3 ^ k1, lo(M0 c0)),
// and the key is bumped by the Weyl constants (W0, W1) between rounds. Ten rounds is the variant the
// authors recommend (it passes TestU01's BigCrush with a margin). The known-answer vectors of
// Random123 (tests/kat_vectors, "philox4x32 10 ...") are checked in tests/sweeps/test_sampling.cpp.
//
// How the sweeps use it (the layout is part of the reproducibility contract: change it and every
// stored study changes):
//   counter = (sample lo32, sample hi32, stream, domain), key = (seed lo32, seed hi32).
// `stream` is the dimension (input index) and `domain` separates the uses: 0 for the uniforms of the
// designs (Monte Carlo draws, Latin-hypercube jitter), 1 for the per-dimension keys of the Latin
// hypercube permutations, 2 for the per-dimension seeds of the Sobol scrambling.
#pragma once
#include <Kokkos_Core.hpp>
#include <cstdint>

namespace lsi::sweeps {

struct Philox4x32Block {
  std::uint32_t v[4];
};

namespace detail {
KOKKOS_INLINE_FUNCTION void philox_mulhilo(std::uint32_t a, std::uint32_t b, std::uint32_t& hi,
                                           std::uint32_t& lo) {
  const std::uint64_t p = static_cast<std::uint64_t>(a) * static_cast<std::uint64_t>(b);
  hi = static_cast<std::uint32_t>(p >> 32);
  lo = static_cast<std::uint32_t>(p);
}

constexpr std::uint32_t philox_m0 = 0xD2511F53u, philox_m1 = 0xCD9E8D57u;  // round multipliers
constexpr std::uint32_t philox_w0 = 0x9E3779B9u,
                        philox_w1 = 0xBB67AE85u;  // key schedule (golden ratio, sqrt(3)-1)

// One round on the counter words c and the round's key (k0, k1).
KOKKOS_INLINE_FUNCTION void philox_round(std::uint32_t* c, std::uint32_t k0, std::uint32_t k1) {
  std::uint32_t hi0, lo0, hi1, lo1;
  philox_mulhilo(philox_m0, c[0], hi0, lo0);
  philox_mulhilo(philox_m1, c[2], hi1, lo1);
  const std::uint32_t next0 = hi1 ^ c[1] ^ k0, next2 = hi0 ^ c[3] ^ k1;
  c[0] = next0;
  c[1] = lo1;
  c[2] = next2;
  c[3] = lo0;
}
}  // namespace detail

// One Philox-4x32 block with `rounds` rounds (10 for Philox-4x32-10; other counts only for the
// known-answer tests of the round structure).
KOKKOS_INLINE_FUNCTION Philox4x32Block philox4x32(Philox4x32Block ctr, std::uint32_t k0,
                                                  std::uint32_t k1, int rounds = 10) {
  for (int r = 0; r < rounds; ++r) {
    if (r > 0) {
      k0 += detail::philox_w0;
      k1 += detail::philox_w1;
    }
    detail::philox_round(ctr.v, k0, k1);
  }
  return ctr;
}

// 64 random bits: the first two words of Philox-4x32-10 at counter (sample, stream, domain), key seed.
KOKKOS_INLINE_FUNCTION std::uint64_t random_bits64(std::uint64_t seed, std::uint64_t sample,
                                                   std::uint32_t stream, std::uint32_t domain = 0) {
  const Philox4x32Block ctr{{static_cast<std::uint32_t>(sample),
                             static_cast<std::uint32_t>(sample >> 32), stream, domain}};
  const Philox4x32Block out =
      philox4x32(ctr, static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32));
  return (static_cast<std::uint64_t>(out.v[0]) << 32) | out.v[1];
}

// 64 random bits to a double in the OPEN interval (0,1) with 53-bit resolution: k = the top 53 bits,
// u = k 2^-53 (exact in double), and the one value k = 0 is moved to the middle of its cell, 2^-54,
// so that u is never 0. The largest value is 1 - 2^-53 < 1. (The obvious (k + 0.5) 2^-53 is not exact
// in double for k near 2^53 and rounds to 1.0.)
KOKKOS_INLINE_FUNCTION double bits_to_open01(std::uint64_t bits) {
  constexpr double two_m53 = 1.0 / 9007199254740992.0;         // 2^-53
  const double u = static_cast<double>(bits >> 11) * two_m53;  // exact
  // u is 0 exactly when k is (the test on the double rather than on k lets GCC vectorise a loop
  // of this, uniform_open01_each).
  return u == 0.0 ? 0.5 * two_m53 : u;
}

// Uniform in the OPEN interval (0,1), 53-bit resolution, a pure function of its arguments:
// Philox-4x32-10 at counter (sample, stream, domain 0), key seed, through bits_to_open01.
KOKKOS_INLINE_FUNCTION double uniform_open01(std::uint64_t seed, std::uint64_t sample,
                                             std::uint32_t stream) {
  return bits_to_open01(random_bits64(seed, sample, stream, 0));
}

// uniform_open01(seed, first + k, stream) for k < n into out[k] (host code), the same bits: the ten
// rounds written out, so that GCC vectorises the loop over k (the general philox4x32 takes its
// round count at run time, and its loop stays scalar).
inline void uniform_open01_each(std::uint64_t seed, std::uint64_t first, std::uint32_t stream,
                                double* out, int n) {
#pragma GCC ivdep
  for (int k = 0; k < n; ++k) {
    const std::uint64_t sample = first + static_cast<std::uint64_t>(k);
    std::uint32_t c[4] = {static_cast<std::uint32_t>(sample),
                          static_cast<std::uint32_t>(sample >> 32), stream, 0};
    std::uint32_t k0 = static_cast<std::uint32_t>(seed),
                  k1 = static_cast<std::uint32_t>(seed >> 32);
#pragma GCC unroll 10
    for (int r = 0; r < 10; ++r) {
      detail::philox_round(c, k0, k1);
      k0 += detail::philox_w0;
      k1 += detail::philox_w1;
    }
    out[k] = bits_to_open01((static_cast<std::uint64_t>(c[0]) << 32) | c[1]);
  }
}

// A 64-bit finaliser (the MurmurHash3 / SplitMix64 mixing constants): a bijection of 64-bit words with
// full avalanche, used to derive sub-keys. Not a random number generator on its own.
KOKKOS_INLINE_FUNCTION std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 31;
  return x;
}

}  // namespace lsi::sweeps
