// In-register transposes of 8 points' values (one AVX-512 register of doubles) for the host's
// blocked P2G and G2P (p2g_block, g2p_block): the point loops there vectorise over the points
// (values of one field for consecutive points are contiguous), while the grid holds a node's
// fields together, so each block turns one layout into the other. Written with GCC's vector
// extensions rather than x86 intrinsics; LSI_MPM_HOST_TRANSPOSE is 1 only where they are
// available with AVX-512 (LSI_HOST_SIMD_LANES of kernels/common/simd_lanes.hpp: GCC 12 or later,
// host code). Everywhere else it is 0 and the callers keep their scalar copies, which give the
// same sums in the same order.
#pragma once

#include "kernels/common/simd_lanes.hpp"

// Defined beforehand (to 0), it chooses the scalar copies on any compiler (to compare both).
#ifndef LSI_MPM_HOST_TRANSPOSE
#define LSI_MPM_HOST_TRANSPOSE LSI_HOST_SIMD_LANES
#endif

#if LSI_MPM_HOST_TRANSPOSE
namespace lsi::mpm::detail::host_simd {

typedef double V8 __attribute__((vector_size(64)));
typedef double V4 __attribute__((vector_size(32)));
typedef double V2 __attribute__((vector_size(16)));

// Unaligned loads and stores of 8 or 4 consecutive doubles.
inline __attribute__((always_inline)) V8 load8(const double* p) {
  V8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline __attribute__((always_inline)) V4 load4(const double* p) {
  V4 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline __attribute__((always_inline)) void store8(double* p, const V8 v) {
  __builtin_memcpy(p, &v, sizeof v);
}

// p[0..6] += x[0..6] (4, 2 and 1 values wide: x[7] is not written anywhere).
inline __attribute__((always_inline)) void add7(double* p, const V8 x) {
  V4 a;
  V2 b;
  __builtin_memcpy(&a, p, sizeof a);
  __builtin_memcpy(&b, p + 4, sizeof b);
  a += __builtin_shufflevector(x, x, 0, 1, 2, 3);
  b += __builtin_shufflevector(x, x, 4, 5);
  __builtin_memcpy(p, &a, sizeof a);
  __builtin_memcpy(p + 4, &b, sizeof b);
  p[6] += x[6];
}

// r[i][j] becomes r[j][i] (8 x 8 doubles): pairs of rows interleaved, then pairs of pairs, then
// the 256-bit halves exchanged.
inline __attribute__((always_inline)) void transpose8(V8 r[8]) {
  V8 t[8], u[8];
  for (int i = 0; i < 8; i += 2) {
    t[i] = __builtin_shufflevector(r[i], r[i + 1], 0, 8, 2, 10, 4, 12, 6, 14);
    t[i + 1] = __builtin_shufflevector(r[i], r[i + 1], 1, 9, 3, 11, 5, 13, 7, 15);
  }
  // u[0]: columns 0, 4 of rows 0..3; u[1]: 2, 6; u[2]: 1, 5; u[3]: 3, 7; u[4..7]: rows 4..7.
  for (int h = 0; h < 8; h += 4) {
    u[h + 0] = __builtin_shufflevector(t[h + 0], t[h + 2], 0, 1, 8, 9, 4, 5, 12, 13);
    u[h + 1] = __builtin_shufflevector(t[h + 0], t[h + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    u[h + 2] = __builtin_shufflevector(t[h + 1], t[h + 3], 0, 1, 8, 9, 4, 5, 12, 13);
    u[h + 3] = __builtin_shufflevector(t[h + 1], t[h + 3], 2, 3, 10, 11, 6, 7, 14, 15);
  }
  r[0] = __builtin_shufflevector(u[0], u[4], 0, 1, 2, 3, 8, 9, 10, 11);
  r[4] = __builtin_shufflevector(u[0], u[4], 4, 5, 6, 7, 12, 13, 14, 15);
  r[2] = __builtin_shufflevector(u[1], u[5], 0, 1, 2, 3, 8, 9, 10, 11);
  r[6] = __builtin_shufflevector(u[1], u[5], 4, 5, 6, 7, 12, 13, 14, 15);
  r[1] = __builtin_shufflevector(u[2], u[6], 0, 1, 2, 3, 8, 9, 10, 11);
  r[5] = __builtin_shufflevector(u[2], u[6], 4, 5, 6, 7, 12, 13, 14, 15);
  r[3] = __builtin_shufflevector(u[3], u[7], 0, 1, 2, 3, 8, 9, 10, 11);
  r[7] = __builtin_shufflevector(u[3], u[7], 4, 5, 6, 7, 12, 13, 14, 15);
}

// From 8 points' rows of 6 doubles (point p's at row[p]) to 6 vectors of 8 points: out[c] lane p
// is row[p][c]. Reads exactly the 6 doubles of each row (two overlapping loads of 4: 0..3 and
// 2..5), so never past a row's end.
inline __attribute__((always_inline)) void gather_rows6(const double* const row[8], V8 out[6]) {
  V8 x[4], z[4];
  for (int j = 0; j < 4; ++j) {  // points j and j + 4 in the two halves
    x[j] = __builtin_shufflevector(load4(row[j]), load4(row[j + 4]), 0, 1, 2, 3, 4, 5, 6, 7);
    z[j] =
        __builtin_shufflevector(load4(row[j] + 2), load4(row[j + 4] + 2), 0, 1, 2, 3, 4, 5, 6, 7);
  }
  // 4 x 4 transposes in both halves: lanes 0..3 points 0..3, lanes 4..7 points 4..7.
  const V8 s0 = __builtin_shufflevector(x[0], x[1], 0, 8, 2, 10, 4, 12, 6, 14);
  const V8 s1 = __builtin_shufflevector(x[0], x[1], 1, 9, 3, 11, 5, 13, 7, 15);
  const V8 s2 = __builtin_shufflevector(x[2], x[3], 0, 8, 2, 10, 4, 12, 6, 14);
  const V8 s3 = __builtin_shufflevector(x[2], x[3], 1, 9, 3, 11, 5, 13, 7, 15);
  out[0] = __builtin_shufflevector(s0, s2, 0, 1, 8, 9, 4, 5, 12, 13);
  out[2] = __builtin_shufflevector(s0, s2, 2, 3, 10, 11, 6, 7, 14, 15);
  out[1] = __builtin_shufflevector(s1, s3, 0, 1, 8, 9, 4, 5, 12, 13);
  out[3] = __builtin_shufflevector(s1, s3, 2, 3, 10, 11, 6, 7, 14, 15);
  const V8 w0 = __builtin_shufflevector(z[0], z[1], 2, 10, 6, 14, 2, 10, 6, 14);
  const V8 w1 = __builtin_shufflevector(z[0], z[1], 3, 11, 7, 15, 3, 11, 7, 15);
  const V8 w2 = __builtin_shufflevector(z[2], z[3], 2, 10, 6, 14, 2, 10, 6, 14);
  const V8 w3 = __builtin_shufflevector(z[2], z[3], 3, 11, 7, 15, 3, 11, 7, 15);
  // w0: (p0, p1, p4, p5) of value 4 (twice); w2: (p2, p3, p6, p7).
  out[4] = __builtin_shufflevector(w0, w2, 0, 1, 8, 9, 2, 3, 10, 11);
  out[5] = __builtin_shufflevector(w1, w3, 0, 1, 8, 9, 2, 3, 10, 11);
}

}  // namespace lsi::mpm::detail::host_simd
#endif
