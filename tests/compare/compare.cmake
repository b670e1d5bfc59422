# mpm3d-compare (tools/mpm3d_compare.py, copied to the build tree's cxx/mpm3d-compare beside
# mpm3d) against a stand-in original, fake_original.py: the real mpm3d, one column optionally
# scaled (MPM3D_FAKE_SCALE, from a given time on), or a rejected deck (MPM3D_FAKE_REJECT),
# posing as the book program (its line '# mpm3d-compare: program=book'; copies below pose as
# others). The deck, 336 particles with two particle curves, runs in a fraction of a second,
# as does compare/leave_grid.mpm, whose particles leave the grid. expect.py checks exit
# status and output together.
find_package(Python3 COMPONENTS Interpreter)
if(Python3_Interpreter_FOUND)
  set(_cmp_dir ${CMAKE_CURRENT_SOURCE_DIR}/compare)
  set(_cmp_out ${CMAKE_CURRENT_BINARY_DIR}/compare)
  set(_cmp_deck ${CMAKE_CURRENT_SOURCE_DIR}/decks/sg_usf_blocks.mpm)
  set(_cmp_exe ${CMAKE_BINARY_DIR}/cxx/mpm3d-compare)

  # --plot needs matplotlib: the interpreter found above, else the system's python3.
  find_program(MPM3D_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
  set(_cmp_plot_python ${Python3_EXECUTABLE})
  foreach(_py IN ITEMS ${Python3_EXECUTABLE} ${MPM3D_SYSTEM_PYTHON3})
    execute_process(COMMAND ${_py} -c "import matplotlib" RESULT_VARIABLE _rc
                    OUTPUT_QUIET ERROR_QUIET)
    if(_rc EQUAL 0)
      set(_cmp_plot_python ${_py})
      break()
    endif()
  endforeach()

  # compare_test(NAME [DIRECT] [ENV VAR=VALUE] [PYTHON EXE] OPTIONS... EXPECT...): compare.NAME
  # runs mpm3d-compare OPTIONS under expect.py EXPECT, with the stand-in's variables set; by
  # PYTHON (default: the one found), or DIRECT as the installed command (its #! line).
  function(compare_test name)
    cmake_parse_arguments(PARSE_ARGV 1 T "DIRECT" "PYTHON;ENV" "EXPECT;OPTIONS")
    if(NOT T_PYTHON)
      set(T_PYTHON ${Python3_EXECUTABLE})
    endif()
    set(_run ${T_PYTHON} ${_cmp_exe})
    if(T_DIRECT)
      set(_run ${_cmp_exe})
    endif()
    set(_env MPM3D_FAKE_MPM3D=$<TARGET_FILE:mpm3d>)
    if(T_ENV)
      list(APPEND _env ${T_ENV})
    endif()
    add_test(NAME compare.${name}
             COMMAND ${CMAKE_COMMAND} -E env ${_env}
                     ${T_PYTHON} ${_cmp_dir}/expect.py ${T_EXPECT} --
                     ${_run} --threads 1 ${T_OPTIONS})
    set_tests_properties(compare.${name} PROPERTIES TIMEOUT 60 SKIP_RETURN_CODE 77)
  endfunction()

  set(_orig --original ${_cmp_dir}/fake_original.py)
  # (a) The same results: every column 0.000 %, exit 0 (mpm3d found beside the script, as
  # every test but mpm3d_rejects finds it).
  compare_test(same DIRECT OPTIONS ${_orig} ${_cmp_deck}
    EXPECT --rc 0 --stdout "total +0\\.000 +0\\.000 +ok" --stdout "kinetic +0\\.000 +0\\.000 +ok"
           --stdout "disz1 +0\\.000 +0\\.000 +ok" --stdout "disx300 +0\\.000 +0\\.000 +ok"
           --stdout "ns per particle-step +[0-9]+\\.[0-9] +[0-9]+\\.[0-9]"
           --stdout "all compared columns within 1 %$" --not-stdout "FAIL|left the grid|before exit")
  # (b) The original's kinetic energy 5 % larger: 0.05/1.05 of its largest value, exit 1.
  compare_test(perturbed ENV MPM3D_FAKE_SCALE=kinetic:1.05 OPTIONS ${_orig} ${_cmp_deck}
    EXPECT --rc 1 --stdout "EnergyPlot.dat +kinetic +4\\.7[56][0-9] +[0-9.]+ +FAIL"
           --stdout "internal +0\\.000 +0\\.000 +ok" --stdout "beyond 1 %: kinetic$")
  compare_test(tolerance ENV MPM3D_FAKE_SCALE=kinetic:1.05 OPTIONS --tolerance 5 ${_orig} ${_cmp_deck}
    EXPECT --rc 0 --stdout "kinetic +4\\.7[56][0-9] +[0-9.]+ +ok"
           --stdout "all compared columns within 5 %")
  # A curve column, matched by its name: 0.1/0.9 of the original's largest.
  compare_test(curve ENV MPM3D_FAKE_SCALE=disx300:0.9 OPTIONS ${_orig} ${_cmp_deck}
    EXPECT --rc 1 --stdout "sg_usf_blocks_curv.dat +disx300 +11\\.11[0-9] +[0-9.]+ +FAIL"
           --stdout "disz1 +0\\.000 +0\\.000 +ok" --stdout "beyond 1 %: disx300$")
  # Particles leave the grid (leave_grid.mpm, 8 particles flying out through a free face;
  # mpm3d's reports count none outside at t = 0.061, 4 at 0.072): the original's results after
  # that are undefined, so the figures up to 0.061 decide, the animation frame at 0.05 too.
  # The stand-in's disx1 10 % smaller from t = 0.07 on: 0.1/0.9 over the run, none before.
  set(_cmp_leave ${_cmp_dir}/leave_grid.mpm)
  compare_test(left_grid ENV MPM3D_FAKE_SCALE=disx1:0.9:0.07 OPTIONS ${_orig} ${_cmp_leave}
    EXPECT --rc 0 --stdout "^  4 particles left the grid by t = 7\\.1954e-02 \\(mpm3d counts them at its reports, none at t = 6\\.1052e-02\\)"
           --stdout "^  so 'before exit %' compares up to t = 6\\.1052e-02, and it alone decides"
           --stdout "disx1 +11\\.11[0-9] +11\\.11[0-9] +0\\.000 +ok$"
           --stdout "leave_grid_anim.dat t=5\\.01[0-9]e-02 +X +0\\.000 +- +0\\.000 +ok$"
           --stdout "all compared columns within 1 % before particles left the grid$")
  # From t = 0.03 on, before the exit too: beyond the tolerance there.
  compare_test(left_grid_fails ENV MPM3D_FAKE_SCALE=disx1:0.9:0.03 OPTIONS ${_orig} ${_cmp_leave}
    EXPECT --rc 1 --stdout "disx1 +11\\.11[0-9] +11\\.11[0-9] +11\\.11[0-9] +FAIL$"
           --stdout "beyond 1 % before particles left the grid: disx1$")
  # (c) No such original program.
  compare_test(missing_original OPTIONS --original ${_cmp_out}/no_such_program ${_cmp_deck}
    EXPECT --rc 2 --stderr "^mpm3d-compare: the original program .*no_such_program: no such file")
  # (d) Decks rejected: by the original (exit 1 after writing its files; 'stop': exit 0
  # without them), by mpm3d.
  compare_test(rejected_deck ENV MPM3D_FAKE_REJECT=original OPTIONS ${_orig} ${_cmp_deck}
    EXPECT --rc 2
           --stderr "^mpm3d-compare: sg_usf_blocks.mpm: the original rejected the deck \\(exit status 1\\)"
           --stderr "fake original: deck sg_usf_blocks.mpm rejected")
  compare_test(rejected_deck_stop ENV MPM3D_FAKE_REJECT=stop OPTIONS ${_orig} ${_cmp_deck}
    EXPECT --rc 2
           --stderr "^mpm3d-compare: sg_usf_blocks.mpm: the original rejected the deck \\(no EnergyPlot.dat written\\)")
  compare_test(mpm3d_rejects ENV MPM3D_FAKE_REJECT=mpm3d
    OPTIONS ${_orig} --mpm3d ${_cmp_dir}/fake_original.py ${_cmp_deck}
    EXPECT --rc 2 --stderr "^mpm3d-compare: sg_usf_blocks.mpm: mpm3d rejected the deck \\(exit status 1\\)"
           --stderr "fake mpm3d rejects the deck")
  # (e) No such deck: exit 2, and the decks after it still compared.
  compare_test(missing_deck OPTIONS ${_orig} ${_cmp_out}/no_such_deck.mpm ${_cmp_deck}
    EXPECT --rc 2 --stderr "^mpm3d-compare: .*no_such_deck.mpm: no such deck"
           --stdout "== sg_usf_blocks.mpm")
  # (f) --plot writes a PNG (skipped where no python3 here imports matplotlib).
  compare_test(plot PYTHON ${_cmp_plot_python} OPTIONS --plot ${_cmp_out}/plot ${_orig} ${_cmp_deck}
    EXPECT --rc 0 --needs matplotlib --clean ${_cmp_out}/plot --file ${_cmp_out}/plot/sg_usf_blocks.png)
  # --keep leaves both runs' files.
  compare_test(keep OPTIONS --keep ${_cmp_out}/keep ${_orig} ${_cmp_deck}
    EXPECT --rc 0 --clean ${_cmp_out}/keep
           --file ${_cmp_out}/keep/sg_usf_blocks/original/EnergyPlot.dat
           --file ${_cmp_out}/keep/sg_usf_blocks/mpm3d/sg_usf_blocks_curv.dat)

  # (g) Rules: --rules/--rule reach mpm3d; --explain names the rule behind a difference. The
  # stand-in original runs by mpm3d's rules as MPM3D_FAKE_RULES sets them; on the explosive
  # slab (a book deck with 'bulk') the book program's ignored 'bulk' moves the time step.
  set(_cmp_slab ${CMAKE_SOURCE_DIR}/inputs/explosives/slab_small.mpm)
  compare_test(rules_passed ENV "MPM3D_FAKE_RULES=--rules original --rule burn=ramp"
    OPTIONS ${_orig} --rules original --rule burn=ramp ${_cmp_slab}
    EXPECT --rc 0 --stdout "^mpm3d-compare: the original program is taken to be the book program \\(its line '# mpm3d-compare: program=book'\\)$"
           --stdout "mpm3d run with --rules book --rule burn=ramp"
           --stdout "kinetic +0\\.000 +0\\.000 +ok" --stdout "all compared columns within 1 %")
  compare_test(explain ENV "MPM3D_FAKE_RULES=--rule bulk_book=ignore"
    OPTIONS ${_orig} --explain ${_cmp_slab}
    EXPECT --rc 1 --stdout "beyond 1 %: kinetic"
           --stdout "^  \\(as compared\\) +[1-9][0-9]*\\.[0-9]+ "
           --stdout "^  bulk_book=ignore +0\\.000 +0\\.000 "
           --stdout "^  deck_reals=single +[1-9][0-9]*\\.[0-9]+ "
           --stdout "^  all \\(--rules book\\) " --not-stdout "not copied"
           --stdout "^  sensitive \\(the original's own results here turn on the last digits"
           --stdout "^    - Mie-Gruneisen \\(material 2\\): the pressure has its energy term g0 e in compression only")
  # The stand-in original differs from mpm3d by the burn alone: the burn's row is 0.000, the
  # other rules' rows keep the difference.
  compare_test(explain_burn ENV "MPM3D_FAKE_RULES=--rule burn=step"
    OPTIONS ${_orig} --explain ${_cmp_slab}
    EXPECT --rc 1 --stdout "beyond 1 %: kinetic"
           --stdout "^  burn=step +0\\.000 +0\\.000 "
           --stdout "^  bulk_book=ignore +[1-9][0-9]*\\.[0-9]+ "
           --stdout "^  all \\(--rules book\\) +[1-9][0-9]*\\.[0-9]+ ")

  # (h) Which original program --original is: --rules original and --explain take its rules.
  # The stand-in's copies pose as the current program, as a script that does not say, and
  # as an executable holding only some of the current version's keywords. On the slab, a
  # book deck, the current program's rules are not the book's (mpm3d --rules original).
  file(READ ${_cmp_dir}/fake_original.py _fake)
  set(_book_line "\n# mpm3d-compare: program=book\n")
  string(REPLACE "${_book_line}" "\n# mpm3d-compare: program=current\n" _fake_current "${_fake}")
  string(REPLACE "${_book_line}" "\n" _fake_unknown "${_fake}")
  file(WRITE ${_cmp_out}/fake_current.py "${_fake_current}")
  file(WRITE ${_cmp_out}/fake_unknown.py "${_fake_unknown}")
  file(WRITE ${_cmp_out}/partial_original "a program with the keywords bimp and sgmp\n")
  file(CHMOD ${_cmp_out}/fake_current.py ${_cmp_out}/fake_unknown.py ${_cmp_out}/partial_original
       PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ
                   WORLD_EXECUTE)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_cmp_dir}/fake_original.py)
  set(_cur --original ${_cmp_out}/fake_current.py)
  compare_test(program_current ENV "MPM3D_FAKE_RULES=--rules current"
    OPTIONS ${_cur} --rules original ${_cmp_slab}
    EXPECT --rc 0 --stdout "^mpm3d-compare: the original program is taken to be the current program \\(its line '# mpm3d-compare: program=current'\\)$"
           --stdout "mpm3d run with --rules current\\)" --stdout "all compared columns within 1 %")
  compare_test(program_current_explain ENV "MPM3D_FAKE_RULES=--rules current"
    OPTIONS ${_cur} --explain ${_cmp_slab}
    EXPECT --rc 1 --stdout "^  time_step=current " --stdout "^  all \\(--rules current\\) +0\\.000 +0\\.000 "
           --not-stdout "bulk_book")
  # sgmp on a grid one cell thick in y (tests/decks/sg_beyond_rows.mpm): the current program
  # puts the weight beyond y in the next row of cells, which no rule copies; --explain says so
  # (mpm3d's summary, not_copied), here with the stand-in's kinetic energy 5 % larger; no
  # Mie-Gruneisen, so nothing sensitive (the slab's copper, compare.explain, is).
  compare_test(not_copied ENV "MPM3D_FAKE_SCALE=kinetic:1.05"
    OPTIONS ${_cur} --rules original --explain ${CMAKE_CURRENT_SOURCE_DIR}/decks/sg_beyond_rows.mpm
    EXPECT --rc 1 --stdout "beyond 1 %: .*kinetic"
           --stdout "^  not copied \\(mpm3d differs from the original here by design"
           --stdout "^    - sgmp on a grid one cell thick along y: the current MPM3D-F90 gives the weight"
           --not-stdout "sensitive")
  # --original-program overrides what the executable says.
  compare_test(program_given ENV "MPM3D_FAKE_RULES=--rules book"
    OPTIONS ${_cur} --original-program book --rules original ${_cmp_slab}
    EXPECT --rc 0 --stdout "taken to be the book program \\(as --original-program says\\)$"
           --stdout "mpm3d run with --rules book\\)" --stdout "all compared columns within 1 %")
  # A program it cannot tell: refused where its rules are needed, compared where not.
  compare_test(program_unknown OPTIONS --original ${_cmp_out}/fake_unknown.py --rules original ${_cmp_slab}
    EXPECT --rc 2 --stderr "^mpm3d-compare: cannot tell which original program .*fake_unknown\\.py is \\(a script without a line '# mpm3d-compare: program=book' \\(or current\\)\\): give --original-program book or current$")
  compare_test(program_partial OPTIONS --original ${_cmp_out}/partial_original --explain ${_cmp_slab}
    EXPECT --rc 2 --stderr "^mpm3d-compare: cannot tell .*partial_original is \\(its executable holds only bimp, sgmp of the keywords bimp, sgmp, TLmp, UVFp, QuLo, neoh\\)")
  compare_test(program_not_needed OPTIONS --original ${_cmp_out}/fake_unknown.py ${_cmp_deck}
    EXPECT --rc 0 --stdout "all compared columns within 1 %" --not-stdout "original program")
  # --rules book or current as given, with a warning where it names the other program.
  compare_test(program_warning ENV "MPM3D_FAKE_RULES=--rules current" OPTIONS ${_orig} --rules current ${_cmp_slab}
    EXPECT --rc 0 --stderr "^mpm3d-compare: warning: --rules current, but the original program is the book program \\(its line"
           --stdout "mpm3d run with --rules current\\)" --not-stdout "taken to be")

  # make bench's pass over every public deck (tools/every_deck_speed.py): its cut deck, and one
  # deck name run end to end with the stand-in as both originals (every_deck_test.py).
  add_test(NAME compare.every_deck_speed
           COMMAND ${Python3_EXECUTABLE} ${_cmp_dir}/every_deck_test.py $<TARGET_FILE:mpm3d> ${_cmp_deck})
  set_tests_properties(compare.every_deck_speed PROPERTIES TIMEOUT 120)
endif()
