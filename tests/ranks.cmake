# MPI ranks x OpenMP threads (issue 17): identical bits for any ranks x threads, equal to one
# process and to mpm3d_ref (tests/rank_determinism.sh). Only when mpm3d is built with MPI.
if(MPM3D_MPI AND MPI_CXX_FOUND AND MPIEXEC_EXECUTABLE)
  # mpm3d_rank_script(NAME SCRIPT ARGS...): test ranks.NAME runs tests/SCRIPT MPM3D MPIRUN ARGS.
  function(mpm3d_rank_script name script)
    add_test(NAME ranks.${name}
             COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/${script} $<TARGET_FILE:mpm3d> ${MPIEXEC_EXECUTABLE} ${ARGN})
    # Several ranks (and their threads) on the machine's cores: run alone.
    set_tests_properties(ranks.${name} PROPERTIES SKIP_RETURN_CODE 77 RUN_SERIAL TRUE)
  endfunction()
  # mpm3d_rank_test(NAME DECK STEPS [CONFIGS...] [OPTIONS...]): tests/rank_determinism.sh.
  set(_rank_ref "${_mpm3d_ref_exe}")
  if(NOT _rank_ref)
    set(_rank_ref none)  # no reference to compare with (rank_determinism.sh skips it)
  endif()
  function(mpm3d_rank_test name deck steps)
    mpm3d_rank_script(${name} rank_determinism.sh ${deck} ${steps} ${CMAKE_CURRENT_BINARY_DIR}/ranks_${name} ${_rank_ref} ${ARGN})
  endfunction()
  # USL, trilinear, gravity: a block and a sphere dropped on a plate; particles cross ranks.
  mpm3d_rank_test(usl_blocks ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks/usl_blocks.mpm 200)
  # MUSL, two blocks meeting: particles cross the ranks' boundary both ways.
  mpm3d_rank_test(two_blocks ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm 207)
  # The Taylor bar (MUSL, Johnson-Cook), coarse model and the book's deck.
  mpm3d_rank_test(taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm 60)
  mpm3d_rank_test(legacy_taylor ${CMAKE_SOURCE_DIR}/../shared/decks/Taylor.mpm 60)
  # The newest version's clay (softening J2 return, Newton iterations per particle).
  mpm3d_rank_test(clay_column ${CMAKE_SOURCE_DIR}/inputs/clay/clay_column.mpm 100)
  # USF with Johnson-Cook; explosive (programmed burn, JWL).
  mpm3d_rank_test(usf_john ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks/usf_john.mpm 100)
  mpm3d_rank_test(slab_small ${CMAKE_SOURCE_DIR}/inputs/explosives/slab_small.mpm 200)
  # drda (the kinetic energy decides, on every rank alike); particles leaving the grid (kept
  # by the last rank, in the energies' last column).
  mpm3d_rank_test(plate_hole_drda ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/plate_hole_drda.mpm 200)
  mpm3d_rank_test(leaving_grid ${CMAKE_SOURCE_DIR}/inputs/stability/leaving_grid.mpm 200)
  # GIMP and B-splines (27-node stencils, buffers with a halo): a rank needs the buffers of
  # patches up to 1 + floor(2 halo / patch cells) away, two with 2-cell patches.
  mpm3d_rank_test(two_blocks_gimp ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks_gimp.mpm 100)
  mpm3d_rank_test(two_blocks_gimp_patch2 ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks_gimp.mpm 100
                  2x1 3x1 4x1 --patch-cells 2)
  mpm3d_rank_test(cook_membrane_bimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_bimp.mpm 60 2x1 3x1)
  # Multi-velocity contact (two grids, each component's buffers exchanged; the contact
  # force and count from per-patch columns): MUSL with friction (2-cell patches, so that
  # the contact nodes reach past the root's patches and their neighbours), and USF with
  # GIMP, whose contact marks outlive the particles' moves between ranks.
  mpm3d_rank_test(contact_sliding_block ${CMAKE_SOURCE_DIR}/inputs/contact/sliding_block.mpm 150
                  2x1 3x1 4x1 2x2 --patch-cells 2)
  # (to its end, redrawing the ranks' runs whenever the rule draws others: 3 times on 3 ranks)
  mpm3d_rank_test(contact_gimp_usf ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks/gimp_contact_usf.mpm 414
                  2x1 3x1 4x1 2x2 ranks: --rebalance-above 1)
  # Mixed runs on ranks: the Fortran stages (they call the same hooks: the buffer exchange
  # before each assembly, the energy and contact columns' exchange before their folds, the
  # one-process order in the bin stage's lists and the energy stage's outside column),
  # every stage or a mix, against one C++ process and mpm3d_ref.
  mpm3d_rank_test(fortran_usl_blocks ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks/usl_blocks.mpm 200
                  2x1 3x1 2x2 ranks: --kernel fortran)
  mpm3d_rank_test(fortran_taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm 60
                  2x1 3x1 ranks: --kernel fortran)
  mpm3d_rank_test(fortran_leaving_grid ${CMAKE_SOURCE_DIR}/inputs/stability/leaving_grid.mpm 200
                  2x1 3x1 ranks: --kernel fortran)
  mpm3d_rank_test(fortran_contact_sliding_block ${CMAKE_SOURCE_DIR}/inputs/contact/sliding_block.mpm 150
                  2x1 3x1 --patch-cells 2 ranks: --kernel fortran)
  mpm3d_rank_test(mixed_slab_small ${CMAKE_SOURCE_DIR}/inputs/explosives/slab_small.mpm 200
                  2x1 3x1 ranks: --kernels bin=fortran,g2p=fortran,energy=fortran)
  # Total Lagrangian MPM: the particles are binned by their reference positions (they never
  # change rank); V0 P scattered and assembled with the buffers of the neighbouring ranks.
  mpm3d_rank_test(soft_beam_tl ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/soft_beam_tl.mpm 300
                  2x1 3x1 4x1 --patch-cells 2)
  # The particles stored in deck order: the ranks keep each one's storage index all the same.
  mpm3d_rank_test(particle_order_deck ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks/usl_blocks.mpm 200
                  2x1 3x1 --particle-order deck)
  # The adaptive grid: each new window's patches drawn over the ranks again (the Taylor
  # bar's window every 10 steps; a block outrunning its window: a forced regrid, from the
  # particles outside the window summed over the ranks).
  mpm3d_rank_test(adaptive_taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm 100
                  2x1 3x1 2x2 --regrid-every 10)
  mpm3d_rank_test(adaptive_rising_block ${CMAKE_SOURCE_DIR}/tests/decks/rising_block.mpm 100 2x1 3x1 4x1)
  # Checkpoints: written by 2 ranks = one process's file; continued on 3 ranks, on one
  # process, and one process's on 2 ranks = the uninterrupted run (tests/rank_restart.sh).
  # The USF contact deck's checkpoint holds the nodes' contact marks, gathered from their
  # owners (2-cell patches: the contact nodes lie beyond the root's reach).
  function(mpm3d_rank_restart_test name deck steps1 steps2)
    mpm3d_rank_script(restart_${name} rank_restart.sh ${deck} ${steps1} ${steps2} ${CMAKE_CURRENT_BINARY_DIR}/ranks_restart_${name} ${ARGN})
  endfunction()
  mpm3d_rank_restart_test(taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm 30 60)
  mpm3d_rank_restart_test(adaptive_taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm 35 70 --regrid-every 10)
  mpm3d_rank_restart_test(contact_usf ${CMAKE_SOURCE_DIR}/tests/decks/sliding_block_usf.mpm 40 150 --patch-cells 2)
  # The result files, written by the root: curves from the ranks holding the curves'
  # particles, frames from the particles gathered on it (TecPlot, HDF5 series), identical to
  # one process's; also continued from a 2-rank checkpoint on 3 ranks (tests/rank_outputs.sh).
  function(mpm3d_rank_outputs_test name deck steps restart_at)
    mpm3d_rank_script(outputs_${name} rank_outputs.sh ${deck} ${steps} ${restart_at} ${CMAKE_CURRENT_BINARY_DIR}/ranks_outputs_${name} ${ARGN})
  endfunction()
  mpm3d_rank_outputs_test(usl_blocks ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks/usl_blocks.mpm 400 90
                          2x1 3x1 2x2 --end-time 0.004)
  mpm3d_rank_outputs_test(slab_small ${CMAKE_SOURCE_DIR}/inputs/explosives/slab_small.mpm 200 0)
  # (B-spline, QuLo, smoo: the smoothed pressure of each frame from the gathered particles)
  mpm3d_rank_outputs_test(cook_membrane_bimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_bimp.mpm 1000 30
                          2x1 3x1 --end-time 1.0)
  mpm3d_rank_outputs_test(contact_sliding_block ${CMAKE_SOURCE_DIR}/inputs/contact/sliding_block.mpm 1000 60
                          2x1 3x1 --end-time 0.1 --patch-cells 2)
  # A rank's health failure ends every rank (usl_blocks runs away at step 253); refusals.
  mpm3d_rank_script(failure rank_failure.sh ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks/usl_blocks.mpm 300
                    ${CMAKE_CURRENT_BINARY_DIR}/ranks_failure)
endif()
