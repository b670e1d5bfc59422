# Thread-count determinism (issue: OpenMP): identical bits at 1-4, 8 and 16 threads, equal to mpm3d_ref.
set(_mpm3d_ref_exe "")
if(TARGET mpm3d_ref)
  set(_mpm3d_ref_exe $<TARGET_FILE:mpm3d_ref>)
endif()
# mpm3d_thread_test(NAME DECK STEPS [OPTIONS...]): OPTIONS go to mpm3d and mpm3d_ref.
function(mpm3d_thread_test name deck steps)
  add_test(NAME threads.${name}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/thread_determinism.sh $<TARGET_FILE:mpm3d> ${deck} ${steps}
                   ${CMAKE_CURRENT_BINARY_DIR}/threads_${name} "${_mpm3d_ref_exe}" ${ARGN})
  set_tests_properties(threads.${name} PROPERTIES SKIP_RETURN_CODE 77)
endfunction()
mpm3d_thread_test(two_blocks ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm 207)
mpm3d_thread_test(taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm 40)
mpm3d_thread_test(legacy_taylor ${CMAKE_SOURCE_DIR}/../shared/decks/Taylor.mpm 60)
mpm3d_thread_test(slab_small ${CMAKE_SOURCE_DIR}/inputs/explosives/slab_small.mpm 200)
mpm3d_thread_test(slope ${CMAKE_SOURCE_DIR}/inputs/granular/slope.mpm 200)
# A cohesionless column collapsing (t = 37 ms): the tension cut-off's opening kept out of the volumes.
mpm3d_thread_test(granular_column ${CMAKE_SOURCE_DIR}/tests/decks/granular_column.mpm 3000)
mpm3d_thread_test(legacy_deto1k ${CMAKE_SOURCE_DIR}/../shared/decks/Deto1k.mpm 60)
mpm3d_thread_test(legacy_tnt3d ${CMAKE_SOURCE_DIR}/../shared/decks/TNT3D.mpm 30)
# Hypervelocity (sjcf with failure, Mie-Gruneisen in compression and tension), run to its
# end: the EOS's tension branch is reached after the shock has crossed the plate.
mpm3d_thread_test(lead_sphere_small ${CMAKE_SOURCE_DIR}/inputs/impact/lead_sphere_small.mpm 2118)
# The adaptive background grid (regrids every 5 steps; the rising block also forces one).
mpm3d_thread_test(two_blocks_adaptive ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm 207 --regrid-every 5)
mpm3d_thread_test(taylor_coarse_adaptive ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm 40 --regrid-every 5)
mpm3d_thread_test(rising_block_adaptive ${CMAKE_CURRENT_SOURCE_DIR}/decks/rising_block.mpm 100)
# GIMP shape functions and multi-velocity contact (issue 5).
mpm3d_thread_test(two_blocks_gimp ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks_gimp.mpm 60)
mpm3d_thread_test(spheres ${CMAKE_SOURCE_DIR}/inputs/contact/spheres.mpm 120)
mpm3d_thread_test(sliding_block ${CMAKE_SOURCE_DIR}/inputs/contact/sliding_block.mpm 80)
mpm3d_thread_test(two_blocks_gimp_adaptive ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks_gimp.mpm 60 --regrid-every 4)
# The current MPM3D-F90's neo-Hookean solids, vsin, part loads, UVFp (issue 16).
mpm3d_thread_test(free_soft_beam ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/free_soft_beam_coarse.mpm 481)
mpm3d_thread_test(neo_block_gimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/neo_block_gimp.mpm 88)
mpm3d_thread_test(cantilever_quasi_static ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cantilever_quasi_static.mpm 300)
mpm3d_thread_test(plate_hole_drda ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/plate_hole_drda.mpm 300)
mpm3d_thread_test(soft_beam_tl ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/soft_beam_tl.mpm 400)
mpm3d_thread_test(soft_beam_sgtl ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/soft_beam_sgtl.mpm 400)
mpm3d_thread_test(current_soft_beam_tl ${CMAKE_SOURCE_DIR}/../shared/decks/current/SoftBeam_SBTL_0p1mesh_SBTL.mpm 300)
mpm3d_thread_test(current_free_soft_beam ${CMAKE_SOURCE_DIR}/../shared/decks/current/FreeSoftBeam_MPM_v0p3_FreeSB_MPM.mpm 300)
# B-spline MPM (bimp) with the current version's two fixed node layers.
mpm3d_thread_test(cook_membrane_bimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_bimp.mpm 400)
mpm3d_thread_test(current_cook_bimp ${CMAKE_SOURCE_DIR}/../shared/decks/current/Cook_membrane_BSMPM5776p_Cookmo_Bimp.mpm 200)
# GIMP on a current-version deck (the current program's quarter-cell particle half-size).
mpm3d_thread_test(cook_membrane_gimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_gimp.mpm 150)
# Smoothed-gradient MPM (sgmp): MUSL and USF.
mpm3d_thread_test(cook_membrane_sgmp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_sgmp.mpm 400)
mpm3d_thread_test(sg_usf_blocks ${CMAKE_CURRENT_SOURCE_DIR}/decks/sg_usf_blocks.mpm 170)
mpm3d_thread_test(current_cook_sg ${CMAKE_SOURCE_DIR}/../shared/decks/current/Cook_membrane_SG5776p_Cookmo_SG.mpm 200)
mpm3d_thread_test(current_sgdeto1k ${CMAKE_SOURCE_DIR}/../shared/decks/current/SGDeto1k.mpm 300)
# Patches at rest: a detonation sweeping a bar at rest (sgmp, run to its end), a block
# striking a block at rest (two-cell patches: the thinnest ring around the moving ones).
mpm3d_thread_test(bar_sgmp ${CMAKE_SOURCE_DIR}/inputs/explosives/bar_sgmp.mpm 983)
mpm3d_thread_test(sg_rest_blocks ${CMAKE_CURRENT_SOURCE_DIR}/decks/sg_rest_blocks.mpm 510 --patch-cells 2)
# The same bar, shorter and two cells thick, with the trilinear and the B-spline stencils.
mpm3d_thread_test(bar_linear ${CMAKE_CURRENT_SOURCE_DIR}/decks/bar_linear.mpm 295)
mpm3d_thread_test(bar_bimp ${CMAKE_CURRENT_SOURCE_DIR}/decks/bar_bimp.mpm 311)
mpm3d_thread_test(dam_break_coarse ${CMAKE_SOURCE_DIR}/inputs/fluids/dam_break_coarse.mpm 297)
mpm3d_thread_test(current_dam_break ${CMAKE_SOURCE_DIR}/../shared/decks/current/DamBreak_SGMPM_Dam_SGR2.mpm 300)
# The newest version: clay (our column), the R1 dam breaks (linear and sgmp).
mpm3d_thread_test(clay_column ${CMAKE_SOURCE_DIR}/inputs/clay/clay_column.mpm 150)
mpm3d_thread_test(newest_dam_r1 ${CMAKE_SOURCE_DIR}/../shared/decks/newest/DamBreak_MPM_R1_Dam_R1.mpm 300)
mpm3d_thread_test(newest_dam_sgr1 ${CMAKE_SOURCE_DIR}/../shared/decks/newest/DamBreak_SGMPM_R1_Dam_SGR1.mpm 300)
# The particles' storage order (tests/particle_order.sh): deck order keeps every bit too.
mpm3d_thread_test(two_blocks_deck_order ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm 207 --particle-order deck)
add_test(NAME particle_order
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/particle_order.sh $<TARGET_FILE:mpm3d> "${_mpm3d_ref_exe}"
                 ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/particle_order)
