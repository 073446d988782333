# Install test (CTest install_run): `cmake --install` into a fresh prefix, then run the installed
# programs from an unrelated working directory with RRF_DATA_DIR unset, so they can only find their
# data through <prefix>/share/rrf-workbench (core/util/data_dir.h):
#   1. rrf render <prefix>/share/rrf-workbench/projects/cornell-box/project.json (32×32, 1 spp);
#      the images must exist;
#   2. with RRF_CHECK_GUI: rrf-workbench with no project under Xvfb for 2 frames; it must open the
#      installed Cornell box, report the installed data directory and write its screenshot.
#
#   cmake -DRRF_BUILD_DIR=<build> -DRRF_PREFIX=<prefix> [-DRRF_CHECK_GUI=ON -DRRF_XVFB_RUN=<xvfb-run>]
#         -P cmake/CheckInstall.cmake
if(NOT RRF_BUILD_DIR OR NOT RRF_PREFIX)
  message(FATAL_ERROR "CheckInstall.cmake: pass -DRRF_BUILD_DIR=<build dir> -DRRF_PREFIX=<install prefix>")
endif()

# Runs a command; fails the test with its output when it exits non-zero. Output in ${out_var}.
function(rrf_run out_var)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${work} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "install test: '${cmd}' failed (${rc}):\n${out}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

set(work ${RRF_PREFIX}-work)
file(REMOVE_RECURSE ${RRF_PREFIX} ${work})
file(MAKE_DIRECTORY ${work})
rrf_run(ignored ${CMAKE_COMMAND} --install ${RRF_BUILD_DIR} --prefix ${RRF_PREFIX})

set(share ${RRF_PREFIX}/share/rrf-workbench)
foreach(f bin/rrf share/rrf-workbench/shaders/predict.frag share/rrf-workbench/projects/cornell-box/project.json)
  if(NOT EXISTS ${RRF_PREFIX}/${f})
    message(FATAL_ERROR "install test: ${RRF_PREFIX}/${f} was not installed")
  endif()
endforeach()

# The data directory must come from the installed layout, never from the environment.
set(env ${CMAKE_COMMAND} -E env --unset=RRF_DATA_DIR)

rrf_run(out ${env} ${RRF_PREFIX}/bin/rrf render ${share}/projects/cornell-box/project.json
        --spp 1 --width 32 --height 32 --format png --threads 1 --out render)
if(NOT EXISTS ${work}/render/global.png OR NOT EXISTS ${work}/render/render.json)
  message(FATAL_ERROR "install test: the installed rrf render wrote no render/global.png, render/render.json:\n${out}")
endif()
message(STATUS "installed rrf render: ok")

if(RRF_CHECK_GUI)
  if(NOT EXISTS ${RRF_PREFIX}/bin/rrf-workbench)
    message(FATAL_ERROR "install test: ${RRF_PREFIX}/bin/rrf-workbench was not installed")
  endif()
  if(NOT RRF_XVFB_RUN)
    message(FATAL_ERROR "install test: xvfb-run is not installed; the GUI check needs it (Debian: apt-get install xvfb xauth)")
  endif()
  # A private config directory keeps the user's recent projects and imgui.ini out of the test.
  rrf_run(out ${env} XDG_CONFIG_HOME=${work}/config ${RRF_XVFB_RUN} -a -s "-screen 0 1600x1000x24"
          ${RRF_PREFIX}/bin/rrf-workbench --frames 2 --screenshot shot.png)
  if(NOT EXISTS ${work}/shot.png)
    message(FATAL_ERROR "install test: the installed rrf-workbench wrote no screenshot:\n${out}")
  endif()
  file(REAL_PATH ${share} realShare)  # the program names the path /proc/self/exe resolves to
  string(FIND "${out}" "data directory: ${realShare}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "install test: the installed rrf-workbench did not use ${share}:\n${out}")
  endif()
  message(STATUS "installed rrf-workbench: ok (data directory ${share})")
endif()
