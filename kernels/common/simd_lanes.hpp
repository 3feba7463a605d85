// The few lane operations that branch-free numerical code written once as a template needs, for
// two lane types: one double (any compiler, any backend) and, on hosts with AVX-512, eight doubles
// in one register (lanes::V8, GCC's vector extensions). Arithmetic, comparisons, bit operations
// and `mask ? a : b` are the language's own for both; what differs is named here: the bits of a
// double as an unsigned integer and back, the signed view of those bits, a fused multiply-add,
// a constant in every lane, and the lookup of a 16-entry table (one two-register permute,
// vpermt2pd, for eight lanes). Code written over these gives the same bits in every lane as its
// scalar instance (tests/kernels/common/test_pow_nonnegative.cpp checks it for pow).
// LSI_HOST_SIMD_LANES is 1 where V8 exists: GCC 12 or later, AVX-512, host code.
#pragma once
#include <cstdint>
#include <cstring>

#ifndef LSI_HOST_SIMD_LANES
#if defined(__GNUC__) && !defined(__clang__) && !defined(__INTEL_COMPILER) && __GNUC__ >= 12 && \
    defined(__AVX512F__) && !defined(__CUDACC__) && !defined(__HIPCC__) &&                      \
    !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
#define LSI_HOST_SIMD_LANES 1
#else
#define LSI_HOST_SIMD_LANES 0
#endif
#endif

#if LSI_HOST_SIMD_LANES
#include <immintrin.h>
#endif

namespace lsi::math::lanes {

// One double.
inline std::uint64_t bits_of(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline double real_of(std::uint64_t u) {
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}
inline std::int64_t signed_of(std::uint64_t u) { return static_cast<std::int64_t>(u); }
inline std::uint64_t unsigned_of(std::int64_t i) { return static_cast<std::uint64_t>(i); }
inline double fused_multiply_add(double a, double b, double c) { return __builtin_fma(a, b, c); }
// table[i] for i < 16.
inline double lookup16(const double* table, std::uint64_t i) { return table[i]; }
template <class Real>
inline Real splat(double c) {
  return Real{} + c;
}

#if LSI_HOST_SIMD_LANES
// Eight doubles; comparisons give I8 masks (all bits set where true), which `?:` takes.
typedef double V8 __attribute__((vector_size(64)));
typedef long long I8 __attribute__((vector_size(64)));
typedef unsigned long long U8 __attribute__((vector_size(64)));

inline __attribute__((always_inline)) U8 bits_of(V8 x) { return (U8)x; }
inline __attribute__((always_inline)) V8 real_of(U8 u) { return (V8)u; }
inline __attribute__((always_inline)) I8 signed_of(U8 u) { return (I8)u; }
inline __attribute__((always_inline)) U8 unsigned_of(I8 i) { return (U8)i; }
inline __attribute__((always_inline)) V8 fused_multiply_add(V8 a, V8 b, V8 c) {
  return (V8)_mm512_fmadd_pd((__m512d)a, (__m512d)b, (__m512d)c);
}
// table[i & 15] in each lane: the table's two halves permuted by the index's low 4 bits.
inline __attribute__((always_inline)) V8 lookup16(const double* table, U8 i) {
  V8 low, high;
  std::memcpy(&low, table, sizeof low);
  std::memcpy(&high, table + 8, sizeof high);
  return (V8)_mm512_permutex2var_pd((__m512d)low, (__m512i)i, (__m512d)high);
}
inline __attribute__((always_inline)) V8 load8(const double* p) {
  V8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline __attribute__((always_inline)) void store8(double* p, V8 v) { std::memcpy(p, &v, sizeof v); }
#endif

}  // namespace lsi::math::lanes
