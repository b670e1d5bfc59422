# Bit-for-bit checks of the Fortran reference against the C++ solver (docs/DESIGN.md 5, 5a).
# Included from tests/CMakeLists.txt. Every comparison is a plain `h5diff` of two HDF5
# state files (no tolerance): the C++ run against --kernel fortran, against each single
# stage taken from Fortran, against the Fortran program mpm3d_ref, and the initial states
# of the two deck readers. The shared decks (../shared/decks) are not part of the
# repository: their tests are skipped when that folder is absent.
if(TARGET mpm3d AND TARGET mpm3d_ref)
  find_program(MPM3D_H5DIFF h5diff HINTS /usr/bin)
  if(NOT MPM3D_H5DIFF)
    message(WARNING "fortran_ref/tests.cmake: h5diff not found; cross-language tests disabled")
    return()
  endif()
  set(_fref_script ${CMAKE_SOURCE_DIR}/fortran_ref/xcheck.sh)
  set(_fref_out ${CMAKE_CURRENT_BINARY_DIR}/fortran_ref)
  set(_fref_steps 60)
  set(_fref_stages bin p2g forces integrate g2p stress energy)

  # fref_add(NAME KIND DECK [MPM3D OPTIONS...])
  function(fref_add name kind deck)
    add_test(NAME ${name}
             COMMAND sh ${_fref_script} ${kind} ${_fref_out}/${name} ${deck}
                     $<TARGET_FILE:mpm3d> $<TARGET_FILE:mpm3d_ref> ${MPM3D_H5DIFF} ${_fref_steps}
                     ${ARGN})
    set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS fortran_ref)
  endfunction()

  # All checks of one deck; extra arguments name further stages the deck runs (contact).
  function(fref_deck tag deck)
    set(_mix bin=fortran,p2g=cxx,forces=fortran,integrate=cxx,g2p=fortran,stress=cxx,energy=fortran)
    foreach(extra ${ARGN})
      set(_mix ${_mix},${extra}=fortran)
    endforeach()
    fref_add(fref_${tag}_init init ${deck})
    fref_add(fref_${tag}_kernel_fortran kernels ${deck} --threads 1 --kernel fortran)
    foreach(stage ${_fref_stages} ${ARGN})
      fref_add(fref_${tag}_stage_${stage} kernels ${deck} --threads 1 --kernels ${stage}=fortran)
    endforeach()
    # A free mix of the two languages on two threads.
    fref_add(fref_${tag}_mixed kernels ${deck} --threads 2 --kernels ${_mix})
    fref_add(fref_${tag}_mpm3d_ref ref ${deck})
  endfunction()

  set(_fref_own ${CMAKE_SOURCE_DIR}/fortran_ref/testdecks)
  set(_fref_shared ${CMAKE_SOURCE_DIR}/../shared/decks)
  fref_deck(taylor ${_fref_shared}/Taylor.mpm)
  fref_deck(usl_blocks ${_fref_own}/usl_blocks.mpm)
  fref_deck(usf_john ${_fref_own}/usf_john.mpm)
  fref_deck(musl_sjcf ${_fref_own}/musl_sjcf.mpm)
  fref_deck(quirks ${_fref_own}/quirks.mpm)
  # Our own decks in inputs/ (cheap enough for 60 steps x 11 variants).
  fref_deck(two_blocks ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm)
  fref_deck(taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm)
  fref_deck(mixed_thermal ${CMAKE_SOURCE_DIR}/tests/decks/mixed_thermal.mpm)
  # Explosives (hiex + JWL, programmed burn, bulk viscosity, sjcf flyer) and Drucker-Prager.
  fref_deck(slab_small ${CMAKE_SOURCE_DIR}/inputs/explosives/slab_small.mpm)
  fref_deck(slope ${CMAKE_SOURCE_DIR}/inputs/granular/slope.mpm)
  fref_deck(null_gas ${_fref_own}/null_gas.mpm)
  fref_deck(water_tension ${CMAKE_SOURCE_DIR}/inputs/fluids/water_tension.mpm)
  fref_deck(deto1k ${_fref_shared}/Deto1k.mpm)
  fref_deck(tnt3d ${_fref_shared}/TNT3D.mpm)
  # The adaptive background grid (regrid every 5 steps): C++ stages, Fortran stages, each
  # single stage from Fortran and mpm3d_ref, all against the plain C++ run on the whole box
  # (the window is on the deck's patch lattice, so the bits do not change), and mpm3d_ref's
  # windows against mpm3d's (kind regrid).
  function(fref_adaptive tag deck)
    fref_add(fref_${tag}_adaptive_same kernels ${deck} --threads 3 --regrid-every 5)
    fref_add(fref_${tag}_adaptive_kernel_fortran kernels ${deck} --threads 1 --kernel fortran --regrid-every 5)
    foreach(stage ${_fref_stages})
      fref_add(fref_${tag}_adaptive_stage_${stage} kernels ${deck} --threads 1 --kernels ${stage}=fortran
               --regrid-every 5)
    endforeach()
    fref_add(fref_${tag}_adaptive_mpm3d_ref regrid ${deck} --regrid-every 5)
  endfunction()
  fref_adaptive(taylor_coarse ${CMAKE_SOURCE_DIR}/inputs/taylor/taylor_coarse.mpm)
  fref_adaptive(two_blocks ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm)
  fref_add(fref_rising_block_adaptive_mpm3d_ref regrid ${CMAKE_SOURCE_DIR}/tests/decks/rising_block.mpm)
  # GIMP shape functions and multi-velocity contact (issue 5).
  fref_deck(two_blocks_gimp ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks_gimp.mpm)
  fref_deck(spheres ${CMAKE_SOURCE_DIR}/inputs/contact/spheres.mpm contact recontact)
  fref_deck(sliding_block ${CMAKE_SOURCE_DIR}/inputs/contact/sliding_block.mpm contact recontact)
  fref_deck(gimp_contact ${_fref_own}/gimp_contact_usf.mpm contact recontact)
  # The current MPM3D-F90's neo-Hookean solid (F carried per particle, volume from det F),
  # vsin, 'part' loads and UVFp on a hypoelastic body, trilinear and GIMP (issue 16).
  fref_deck(free_soft_beam ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/free_soft_beam_coarse.mpm)
  fref_deck(neo_block_gimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/neo_block_gimp.mpm)
  fref_deck(cantilever_quasi_static ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cantilever_quasi_static.mpm)
  fref_deck(plate_hole_drda ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/plate_hole_drda.mpm)
  # The current version's built-in velocity fields: the initial states (nuli's 49,152
  # particles only at the start), ksin's strip also through its steps.
  fref_add(fref_ksin_strip_init init ${CMAKE_SOURCE_DIR}/tests/decks/ksin_strip.mpm)
  fref_add(fref_ksin_strip_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/tests/decks/ksin_strip.mpm)
  fref_add(fref_nuli_beam_init init ${CMAKE_SOURCE_DIR}/tests/decks/nuli_beam.mpm)
  # Total Lagrangian MPM (TLmp): our coarse soft cantilever and the public soft beam.
  fref_deck(soft_beam_tl ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/soft_beam_tl.mpm)
  fref_deck(current_soft_beam_tl ${_fref_shared}/current/SoftBeam_SBTL_0p1mesh_SBTL.mpm)
  fref_deck(current_free_soft_beam ${_fref_shared}/current/FreeSoftBeam_MPM_v0p3_FreeSB_MPM.mpm)
  # B-spline MPM (bimp, two fixed node layers): our coarse Cook membrane and the public one.
  fref_deck(cook_membrane_bimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_bimp.mpm)
  fref_deck(current_cook_bimp ${_fref_shared}/current/Cook_membrane_BSMPM5776p_Cookmo_Bimp.mpm)
  # GIMP on a current-version deck (particles a quarter cell in half-size, whatever their
  # volume, as the current program): our coarse Cook membrane of poin particles.
  fref_deck(cook_membrane_gimp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_gimp.mpm)
  # Smoothed-gradient MPM (sgmp): our Cook membrane (MUSL), USF blocks under gravity, the
  # public Cook membrane and the one-dimensional detonation.
  fref_deck(cook_membrane_sgmp ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/cook_membrane_sgmp.mpm)
  fref_deck(sg_usf_blocks ${CMAKE_SOURCE_DIR}/tests/decks/sg_usf_blocks.mpm)
  # sgmp with TLmp: the smoothed-gradient total Lagrangian soft beam (V0 P to the centres).
  fref_deck(soft_beam_sgtl ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/soft_beam_sgtl.mpm)
  fref_deck(current_cook_sg ${_fref_shared}/current/Cook_membrane_SG5776p_Cookmo_SG.mpm)
  fref_add(fref_current_sgdeto1k_mpm3d_ref ref ${_fref_shared}/current/SGDeto1k.mpm)
  # The current version's null water with its weakly compressible EOS, sgmp: the dam break.
  fref_deck(dam_break_coarse ${CMAKE_SOURCE_DIR}/inputs/fluids/dam_break_coarse.mpm)
  fref_add(fref_current_dam_break_mpm3d_ref ref ${_fref_shared}/current/DamBreak_SGMPM_Dam_SGR2.mpm)
  # The newest version's clay (softening J2): our column, and the newest public decks, the R1
  # dam breaks and the three 311,550-particle landslides (written by the shared folder's
  # make_landslide_decks.py into the build tree; 3 steps against mpm3d_ref).
  fref_deck(clay_column ${CMAKE_SOURCE_DIR}/inputs/clay/clay_column.mpm)
  set(_fref_newest ${CMAKE_SOURCE_DIR}/../shared/decks/newest)
  fref_add(fref_newest_dam_r1_mpm3d_ref ref ${_fref_newest}/DamBreak_MPM_R1_Dam_R1.mpm)
  fref_add(fref_newest_dam_sgr1_mpm3d_ref ref ${_fref_newest}/DamBreak_SGMPM_R1_Dam_SGR1.mpm)
  fref_add(fref_newest_dam_sgr1_pressure_mpm3d_ref ref ${_fref_newest}/DamBreak_SGMPMvsPressureR1_Dam_SGR1.mpm)
  foreach(_ls BS GIMP SG)
    add_test(NAME fref_newest_landslide_${_ls}_mpm3d_ref
             COMMAND sh ${CMAKE_SOURCE_DIR}/tests/newest_landslide.sh ${_fref_newest} ${_fref_out}/landslides ${_ls}
                     sh ${_fref_script} ref ${_fref_out}/fref_newest_landslide_${_ls}
                     ${_fref_out}/landslides/${_ls}.mpm $<TARGET_FILE:mpm3d> $<TARGET_FILE:mpm3d_ref> ${MPM3D_H5DIFF} 3)
    set_tests_properties(fref_newest_landslide_${_ls}_mpm3d_ref PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600
                         LABELS fortran_ref RESOURCE_LOCK landslide_decks)
  endforeach()
  # GIMP with the adaptive grid (halo patches on the deck's patch lattice).
  fref_adaptive(two_blocks_gimp ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks_gimp.mpm)
  # Transfer method x material family (tools/method_matrix.py, docs/DECK_FORMAT.md): each deck
  # of inputs/methods/ against mpm3d_ref over the first 60 steps.
  fref_add(fref_methods_j2eos_linear_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_linear.mpm)
  fref_add(fref_methods_j2eos_gimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_gimp.mpm)
  fref_add(fref_methods_j2eos_bimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_bimp.mpm)
  fref_add(fref_methods_j2eos_sgmp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/j2eos_sgmp.mpm)
  fref_add(fref_methods_neoh_linear_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_linear.mpm)
  fref_add(fref_methods_neoh_gimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_gimp.mpm)
  fref_add(fref_methods_neoh_bimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_bimp.mpm)
  fref_add(fref_methods_neoh_sgmp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_sgmp.mpm)
  fref_add(fref_methods_neoh_tlmp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/neoh_TLmp.mpm)
  fref_add(fref_methods_null_linear_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/null_linear.mpm)
  fref_add(fref_methods_null_gimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/null_gimp.mpm)
  fref_add(fref_methods_null_bimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/null_bimp.mpm)
  fref_add(fref_methods_null_sgmp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/null_sgmp.mpm)
  fref_add(fref_methods_hiex_linear_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_linear.mpm)
  fref_add(fref_methods_hiex_gimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_gimp.mpm)
  fref_add(fref_methods_hiex_bimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_bimp.mpm)
  fref_add(fref_methods_hiex_sgmp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/hiex_sgmp.mpm)
  fref_add(fref_methods_dpm_linear_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_linear.mpm)
  fref_add(fref_methods_dpm_gimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_gimp.mpm)
  fref_add(fref_methods_dpm_bimp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_bimp.mpm)
  fref_add(fref_methods_dpm_sgmp_mpm3d_ref ref ${CMAKE_SOURCE_DIR}/inputs/methods/dpm_sgmp.mpm)
  # Hypervelocity lead sphere: every variant over the first 60 steps, and the whole run
  # (2,118 steps, into the EOS's tension branch) with every stage from Fortran.
  fref_deck(lead_sphere_small ${CMAKE_SOURCE_DIR}/inputs/impact/lead_sphere_small.mpm)
  add_test(NAME fref_lead_sphere_small_kernel_fortran_to_end
           COMMAND sh ${_fref_script} kernels ${_fref_out}/fref_lead_sphere_small_kernel_fortran_to_end
                   ${CMAKE_SOURCE_DIR}/inputs/impact/lead_sphere_small.mpm $<TARGET_FILE:mpm3d>
                   $<TARGET_FILE:mpm3d_ref> ${MPM3D_H5DIFF} 2118 --threads 2 --kernel fortran)
  set_tests_properties(fref_lead_sphere_small_kernel_fortran_to_end PROPERTIES TIMEOUT 300 LABELS fortran_ref)
  fref_add(fref_quirks_crlf crlf ${_fref_own}/quirks.mpm)
  fref_add(fref_usl_blocks_unstable unstable ${_fref_own}/usl_blocks.mpm)
  fref_add(fref_h5diff_detects detect ${_fref_own}/musl_sjcf.mpm)
  fref_add(fref_refusals refuse ${_fref_own}/usl_blocks.mpm)

  if(TARGET mpm3d_fortran_layout)
    add_test(NAME fref_layout COMMAND mpm3d_fortran_layout)
    set_tests_properties(fref_layout PROPERTIES LABELS fortran_ref)
  endif()
endif()
