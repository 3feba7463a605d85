// The execution space of the study programs (tools/studies/*_study.cpp): Serial when Kokkos has
// it (the one-thread runs the docs quote), else the default host space.
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::test {
#ifdef KOKKOS_ENABLE_SERIAL
using StudySpace = Kokkos::Serial;
#else
using StudySpace = Kokkos::DefaultHostExecutionSpace;
#endif
}  // namespace lsi::test
