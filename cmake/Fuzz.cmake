# libFuzzer targets (-DRRF_BUILD_FUZZ=ON, cmake/Sanitizers.cmake): one executable fuzz_<name> per
# tests/fuzz/<name>.cpp, each feeding bytes to one parser. Seeds are tests/fuzz/corpus/<name>/ and
# fixed crashes are kept in tests/fuzz/regressions/<name>/; the CTest fuzz_<name>_corpus runs every
# seed and regression once (no mutation), and scripts/sanitize.sh fuzzes each target for a bounded
# time.
set(RRF_FUZZ_DIR ${CMAKE_SOURCE_DIR}/tests/fuzz)
# Coverage feedback from everything the parsers call (all of it in core); the fuzz executables add
# libFuzzer's main.
target_compile_options(rrf_core PRIVATE -fsanitize=fuzzer-no-link)
file(GLOB RRF_FUZZ_SOURCES CONFIGURE_DEPENDS ${RRF_FUZZ_DIR}/*.cpp)
foreach(src ${RRF_FUZZ_SOURCES})
  get_filename_component(name ${src} NAME_WE)
  add_executable(fuzz_${name} ${src})
  target_link_libraries(fuzz_${name} PRIVATE rrf_core rrf_warnings)
  target_compile_options(fuzz_${name} PRIVATE -fsanitize=fuzzer-no-link)
  target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  target_compile_definitions(fuzz_${name} PRIVATE RRF_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  if(RRF_BUILD_TESTS)
    set(inputs ${RRF_FUZZ_DIR}/corpus/${name})
    if(EXISTS ${RRF_FUZZ_DIR}/regressions/${name})
      list(APPEND inputs ${RRF_FUZZ_DIR}/regressions/${name})
    endif()
    add_test(NAME fuzz_${name}_corpus COMMAND fuzz_${name} -runs=0 ${inputs})
    set_tests_properties(fuzz_${name}_corpus PROPERTIES TIMEOUT 120)
  endif()
endforeach()
