// Software prefetch of point data for the host's blocked point loops (the two-phase P2G and G2P):
// a block of points reads or writes many point arrays ("streams", one per field component or
// point-interleaved record), more than the hardware's prefetchers follow at once, so that on
// points beyond the caches a block waits for memory at each stream's first line. Asked for one
// block ahead, the next block's lines arrive while this block computes.
// Host code only (GCC's and Clang's __builtin_prefetch); in device code prefetch_streams does
// nothing.
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::mpm::detail {

// A stream of point data: `bytes_per_point` bytes per point from `values`.
struct PointStream {
  const void* values;
  int bytes_per_point;
};

// The stream of one array of T per point, or of N interleaved T per point.
template <class T, int N = 1>
KOKKOS_FORCEINLINE_FUNCTION PointStream point_stream(const T* values) {
  return {values, static_cast<int>(sizeof(T)) * N};
}

// Asks the caches for points [q0, q1) of each stream. Addresses past the arrays' ends are
// harmless: a prefetch never faults. Always inlined, with the loop written here: GCC takes a
// function that only prefetches for one without side effects ("looping pure") and drops the
// calls to it (check a build with `objdump -d | grep prefetch`).
template <int Locality = 3, int N>
KOKKOS_FORCEINLINE_FUNCTION void prefetch_streams(const PointStream (&streams)[N], const int q0,
                                                  const int q1) {
#if defined(__GNUC__) && !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
  for (const PointStream& stream : streams) {
    const char* from =
        static_cast<const char*>(stream.values) + static_cast<long>(stream.bytes_per_point) * q0;
    const int bytes = stream.bytes_per_point * (q1 - q0);
    for (int line = 0; line < bytes; line += 64) __builtin_prefetch(from + line, 0, Locality);
  }
#else
  (void)streams;
  (void)q0;
  (void)q1;
#endif
}

}  // namespace lsi::mpm::detail
