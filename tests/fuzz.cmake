# Robustness tests (docs/RELIABILITY.md): decks found by fuzzing (tests/fuzz_regressions)
# must be refused cleanly, and the hand-mutated decks of tools/mutate_decks.py must each be
# accepted, refused with one `file:line:` line, or stopped by the health check - by mpm3d,
# and without a crash by mpm3d_ref.
find_package(Python3 COMPONENTS Interpreter)
if(Python3_Interpreter_FOUND)
  set(_mpm3d_ref_arg)
  if(TARGET mpm3d_ref)
    set(_mpm3d_ref_arg --ref $<TARGET_FILE:mpm3d_ref>)
  endif()
  file(GLOB _fuzz_regressions CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/fuzz_regressions/*.mpm)
  if(_fuzz_regressions)
    add_test(NAME fuzz_regressions
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/tools/mutate_decks.py
                     --mpm3d $<TARGET_FILE:mpm3d> ${_mpm3d_ref_arg}
                     --work ${CMAKE_CURRENT_BINARY_DIR}/fuzz_regressions --refused ${_fuzz_regressions})
  endif()
  add_test(NAME mutated_decks
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/tools/mutate_decks.py
                   --mpm3d $<TARGET_FILE:mpm3d> ${_mpm3d_ref_arg}
                   --work ${CMAKE_CURRENT_BINARY_DIR}/mutated_decks)
  set_tests_properties(mutated_decks PROPERTIES ENVIRONMENT OMP_NUM_THREADS=1)
endif()
