# Verification and stability suite (docs/VERIFICATION.md, docs/STABILITY.md).
# The driver runs decks through the library and writes what the analysis needs; the fast
# checks below use it with small resolutions; `make report` (tools/report.py) runs the
# full studies.
add_executable(mpm3d_verify ${CMAKE_CURRENT_LIST_DIR}/verify_driver.cpp)
target_link_libraries(mpm3d_verify PRIVATE mpm3d_core)
target_compile_options(mpm3d_verify PRIVATE ${MPM3D_FP_FLAGS})

# Python with numpy (Debian's python3-numpy, installed by `make deps`): prefer the system
# interpreter, where Debian's packages live.
find_program(MPM3D_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT MPM3D_PYTHON3)
  find_program(MPM3D_PYTHON3 python3)
endif()
if(MPM3D_PYTHON3)
  function(mpm3d_verification_test name)
    add_test(NAME verification.${name}
             COMMAND ${MPM3D_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${name}
                     --driver $<TARGET_FILE:mpm3d_verify>
                     --work ${CMAKE_CURRENT_BINARY_DIR}/verification_${name})
    # One thread per test process (ctest runs tests side by side); exit 77: skipped
    # (the build refuses the deck, or numpy is missing).
    set_tests_properties(verification.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300
                         ENVIRONMENT "OMP_NUM_THREADS=1;OMP_WAIT_POLICY=PASSIVE")
  endfunction()
  # Vibrating bar: period and amplitude of the centre-of-mass velocity (analytic).
  mpm3d_verification_test(bar)
  # Manufactured solution (Wallstedt & Guilkey 2008) at two resolutions, linear shape
  # functions: the order they honestly show is asserted (check.py MMS_LINEAR_ORDER).
  mpm3d_verification_test(mms_linear)
  # The same with GIMP, order above 1.5.
  mpm3d_verification_test(mms_gimp)
  # B-splines and smoothed gradients on the free-face manufactured solution: order above 1.5.
  mpm3d_verification_test(mms_smooth)
  # Elastic wave speed within 2 %, Hugoniot elastic limit and plastic wave speed.
  mpm3d_verification_test(wave)
  # The GIMP variants of the 1D decks (bar, waves, Sod; two cells thick): they run and
  # give the 1D answers.
  mpm3d_verification_test(gimp_1d)
  # Stability: no NaN/Inf, exact mass, momentum, or a clean stop naming step/particle/cause.
  mpm3d_verification_test(stability)
endif()