# Parallel regions a step, counted from outside by tools/omp_regions.c (LD_PRELOAD; not in
# the sanitizer build, where the ASan runtime must come first among the loaded libraries).
if(NOT MPM3D_SANITIZE)
  add_test(NAME omp_regions_per_step
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/omp_regions.sh $<TARGET_FILE:mpm3d> $<TARGET_FILE:mpm3d_omp_regions>
                   ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm ${CMAKE_CURRENT_BINARY_DIR}/omp_regions)
endif()
# Transfer method x material family: the decks of inputs/methods/ (tools/method_matrix.py).
mpm3d_thread_test(methods_j2eos_linear ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_linear.mpm 150)
mpm3d_thread_test(methods_j2eos_gimp ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_gimp.mpm 150)
mpm3d_thread_test(methods_j2eos_bimp ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_bimp.mpm 150)
mpm3d_thread_test(methods_j2eos_sgmp ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_sgmp.mpm 150)
mpm3d_thread_test(methods_neoh_linear ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_linear.mpm 150)
mpm3d_thread_test(methods_neoh_gimp ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_gimp.mpm 150)
mpm3d_thread_test(methods_neoh_bimp ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_bimp.mpm 150)
mpm3d_thread_test(methods_neoh_sgmp ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_sgmp.mpm 150)
mpm3d_thread_test(methods_neoh_tlmp ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_TLmp.mpm 150)
mpm3d_thread_test(methods_null_linear ${CMAKE_SOURCE_DIR}/inputs/methods/null_linear.mpm 150)
mpm3d_thread_test(methods_null_gimp ${CMAKE_SOURCE_DIR}/inputs/methods/null_gimp.mpm 150)
mpm3d_thread_test(methods_null_bimp ${CMAKE_SOURCE_DIR}/inputs/methods/null_bimp.mpm 150)
mpm3d_thread_test(methods_null_sgmp ${CMAKE_SOURCE_DIR}/inputs/methods/null_sgmp.mpm 150)
mpm3d_thread_test(methods_hiex_linear ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_linear.mpm 150)
mpm3d_thread_test(methods_hiex_gimp ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_gimp.mpm 150)
mpm3d_thread_test(methods_hiex_bimp ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_bimp.mpm 150)
mpm3d_thread_test(methods_hiex_sgmp ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_sgmp.mpm 150)
mpm3d_thread_test(methods_dpm_linear ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_linear.mpm 150)
mpm3d_thread_test(methods_dpm_gimp ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_gimp.mpm 150)
mpm3d_thread_test(methods_dpm_bimp ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_bimp.mpm 150)
mpm3d_thread_test(methods_dpm_sgmp ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_sgmp.mpm 150)
