# GLSL prediction: an offscreen OpenGL 3.3 core context (hidden GLFW window) and the renderer that
# rasterises a G-buffer and evaluates every object's network in a fragment shader.
# Included from cmake/Gui.cmake, which finds glfw3 and OpenGL and builds the glad loader (rrf_glad).

file(GLOB RRF_GL_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/app/gl/*.cpp)
add_library(rrf_gl STATIC ${RRF_GL_SOURCES})
target_link_libraries(rrf_gl PUBLIC rrf_core rrf_glad glfw OpenGL::GL ${CMAKE_DL_LIBS} PRIVATE rrf_warnings)
# Shaders are read at run time from the data directory (core/util/data_dir.h): a program that uses
# rrf_gl needs the build tree's copy, which every build refreshes from shaders/.
add_dependencies(rrf_gl rrf_data)

if(RRF_BUILD_TESTS)
  find_package(GTest REQUIRED)
  file(GLOB RRF_GL_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/gl/*.cpp)
  # The band policy of the workbench's full-quality frames (pure arithmetic, no GUI) is checked
  # against whole frames here.
  add_executable(rrf_gl_tests ${RRF_GL_TEST_SOURCES} ${CMAKE_SOURCE_DIR}/app/gui/prediction_bands.cpp
                              ${CMAKE_SOURCE_DIR}/app/gui/live_prediction.cpp)
  target_link_libraries(rrf_gl_tests PRIVATE rrf_gl GTest::gtest rrf_warnings)
  target_compile_definitions(rrf_gl_tests PRIVATE RRF_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  # The GL tests need an X server: CTest always runs them inside a fresh Xvfb (Mesa llvmpipe unless a
  # GPU driver is configured). A missing xvfb-run is a test FAILURE with a message, never a skip.
  find_program(RRF_XVFB_RUN xvfb-run)
  if(RRF_XVFB_RUN)
    add_test(NAME rrf_gl_tests
             COMMAND ${RRF_XVFB_RUN} -a -s "-screen 0 1280x1024x24" $<TARGET_FILE:rrf_gl_tests>)
  else()
    add_test(NAME rrf_gl_tests
             COMMAND sh -c "echo 'rrf_gl_tests: xvfb-run not found; install the xvfb package (Debian: apt-get install xvfb) to run the OpenGL tests' >&2; exit 1")
  endif()
  # What these tests check is the GLSL code's output, not llvmpipe's speed: without LLVM's
  # optimisation passes llvmpipe compiles each program several times faster and the frames, a few
  # small ones per test, cost little more (a GPU driver ignores the variable). The benchmarks and the
  # workbench's sessions keep the default.
  set_tests_properties(rrf_gl_tests PROPERTIES TIMEOUT 600 ENVIRONMENT "GALLIVM_PERF=nopt")
endif()

if(RRF_BUILD_BENCH)
  add_executable(bench_glsl ${CMAKE_SOURCE_DIR}/bench/gl/bench_glsl.cpp)
  target_link_libraries(bench_glsl PRIVATE rrf_gl CLI11::CLI11 rrf_warnings)
endif()
