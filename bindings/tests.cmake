# Tests of the C and Fortran bindings (docs/DESIGN.md section 5a). Included from
# tests/CMakeLists.txt:  include(${CMAKE_SOURCE_DIR}/bindings/tests.cmake OPTIONAL)
#   bindings.state.*          the library, called from Fortran, writes the same state file
#                             as the mpm3d program, bit for bit (h5diff, no tolerance)
#   bindings.capi_errors      error codes and messages of the C API (a C99 program)
#   bindings.install_example  cmake --install, then find_package and pkg-config users
include_guard(GLOBAL)
if(NOT TARGET mpm3d_capi)
  return()
endif()

set(_mpm3d_bt ${CMAKE_SOURCE_DIR}/bindings/tests)
set(_mpm3d_bw ${CMAKE_BINARY_DIR}/bindings/test_work)
file(MAKE_DIRECTORY ${_mpm3d_bw})
find_program(MPM3D_BASH bash REQUIRED)
find_program(MPM3D_H5DIFF h5diff HINTS /usr/bin)
if(NOT MPM3D_H5DIFF)
  set(MPM3D_H5DIFF /usr/bin/h5diff)  # the test reports it missing
endif()

add_executable(mpm3d_bindings_fortran_state ${_mpm3d_bt}/fortran_state.f90)
set_target_properties(mpm3d_bindings_fortran_state PROPERTIES
  Fortran_MODULE_DIRECTORY ${CMAKE_BINARY_DIR}/bindings/test_modules)
target_compile_options(mpm3d_bindings_fortran_state PRIVATE ${MPM3D_FORTRAN_FLAGS} -Wall)
target_link_libraries(mpm3d_bindings_fortran_state PRIVATE MPM3D::mpm3d_fortran)

add_executable(mpm3d_bindings_capi_errors ${_mpm3d_bt}/capi_errors.c)
set_target_properties(mpm3d_bindings_capi_errors PROPERTIES
  C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(mpm3d_bindings_capi_errors PRIVATE -Wall -Wextra -pedantic)
target_link_libraries(mpm3d_bindings_capi_errors PRIVATE MPM3D::mpm3d m)

# (a) bit for bit: library from Fortran == program. name, deck, kernels.
function(mpm3d_bindings_state_test name deck)
  add_test(NAME bindings.state.${name}
    COMMAND ${MPM3D_BASH} ${_mpm3d_bt}/compare_state.sh $<TARGET_FILE:mpm3d>
            $<TARGET_FILE:mpm3d_bindings_fortran_state> ${MPM3D_H5DIFF} ${deck}
            ${_mpm3d_bw}/state_${name} 60 ${ARGN})
  set_tests_properties(bindings.state.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120
                       LABELS bindings)
endfunction()
mpm3d_bindings_state_test(drop_blocks ${_mpm3d_bt}/decks/drop_blocks.mpm)
mpm3d_bindings_state_test(taylor ${CMAKE_SOURCE_DIR}/../shared/decks/Taylor.mpm)
# The kernel selection goes through the API too (skipped without Fortran kernels).
mpm3d_bindings_state_test(drop_blocks_mixed_kernels ${_mpm3d_bt}/decks/drop_blocks.mpm
                          p2g=fortran,stress=fortran)

# (b) error paths of the C API.
add_test(NAME bindings.capi_errors
  COMMAND mpm3d_bindings_capi_errors ${_mpm3d_bt}/decks/drop_blocks.mpm ${_mpm3d_bw})
set_tests_properties(bindings.capi_errors PROPERTIES TIMEOUT 60 LABELS bindings)

# (c) installation, find_package(MPM3D) and pkg-config.
add_test(NAME bindings.install_example
  COMMAND ${MPM3D_BASH} ${_mpm3d_bt}/install_example.sh ${CMAKE_COMMAND} ${CMAKE_BINARY_DIR}
          ${CMAKE_SOURCE_DIR} ${_mpm3d_bw}/install $<CONFIG> ${CMAKE_Fortran_COMPILER} ${CMAKE_C_COMPILER})
set_tests_properties(bindings.install_example PROPERTIES TIMEOUT 180 LABELS bindings)
