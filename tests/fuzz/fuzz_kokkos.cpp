// ensure_kokkos() for the libFuzzer build (tests/fuzz/CMakeLists.txt, LSI_FUZZ_LIBFUZZER), which
// compiles the parser sources without model/mpm_runner.cpp (the MPM solver, not fuzzed): the
// same behaviour as the runner's, Kokkos started once and finalised at exit.
#include <Kokkos_Core.hpp>
#include <cstdlib>

#include "model/mpm_runner.hpp"

namespace lsi {

void ensure_kokkos() {
  if (Kokkos::is_initialized()) return;
  setenv("OMP_PROC_BIND", "false", /*overwrite=*/0);
  Kokkos::initialize();
  std::atexit([] {
    if (Kokkos::is_initialized()) Kokkos::finalize();
  });
}

}  // namespace lsi
