// The Kokkos execution spaces compiled in: typed tests run once per backend (Picasso-style).
#pragma once
#include <Kokkos_Core.hpp>
#include <gtest/gtest.h>

namespace lsi::test {
template <class... T>
struct List {};
using Backends = ::testing::Types<
#if defined(KOKKOS_ENABLE_SERIAL)
    Kokkos::Serial
#endif
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
    ,
#endif
#if defined(KOKKOS_ENABLE_OPENMP)
    Kokkos::OpenMP
#endif
#if defined(KOKKOS_ENABLE_CUDA)
    ,
    Kokkos::Cuda
#endif
    >;
}  // namespace lsi::test
