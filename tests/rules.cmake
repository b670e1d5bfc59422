# The rules (cxx/core/rules.hpp, fortran_ref/rules.f90; docs/FROM_MPM3D_F90.md "The rules").
# rules_add(NAME DECK STEPS OPTIONS...): under OPTIONS (--rules ..., --rule NAME=VALUE) mpm3d
# on 1 and 2 threads, mpm3d with every stage from Fortran and mpm3d_ref give the same state
# bit for bit, and a state that differs from the plain run's (fortran_ref/xcheck.sh rules).
# Included from tests/CMakeLists.txt; each group of rules adds its cases in its own file.
if(TARGET mpm3d AND TARGET mpm3d_ref AND MPM3D_H5DIFF)
  function(rules_add name deck steps)
    add_test(NAME rules.${name}
             COMMAND sh ${CMAKE_SOURCE_DIR}/fortran_ref/xcheck.sh rules
                     ${CMAKE_CURRENT_BINARY_DIR}/rules/${name} ${deck}
                     $<TARGET_FILE:mpm3d> $<TARGET_FILE:mpm3d_ref> ${MPM3D_H5DIFF} ${steps} ${ARGN})
    set_tests_properties(rules.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS rules)
  endfunction()
  set(_rules_inputs ${CMAKE_SOURCE_DIR}/inputs)
  set(_rules_shared ${CMAKE_SOURCE_DIR}/../shared/decks)
  # Deck-level rules (both readers).
  rules_add(bulk_book ${_rules_inputs}/explosives/slab_small.mpm 40 --rule bulk_book=ignore)
  rules_add(deck_reals ${_rules_inputs}/impact/two_blocks.mpm 40 --rule deck_reals=single)
  rules_add(time_step ${_rules_inputs}/taylor/taylor_coarse.mpm 40 --rule time_step=current)
  rules_add(program_current ${_rules_inputs}/taylor/taylor_coarse.mpm 40 --rules current)
  rules_add(original_book ${_rules_inputs}/explosives/slab_small.mpm 40 --rules original)
  # Rule start_temp: the particles start at 293, not at the card's room temperature 20.
  rules_add(start_temp ${_rules_inputs}/rules/john_celsius.mpm 40 --rule start_temp=293)
  # Rule contact: the originals' contact (no recontact stage, forces by the full dt), MUSL
  # and USF with friction.
  rules_add(contact_musl ${_rules_inputs}/contact/spheres.mpm 120 --rule contact=original)
  rules_add(contact_usf ${_rules_inputs}/contact/oblique.mpm 400 --rule contact=original)
  # A restart keeps the rules of the run it continues (the checkpoint records them).
  add_test(NAME rules.restart
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/rules_restart.sh $<TARGET_FILE:mpm3d>
                   ${_rules_inputs}/rules/bar_bulk_book.mpm ${CMAKE_CURRENT_BINARY_DIR}/rules/restart)
  set_tests_properties(rules.restart PROPERTIES TIMEOUT 120 LABELS rules)
  # pressure_q acts on the written pressure only (no state to compare): the curve files.
  add_test(NAME rules.pressure_q
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/rules_pressure.sh $<TARGET_FILE:mpm3d>
                   ${_rules_inputs}/fluids/viscous_column.mpm ${CMAKE_CURRENT_BINARY_DIR}/rules/pressure_q)
  set_tests_properties(rules.pressure_q PROPERTIES TIMEOUT 120 LABELS rules)
  # rules_reference(STEM DECK OPTIONS...): DECK under OPTIONS against the original program's
  # own output for it (tests/reference/rules/STEM: every column within the bounds), and under
  # our rules beyond them (the rule is what brings the agreement). tests/rules_reference.py.
  find_package(Python3 COMPONENTS Interpreter)
  function(rules_reference stem deck)
    # REFUSED_BY_OURS: a deck our rules refuse (the reader's check has its own test): no _ours run.
    set(_args ${ARGN})
    list(FIND _args REFUSED_BY_OURS _refused)
    list(REMOVE_ITEM _args REFUSED_BY_OURS)
    set(_ref ${CMAKE_CURRENT_SOURCE_DIR}/reference/rules/${stem})
    add_test(NAME rules_reference.${stem}
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/rules_reference.py
                     $<TARGET_FILE:mpm3d> ${deck} ${_ref} ${_args})
    set_tests_properties(rules_reference.${stem} PROPERTIES TIMEOUT 300 LABELS rules)
    if(_refused EQUAL -1)
      add_test(NAME rules_reference.${stem}_ours
               COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/rules_reference.py
                       $<TARGET_FILE:mpm3d> ${deck} ${_ref} --beyond)
      set_tests_properties(rules_reference.${stem}_ours PROPERTIES TIMEOUT 300 LABELS rules)
    endif()
  endfunction()
  if(Python3_Interpreter_FOUND)
    rules_reference(bar_bulk_book ${_rules_inputs}/rules/bar_bulk_book.mpm --rules original)
    rules_reference(block_single_reals ${_rules_inputs}/rules/block_single_reals.mpm --rules original)
    rules_reference(slope ${_rules_inputs}/granular/slope.mpm --rules original)
    rules_reference(block_floor_sgmp ${_rules_inputs}/hyperelastic/block_floor_sgmp.mpm --rules original REFUSED_BY_OURS)
    rules_reference(soft_beam_tl ${_rules_inputs}/hyperelastic/soft_beam_tl.mpm --rules original)
    rules_reference(viscous_column ${_rules_inputs}/fluids/viscous_column.mpm --rules original)
    rules_reference(j2eos_linear ${_rules_inputs}/methods/j2eos_linear.mpm --rules original)
    rules_reference(john_wall ${_rules_inputs}/rules/john_wall.mpm --rules original)
    rules_reference(john_celsius ${_rules_inputs}/rules/john_celsius.mpm --rules original)
    rules_reference(spheres ${_rules_inputs}/contact/spheres.mpm --rules original)
    rules_reference(oblique ${_rules_inputs}/contact/oblique.mpm --rules original)
    rules_reference(sphere_sand ${_rules_inputs}/contact/sphere_sand.mpm --rules original)
    rules_reference(clay_column ${_rules_inputs}/clay/clay_column.mpm --rules original)
    rules_reference(water_tube_mg ${CMAKE_CURRENT_SOURCE_DIR}/decks/water_tube_mg.mpm --rules original)
  endif()
  file(GLOB _rules_groups ${CMAKE_CURRENT_SOURCE_DIR}/rules_*.cmake)
  foreach(_g ${_rules_groups})
    include(${_g})
  endforeach()
endif()
