# rrf_threaded_tests: the tests that run work on several threads, built alone for the
# ThreadSanitizer job (-DRRF_SANITIZE=thread, cmake/Sanitizers.cmake; scripts/sanitize.sh runs it).
# A subset of rrf_tests' sources so that the TSan build compiles core and these files only:
#   renderer (tiles in parallel, snapshots, cancel; BDPT iterations and their splats), data generator (cells in parallel, cancel),
#   LM / Adam / per-object training (parallel blocks and objects, cancel), training runs, and the
#   workbench's job runner and job sessions (worker threads, progress, cancel; no ImGui, no GL).
# Their CLI tests (DataGenerator.Cli*, DataGenerator.InterruptedCli*) start the rrf program and so
# check a separate process: the TSan job leaves them to rrf_tests (gtest filter in sanitize.sh).
add_executable(rrf_threaded_tests
  ${CMAKE_SOURCE_DIR}/tests/test_renderer.cpp
  ${CMAKE_SOURCE_DIR}/tests/test_bdpt.cpp
  ${CMAKE_SOURCE_DIR}/tests/test_data_generator.cpp
  ${CMAKE_SOURCE_DIR}/tests/test_nn_training.cpp
  ${CMAKE_SOURCE_DIR}/tests/test_nn_objects.cpp
  ${CMAKE_SOURCE_DIR}/tests/test_training_run.cpp
  ${CMAKE_SOURCE_DIR}/tests/gui/test_job_runner.cpp
  ${CMAKE_SOURCE_DIR}/app/gui/job_runner.cpp
  ${CMAKE_SOURCE_DIR}/app/gui/worker_priority.cpp
  ${CMAKE_SOURCE_DIR}/app/gui/job_session.cpp
  ${CMAKE_SOURCE_DIR}/panels/log.cpp)
target_link_libraries(rrf_threaded_tests PRIVATE rrf_core GTest::gtest GTest::gtest_main rrf_warnings)
target_compile_definitions(rrf_threaded_tests PRIVATE RRF_CLI_PATH="$<TARGET_FILE:rrf>"
                                                      RRF_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
