# ParaView reads the animation files (docs/DECK_FORMAT.md, "Animation files"): pvbatch under
# xvfb-run on the .pvd series (ASCII, book fields; binary, current fields), the HDF5 + XDMF
# series and the grid file of inputs/impact/two_blocks.mpm, checked against the run's HDF5
# state (check_paraview.py). Skipped (exit 77, naming the missing Debian package) where
# ParaView, xvfb or h5dump is not installed; .ci/run installs them.
find_program(MPM3D_PV_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT MPM3D_PV_PYTHON3)
  find_program(MPM3D_PV_PYTHON3 python3)
endif()
if(MPM3D_PV_PYTHON3)
  foreach(mode pvd pvd_binary xdmf grid)
    add_test(NAME paraview.${mode}
             COMMAND ${MPM3D_PV_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/paraview/check_paraview.py ${mode}
                     $<TARGET_FILE:mpm3d> ${CMAKE_SOURCE_DIR}/inputs/impact/two_blocks.mpm
                     ${CMAKE_CURRENT_BINARY_DIR}/paraview_${mode})
    # One at a time: each starts an X server (xvfb-run -a), and two starting together may
    # take the same display.
    set_tests_properties(paraview.${mode} PROPERTIES LABELS paraview SKIP_RETURN_CODE 77 TIMEOUT 300
                         RESOURCE_LOCK mpm3d_xvfb)
  endforeach()
  # The decks of inputs/ that write their own series (para), as they are.
  foreach(deck soft_beam_tl soft_beam_sgtl)
    add_test(NAME paraview.${deck}
             COMMAND ${MPM3D_PV_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/paraview/check_paraview.py deck_current
                     $<TARGET_FILE:mpm3d> ${CMAKE_SOURCE_DIR}/inputs/hyperelastic/${deck}.mpm
                     ${CMAKE_CURRENT_BINARY_DIR}/paraview_${deck})
    set_tests_properties(paraview.${deck} PROPERTIES LABELS paraview SKIP_RETURN_CODE 77 TIMEOUT 300
                         RESOURCE_LOCK mpm3d_xvfb)
  endforeach()
endif()
