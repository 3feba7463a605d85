# `cmake --install BUILD --prefix P`: the commands, the libraries a C++ project builds on with their
# headers, and the CMake package `lsi` (docs/guide/cmake_package.md):
#
#   P/bin/lsi, P/bin/lsi-mpi                  the commands (lsi-mpi where MPI was found)
#   P/include/lsi/{kernels,sweeps,model,io}/  the headers, included as "kernels/closed_form/..."
#   P/lib/liblsi_{sweeps,model,io}.a         the compiled libraries
#   P/lib/cmake/lsi/                          lsiConfig.cmake, lsiConfigVersion.cmake, lsiTargets*
#   P/lib/pythonX.Y/site-packages/lsi*.so     the Python module where it is built
#                                             (LSI_PYTHON_INSTALL_DIR, python/CMakeLists.txt)
#
# The exported targets, lsi::NAME (the build tree's lsi_NAME):
#   closed_form  kernels/closed_form and kernels/common: header-only, on Kokkos' macros and math
#   mpm          kernels/mpm: header-only Kokkos kernels (with closed_form)
#   kernels      both
#   sweeps       sampling, statistics, calibration (Eigen)
#   model        a scene as typed inputs, the closed-form methods, the MPM runner (nlohmann-json)
#   io           scene files parsed, HDF5 results written (HDF5)
# lsi_app (the subcommands) belongs to the commands and is not installed.
include(CMakePackageConfigHelpers)

set(LSI_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/lsi)
set(_lsi_exported lsi_closed_form lsi_mpm lsi_kernels lsi_sweeps lsi_model lsi_io)
set(_lsi_compiled lsi_sweeps lsi_model lsi_io)

foreach(_target IN LISTS _lsi_exported)
  string(REGEX REPLACE "^lsi_" "" _name ${_target})
  set_target_properties(${_target} PROPERTIES EXPORT_NAME ${_name})
endforeach()

# sweeps/ names the source tree as its include directory; in an install the headers come from
# lsi_kernels, which it links.
get_target_property(_lsi_sweeps_dirs lsi_sweeps INTERFACE_INCLUDE_DIRECTORIES)
set(_lsi_build_dirs)
foreach(_dir IN LISTS _lsi_sweeps_dirs)
  list(APPEND _lsi_build_dirs "$<BUILD_INTERFACE:${_dir}>")
endforeach()
set_property(TARGET lsi_sweeps PROPERTY INTERFACE_INCLUDE_DIRECTORIES ${_lsi_build_dirs})

# What a consumer of the compiled libraries must share with their build: the instruction set
# (Eigen's alignment of the vectors that cross the library boundary follows it) and the
# sanitizers' runtime.
foreach(_target IN LISTS _lsi_compiled)
  if(LSI_NATIVE_ARCH)
    target_compile_options(${_target} INTERFACE $<INSTALL_INTERFACE:-march=native>)
  endif()
  if(LSI_SANITIZE)
    target_link_options(${_target} INTERFACE $<INSTALL_INTERFACE:-fsanitize=${LSI_SANITIZE}>)
  endif()
endforeach()

set(_lsi_commands lsi)
if(TARGET lsi-mpi)
  list(APPEND _lsi_commands lsi-mpi)
endif()
# An installed command keeps the paths of the shared libraries it was linked with (a Kokkos or
# HDF5 outside the system's folders).
set_target_properties(${_lsi_commands} PROPERTIES INSTALL_RPATH_USE_LINK_PATH ON)
install(TARGETS ${_lsi_commands} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The Python module `lsi` (docs/guide/python.md): one file, importable with its folder on
# PYTHONPATH; it keeps the paths of its shared libraries as the commands do.
if(TARGET lsi_python)
  set_target_properties(lsi_python PROPERTIES INSTALL_RPATH_USE_LINK_PATH ON)
  install(TARGETS lsi_python LIBRARY DESTINATION ${LSI_PYTHON_INSTALL_DIR})
endif()

install(TARGETS ${_lsi_exported} EXPORT lsiTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(_room kernels sweeps model io)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_room}/ DESTINATION ${LSI_INSTALL_INCLUDEDIR}/${_room}
          FILES_MATCHING PATTERN "*.hpp")
endforeach()

install(EXPORT lsiTargets NAMESPACE lsi:: DESTINATION ${LSI_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/lsiConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/lsiConfig.cmake
                              INSTALL_DESTINATION ${LSI_INSTALL_CMAKEDIR})
# Before 1.0 a minor version may change the interfaces: only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/lsiConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/lsiConfig.cmake ${PROJECT_BINARY_DIR}/lsiConfigVersion.cmake
        DESTINATION ${LSI_INSTALL_CMAKEDIR})
