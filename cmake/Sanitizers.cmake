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
  if("undefined" IN_LIST RRF_SANITIZE)
    # stb_image 2.27 (Debian bookworm), compiled into core/util/stb_reader.cpp, shifts a 32-bit bit
    # buffer by 32 in its JPEG bit reader and lets its integer IDCT overflow on corrupt data (both
    # fixed upstream in 2.28, harmless on the targets it runs on: a garbage pixel, no memory access).
    # The image fuzz target reaches them within minutes, so that one file is built without those two
    # checks (on its own, outside the unity batches); AddressSanitizer and every other check of the
    # undefined-behaviour sanitizer still cover it, and the bugs of 2.27 that do touch memory are
    # refused before stb runs (core/util/stb_reader.h).
    set_source_files_properties(core/util/stb_reader.cpp PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON
                                COMPILE_OPTIONS "-fno-sanitize=shift,signed-integer-overflow")
  endif()
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
  # The coverage feedback (-fsanitize=fuzzer-no-link) is compiled into rrf_core and the fuzz
  # targets only (cmake/Fuzz.cmake): the parsers are all in core, and the tests and the CLI that the
  # same build runs would only be slower with it. Linking it into every program gives the ones that
  # are not fuzz targets the runtime's hooks.
  add_link_options(-fsanitize=fuzzer-no-link)
endif()
