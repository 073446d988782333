# GUI dependencies: GLFW, OpenGL, Dear ImGui 1.86 (Debian static lib with GLFW + OpenGL3 backends),
# and a glad 2 loader generated at build time (offline thanks to --reproducible).
find_package(glfw3 3.3 REQUIRED)
find_package(OpenGL REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
find_program(GLAD_EXECUTABLE glad REQUIRED)

set(RRF_GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${RRF_GLAD_DIR}/src/gl.c ${RRF_GLAD_DIR}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --api gl:core=3.3 --out-path ${RRF_GLAD_DIR} c
  COMMENT "Generating the glad OpenGL 3.3 core loader"
  VERBATIM)
add_library(rrf_glad STATIC ${RRF_GLAD_DIR}/src/gl.c)
target_include_directories(rrf_glad PUBLIC ${RRF_GLAD_DIR}/include)
set(RRF_HAVE_GUI_DEPS TRUE)

# ---- panels: ImGui views over core state (no GLFW, no GL) ----------------------------------------
file(GLOB RRF_PANELS_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/panels/*.cpp)
add_library(rrf_panels STATIC ${RRF_PANELS_SOURCES})
target_link_libraries(rrf_panels PUBLIC rrf_core PkgConfig::IMGUI PRIVATE rrf_warnings)

# ---- GLSL prediction (app/gl): the workbench's live prediction draws with it ----------------------
include(cmake/Gl.cmake)

# ---- rrf-workbench: window, GL, job runner, main ------------------------------------------------
file(GLOB RRF_GUI_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/app/gui/*.cpp)
add_executable(rrf-workbench ${RRF_GUI_SOURCES})
target_link_libraries(rrf-workbench PRIVATE rrf_panels rrf_gl rrf_glad glfw OpenGL::GL ${CMAKE_DL_LIBS}
                                            CLI11::CLI11 rrf_warnings)
add_dependencies(rrf-workbench rrf_data)  # the default project and the shaders (core/util/data_dir.h)
install(TARGETS rrf-workbench RUNTIME DESTINATION ${RRF_INSTALL_BINDIR})

# ---- GUI tests ----------------------------------------------------------------------------------
if(RRF_BUILD_TESTS)
  enable_testing()
  find_package(GTest REQUIRED)
  # Panel logic in a bare ImGui context and the job runner: no GLFW, no GL.
  add_executable(rrf_gui_tests
    ${CMAKE_SOURCE_DIR}/tests/gui/test_panels.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_project_io.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_job_runner.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_learning_panels.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_honest_figures.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_leaves_panel.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_encoding_panel.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_object_networks_panel.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_workbench_status.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_project_carry.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_runs_compared.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_user_workspace.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_views_layout.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_pane_docking.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_pipeline_controls.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_frame_stats.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_prediction_draft.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_input_habits.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_readability.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_stored_evaluation.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_prediction_bands.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_ground_truth_restart.cpp
    ${CMAKE_SOURCE_DIR}/tests/gui/test_read_back.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/job_runner.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/worker_priority.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/job_session.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/frame_stats.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/prediction_draft.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/user_workspace.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/shortcuts.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/key_taps.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/stored_evaluation_file.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/prediction_bands.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/ground_truth_controller.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/render_session.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/picking_controller.cpp
    ${CMAKE_SOURCE_DIR}/app/gui/controller_context.cpp)
  target_link_libraries(rrf_gui_tests PRIVATE rrf_panels GTest::gtest GTest::gtest_main rrf_warnings)
  target_compile_definitions(rrf_gui_tests PRIVATE RRF_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  include(GoogleTest)
  gtest_discover_tests(rrf_gui_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 120)

  add_executable(rrf_gui_shotcheck ${CMAKE_SOURCE_DIR}/tests/gui/shot_check.cpp)
  target_link_libraries(rrf_gui_shotcheck PRIVATE rrf_core rrf_warnings)

  # The real window under Xvfb: N frames on the Cornell box, then a screenshot that must show the
  # ground truth; and a scripted session (render, save a run, save/re-open, compare, generate, train,
  # evaluate, export, move the light, re-open) whose screenshot must show ground truth | prediction |
  # error map filled.
  set(RRF_GUI_RUNNER ${CMAKE_SOURCE_DIR}/tests/gui/run_workbench.sh)
  add_test(NAME gui_screenshot
           COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/gui_test_screenshot 1)
  add_test(NAME gui_scripted_session
           COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/gui_test_session 3
                   ${CMAKE_SOURCE_DIR}/tests/gui/session.json)
  # Stop and switch (issue 14): a cancelled render and a stopped training are called what they are,
  # the prediction keeps the last complete models, Open with unsaved changes asks first, and Save As
  # carries the runs so that they re-open from the new place.
  add_test(NAME gui_stop_and_switch
           COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/gui_test_stop_and_switch 3
                   ${CMAKE_SOURCE_DIR}/tests/gui/session_stop_and_switch.json)
  # ... at 1280x720, the smallest size the panels are laid out for: its screenshot must show
  # prediction A | prediction B | difference filled. B is the stopped run's partial prediction: which
  # objects it lacks (hatched) depends on when the stop landed, so only A must show both walls.
  set_tests_properties(gui_stop_and_switch PROPERTIES ENVIRONMENT "RRF_GUI_SIZE=1280x720;RRF_SHOT_SCENE_VIEWS=1")
  # Tabs moved between panes and panes split (issue 14 item 7): the arrangement is saved with the
  # project and re-opened, a pane emptied by a move collapses, and Reset layout restores the default.
  add_test(NAME gui_pane_layout
           COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/gui_test_pane_layout 1
                   ${CMAKE_SOURCE_DIR}/tests/gui/session_layout.json)
  set_tests_properties(gui_pane_layout PROPERTIES ENVIRONMENT "RRF_GUI_SIZE=1280x720")
  # Nothing cut off (issue 14 item 6): after a short render → generate → train → evaluate session every
  # panel is brought to the front and no window, table column or fitted widget may cut its text, at
  # the smallest size the panels are laid out for and at a common desktop size.
  foreach(size 1280x720 1600x1000)
    add_test(NAME gui_unclipped_${size}
             COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                     ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/gui_test_unclipped_${size} 3
                     ${CMAKE_SOURCE_DIR}/tests/gui/session_unclipped.json)
    set_tests_properties(gui_unclipped_${size} PROPERTIES ENVIRONMENT "RRF_GUI_SIZE=${size}" TIMEOUT 600)
  endforeach()
  # The one-click pipeline (issue 14 item 9): the quick preset, shrunk further, renders, generates,
  # trains and evaluates end to end at 1280x720 and leaves a training run with its evaluation.
  add_test(NAME gui_pipeline
           COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/gui_test_pipeline 3
                   ${CMAKE_SOURCE_DIR}/tests/gui/session_pipeline.json)
  set_tests_properties(gui_pipeline PROPERTIES ENVIRONMENT "RRF_GUI_SIZE=1280x720" TIMEOUT 600)
  # The glossy gather in the workbench (issue 26): on the glossy box the GLSL frame is followed by the
  # CPU frame with the gather, after training and after the light moves, and the Views' error figures
  # are against a ground truth of the same light.
  add_test(NAME gui_glossy_gather
           COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-glossy ${CMAKE_BINARY_DIR}/gui_test_glossy_gather 1
                   ${CMAKE_SOURCE_DIR}/tests/gui/session_glossy_gather.json)
  set_tests_properties(gui_glossy_gather PROPERTIES ENVIRONMENT "RRF_GUI_SIZE=1280x720" TIMEOUT 600)
  # Reopen (issue 29): the Objects table of the last evaluation comes back when the ground truth and
  # models it judged are the same, and not for another light; the GLSL programs come from the binary
  # cache and the full frame follows the draft in bands, the UI thread never rendering it in one go.
  add_test(NAME gui_reopen
           COMMAND ${RRF_GUI_RUNNER} $<TARGET_FILE:rrf-workbench> $<TARGET_FILE:rrf_gui_shotcheck>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/gui_test_reopen 3
                   ${CMAKE_SOURCE_DIR}/tests/gui/session_reopen.json)
  set_tests_properties(gui_reopen PROPERTIES TIMEOUT 600 COST 10)
  # A first start without a project works in the per-user workspace; the bundled project stays clean.
  add_test(NAME gui_first_start_workspace
           COMMAND ${CMAKE_SOURCE_DIR}/tests/gui/run_first_start.sh $<TARGET_FILE:rrf-workbench>
                   ${CMAKE_SOURCE_DIR}/projects/cornell-box ${CMAKE_BINARY_DIR}/share/rrf-workbench/projects/cornell-box
                   ${CMAKE_BINARY_DIR}/gui_test_first_start ${CMAKE_SOURCE_DIR}/tests/gui/session_first_start.json)
  set_tests_properties(gui_screenshot gui_scripted_session gui_stop_and_switch gui_first_start_workspace
                       gui_pane_layout PROPERTIES TIMEOUT 600)
  # CTest starts the costliest tests first (COST; a clean clone has no timings of its own): the long
  # sessions then run beside the short tests instead of after them, two long ones alone at the end.
  # Rough seconds on the 2-core CI machine.
  set_tests_properties(gui_glossy_gather PROPERTIES COST 8)
  set_tests_properties(gui_pipeline PROPERTIES COST 25)
  set_tests_properties(gui_scripted_session gui_stop_and_switch PROPERTIES COST 15)
  set_tests_properties(gui_unclipped_1280x720 gui_unclipped_1600x1000 PROPERTIES COST 10)
  # The GLSL tests compile a program per network layout, which llvmpipe does in a second or more each
  # when its shader cache is cold (a fresh CI machine): started late, they would run alone at the end.
  set_tests_properties(rrf_gl_tests PROPERTIES COST 15)
endif()
