# Thread-count determinism (issue: OpenMP): identical bits at 1-4 threads, equal to mpm3d_ref.
set(_ref "")
if(TARGET mpm3d_ref)
  set(_ref $<TARGET_FILE:mpm3d_ref>)
endif()
foreach(_case "two_blocks\;${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm\;207"
              "taylor_coarse\;${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm\;40"
              "legacy_taylor\;${CMAKE_SOURCE_DIR}/../shared/decks/Taylor.mpm\;60")
  list(GET _case 0 _name)
  list(GET _case 1 _deck)
  list(GET _case 2 _steps)
  add_test(NAME threads.${_name}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/thread_determinism.sh $<TARGET_FILE:mpm3d> ${_deck} ${_steps}
                   ${CMAKE_CURRENT_BINARY_DIR}/threads_${_name} ${_ref})
  set_tests_properties(threads.${_name} PROPERTIES SKIP_RETURN_CODE 77)
endforeach()
