// main() for tests that use Kokkos: initialise it once around all tests.
#include <Kokkos_Core.hpp>
#include <cstdlib>
#include <gtest/gtest.h>

int main(int argc, char** argv) {
  // Without a binding policy Kokkos prints a warning on stdout, which gtest's test discovery
  // would read as test names: choose the unit-testing policy unless the caller set one.
  setenv("OMP_PROC_BIND", "false", /*overwrite=*/0);
  ::testing::InitGoogleTest(&argc, argv);
  Kokkos::ScopeGuard kokkos(argc, argv);
  return RUN_ALL_TESTS();
}
