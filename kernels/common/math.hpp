// Math functions usable inside Kokkos kernels on every backend (Serial, OpenMP, CUDA), for Kokkos
// 3.4 (functions in Kokkos::Experimental) and 4.x (functions in Kokkos::).
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::math {

#if KOKKOS_VERSION >= 30700
using Kokkos::cos;
using Kokkos::fabs;
using Kokkos::floor;
using Kokkos::isfinite;
using Kokkos::isinf;
using Kokkos::nearbyint;
using Kokkos::pow;
using Kokkos::sin;
using Kokkos::sqrt;
using Kokkos::tan;
#else
using Kokkos::Experimental::cos;
using Kokkos::Experimental::fabs;
using Kokkos::Experimental::floor;
using Kokkos::Experimental::isfinite;
using Kokkos::Experimental::isinf;
using Kokkos::Experimental::nearbyint;
using Kokkos::Experimental::pow;
using Kokkos::Experimental::sin;
using Kokkos::Experimental::sqrt;
using Kokkos::Experimental::tan;
#endif

KOKKOS_INLINE_FUNCTION constexpr double pi() { return 3.14159265358979323846; }
KOKKOS_INLINE_FUNCTION constexpr double degrees_to_radians(double deg) {
  return deg * pi() / 180.0;
}
KOKKOS_INLINE_FUNCTION constexpr double infinity() { return __builtin_huge_val(); }
KOKKOS_INLINE_FUNCTION constexpr double quiet_nan() { return __builtin_nan(""); }
KOKKOS_INLINE_FUNCTION constexpr double min(double a, double b) { return a < b ? a : b; }
KOKKOS_INLINE_FUNCTION constexpr double max(double a, double b) { return a > b ? a : b; }

// a b + c rounded once, on every backend: for code whose rounding must not depend on whether the
// compiler fuses a written a * b + c (GCC does so with -march=native, by context).
KOKKOS_FORCEINLINE_FUNCTION double fused_multiply_add(double a, double b, double c) {
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
  return ::fma(a, b, c);
#else
  return __builtin_fma(a, b, c);
#endif
}

}  // namespace lsi::math
