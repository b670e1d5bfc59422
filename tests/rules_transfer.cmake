# The rules of the transfer (cxx/transfer, fortran_ref/stage_bin.f90, stage_sg.f90,
# neo_hookean.f90): the current program's TLmp shape functions and work, its sgmp auxiliary
# cells. Included by tests/rules.cmake (rules_add there).
# tl_shape=centre: trilinear TLmp with every particle at its reference cell's centre (four
# particles a cell here) and the work of P on dF by the current volume; with sgmp the work alone.
rules_add(tl_shape ${_rules_inputs}/hyperelastic/soft_beam_tl.mpm 40 --rule tl_shape=centre)
rules_add(tl_shape_sgmp ${_rules_inputs}/hyperelastic/soft_beam_sgtl.mpm 40 --rule tl_shape=centre)
# sg_lower=truncate: the block's first layer along x lies in the outer half of the grid's
# first cell, on a free face (our rules refuse particles in a held lower face's first cell).
rules_add(sg_lower ${CMAKE_SOURCE_DIR}/tests/decks/sg_lower_free_face.mpm 40 --rule sg_lower=truncate)
# sg_beyond=drop: a bar one cell thick in y and z, its particles at three quarters of it.
rules_add(sg_beyond ${_rules_inputs}/explosives/thin_bar_sgmp.mpm 40 --rule sg_beyond=drop)
# ... and on a grid one cell thick in y alone: dropped only in the top row of cells.
rules_add(sg_beyond_rows ${CMAKE_SOURCE_DIR}/tests/decks/sg_beyond_rows.mpm 40 --rule sg_beyond=drop)
