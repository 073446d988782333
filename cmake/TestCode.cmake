# The test programs' own sources (tests/, tests/gui, tests/gl, the threaded tests) compile without
# optimisation in every build type, CI's Release and sanitizer builds included. Their run time is
# spent in what they call (rrf_core, rrf_panels, rrf_gl, the rrf program), which keeps the build's
# flags, so the tests run at nearly the same speed, while the optimiser's time on their GoogleTest
# expansions was the largest single part of CI's compile time (docs/design.md §22).
# -DRRF_OPTIMIZE_TEST_CODE=ON compiles them with the build's flags, e.g. to profile a test.
option(RRF_OPTIMIZE_TEST_CODE "Compile the test programs' own sources with the build's optimisation" OFF)

if(NOT RRF_OPTIMIZE_TEST_CODE)
  foreach(t rrf_tests rrf_gui_tests rrf_gl_tests rrf_threaded_tests)
    if(TARGET ${t})
      # Last on the command line, so it overrides the build type's -O level; the precompiled header of
      # the target is built with the same flags.
      target_compile_options(${t} PRIVATE -O0)
    endif()
  endforeach()
endif()
