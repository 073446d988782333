# Sanitizer builds (docs/design.md §22; scripts/sanitize.sh runs them in CI). Included before any
# target is declared, so every target of the build (core, CLI, tests, fuzz targets) is instrumented
# alike; the system libraries (Embree, TBB, GoogleTest) are not.
#
#   -DRRF_SANITIZE="address;undefined"   AddressSanitizer + UndefinedBehaviorSanitizer
#   -DRRF_SANITIZE=thread                ThreadSanitizer (with -DRRF_BUILD_TESTS=ON: rrf_threaded_tests)
#   -DRRF_BUILD_FUZZ=ON                  libFuzzer targets in tests/fuzz (clang; coverage-instruments all
#                                        code; use with address;undefined)
#
# Every report is fatal (-fno-sanitize-recover=all): a test or fuzz run that triggers one fails.
set(RRF_SANITIZE "" CACHE STRING "Sanitizers to build with: address;undefined, or thread (empty: none)")
option(RRF_BUILD_FUZZ "Build the libFuzzer targets in tests/fuzz (needs clang)" OFF)

if(RRF_SANITIZE)
  foreach(s ${RRF_SANITIZE})
    if(NOT s MATCHES "^(address|undefined|thread)$")
      message(FATAL_ERROR "RRF_SANITIZE: unknown sanitizer '${s}' (expected address, undefined or thread)")
    endif()
  endforeach()
  if("thread" IN_LIST RRF_SANITIZE AND "address" IN_LIST RRF_SANITIZE)
    message(FATAL_ERROR "RRF_SANITIZE: thread and address cannot be combined; build them separately")
  endif()
  list(JOIN RRF_SANITIZE "," rrf_sanitizers)
  add_compile_options(-fsanitize=${rrf_sanitizers} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${rrf_sanitizers})
  # Line tables are enough for symbolised stacks and cost far less compile time than full -g.
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    add_compile_options(-gline-tables-only)
  else()
    add_compile_options(-g1)
  endif()
endif()

if(RRF_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "RRF_BUILD_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  # Coverage feedback from everything the parsers call; the fuzz executables add libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link)
  add_link_options(-fsanitize=fuzzer-no-link)
endif()

# scripts/sanitize.sh builds with CMAKE_UNITY_BUILD (several sources per compiler run: instrumented
# template code is generated once per batch instead of once per file, which halves the build). These
# sources define file-local helpers under names that other sources use too, so they are compiled
# on their own.
set_source_files_properties(
  core/eval/reference_store.cpp core/nn/model_file.cpp core/nn/model_set.cpp core/project/scene_overrides.cpp
  app/cli/cli_reference.cpp
  PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
# The test sources share helper names (TempDir, toD, ...) in anonymous namespaces: each is compiled
# on its own.
file(GLOB rrf_unity_skipped_tests CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/*.cpp)
set_source_files_properties(${rrf_unity_skipped_tests} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
