# The current MPM3D-F90's public decks (../shared/decks/current) against the current
# program's own results (../shared/reference/current): energies and curves row by row over
# the first steps, within a tolerance at the print resolution of those files (four digits).
# Skipped when ../shared is absent.
find_package(Python3 COMPONENTS Interpreter)
if(NOT Python3_Interpreter_FOUND)
  return()
endif()
set(_cur_decks ${CMAKE_SOURCE_DIR}/../shared/decks/current)
set(_cur_ref ${CMAKE_SOURCE_DIR}/../shared/reference/current)
# current_reference_test(NAME DECK_BASE STEPS TOL [--skip-internal])
function(current_reference_test name base steps tol)
  add_test(NAME current_reference.${name}
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/current_reference.py ${ARGN} $<TARGET_FILE:mpm3d>
                   ${_cur_decks}/${base}.mpm ${_cur_ref}/${base} ${steps} ${tol}
                   ${CMAKE_CURRENT_BINARY_DIR}/current_reference_${name} --threads 2)
  set_tests_properties(current_reference.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
endfunction()
# B-spline MPM (bimp) with neoh, QuLo, Damp, smoo: Cook's membrane.
current_reference_test(cook_bimp Cook_membrane_BSMPM5776p_Cookmo_Bimp 2000 1e-3)
# Smoothed-gradient MPM (sgmp) with neoh, QuLo, Damp, smoo: Cook's membrane.
current_reference_test(cook_sg Cook_membrane_SG5776p_Cookmo_SG 2000 1e-3)
# The dam break: the current version's null water (bulk modulus, viscosity), its weakly
# compressible EOS, sgmp, gravity: kinetic energy and the surge front's particles (the
# water's internal energy, 0.2 % of its energy, differs: docs/CURRENT_DECKS.md).
current_reference_test(dam_break DamBreak_SGMPM_Dam_SGR2 2000 1e-3 --skip-internal)
