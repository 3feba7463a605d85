# Kokkos: a user's own install (-DKokkos_ROOT=..., e.g. with CUDA) is used as it is and nothing is
# built. Otherwise ci/kokkos.sh builds Kokkos with the Serial and OpenMP backends from Debian's
# `trilinos` source package, once, into a cache outside the build tree (LSI_CACHE, default
# ~/.cache/lsi), and later configurations reuse it.
if(NOT Kokkos_ROOT AND NOT DEFINED ENV{Kokkos_ROOT})
  execute_process(COMMAND bash ${CMAKE_SOURCE_DIR}/ci/kokkos.sh
                  OUTPUT_VARIABLE _lsi_kokkos_prefix OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE _lsi_kokkos_rc)
  if(NOT _lsi_kokkos_rc EQUAL 0)
    message(FATAL_ERROR "Building Kokkos from Debian's trilinos source failed (see above). "
                        "Pass -DKokkos_ROOT=<your Kokkos install> to use your own.")
  endif()
  set(Kokkos_ROOT "${_lsi_kokkos_prefix}" CACHE PATH "Kokkos install prefix" FORCE)
endif()
find_package(Kokkos REQUIRED)
message(STATUS "lsi: Kokkos ${Kokkos_VERSION} from ${Kokkos_DIR}")
foreach(_backend SERIAL OPENMP CUDA)
  kokkos_check(DEVICES ${_backend} RETURN_VALUE _has)
  if(_has)
    list(APPEND LSI_KOKKOS_BACKENDS ${_backend})
  endif()
endforeach()
message(STATUS "lsi: Kokkos backends: ${LSI_KOKKOS_BACKENDS}")
