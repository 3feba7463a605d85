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
}  // namespace detail

// One Philox-4x32 block with `rounds` rounds (10 for Philox-4x32-10; other counts only for the
// known-answer tests of the round structure).
KOKKOS_INLINE_FUNCTION Philox4x32Block philox4x32(Philox4x32Block ctr, std::uint32_t k0,
                                                  std::uint32_t k1, int rounds = 10) {
  constexpr std::uint32_t M0 = 0xD2511F53u, M1 = 0xCD9E8D57u;  // round multipliers
  constexpr std::uint32_t W0 = 0x9E3779B9u,
                          W1 = 0xBB67AE85u;  // key schedule (golden ratio, sqrt(3)-1)
  for (int r = 0; r < rounds; ++r) {
    if (r > 0) {
      k0 += W0;
      k1 += W1;
    }
    std::uint32_t hi0, lo0, hi1, lo1;
    detail::philox_mulhilo(M0, ctr.v[0], hi0, lo0);
    detail::philox_mulhilo(M1, ctr.v[2], hi1, lo1);
    const Philox4x32Block next{{hi1 ^ ctr.v[1] ^ k0, lo1, hi0 ^ ctr.v[3] ^ k1, lo0}};
    ctr = next;
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
  const std::uint64_t k = bits >> 11;
  constexpr double two_m53 = 1.0 / 9007199254740992.0;  // 2^-53
  return k == 0 ? 0.5 * two_m53 : static_cast<double>(k) * two_m53;
}

// Uniform in the OPEN interval (0,1), 53-bit resolution, a pure function of its arguments:
// Philox-4x32-10 at counter (sample, stream, domain 0), key seed, through bits_to_open01.
KOKKOS_INLINE_FUNCTION double uniform_open01(std::uint64_t seed, std::uint64_t sample,
                                             std::uint32_t stream) {
  return bits_to_open01(random_bits64(seed, sample, stream, 0));
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
