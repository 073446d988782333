# The programs' read-only data (shaders/, projects/) and where it goes. core/util/data_dir.h looks
# for it relative to the executable, so both trees below work from any working directory:
#
#   build tree:  <build>/rrf, <build>/rrf-workbench, <build>/bench_*  +  <build>/share/rrf-workbench
#   installed:   <prefix>/bin/rrf, <prefix>/bin/rrf-workbench         +  <prefix>/share/rrf-workbench
#
# These layouts are what data_dir.cpp expects; change them together.
set(RRF_INSTALL_BINDIR bin)
set(RRF_INSTALL_DATADIR share/rrf-workbench)
set(RRF_BUILD_DATADIR ${CMAKE_BINARY_DIR}/${RRF_INSTALL_DATADIR})

# The bundled projects are projects/<name>/ without what working in them produces: the folders the
# workbench writes next to a project (app/gui: data/, export/, models/, runs/, sweeps/,
# ground_truth/) and dataset,
# model and temporary files, and the workbench's autosaves (*.autosave.json). So running the
# workbench on a source project never ships its outputs.
file(GLOB_RECURSE RRF_DATA_FILES CONFIGURE_DEPENDS RELATIVE ${CMAKE_SOURCE_DIR}
     ${CMAKE_SOURCE_DIR}/shaders/* ${CMAKE_SOURCE_DIR}/projects/*)
list(FILTER RRF_DATA_FILES EXCLUDE REGEX "^projects/[^/]+/(data|export|models|runs|sweeps|ground_truth)/")
list(FILTER RRF_DATA_FILES EXCLUDE REGEX "\\.(rrfd|rrfm|tmp)$")
list(FILTER RRF_DATA_FILES EXCLUDE REGEX "\\.autosave\\.json$")

# One copy command per file, so an edited shader or project reaches the build tree at the next build
# (and only changed files are copied); CONFIGURE_DEPENDS picks up added or removed files. The same
# list is installed.
set(RRF_DATA_OUTPUTS "")
foreach(f ${RRF_DATA_FILES})
  add_custom_command(
    OUTPUT ${RRF_BUILD_DATADIR}/${f}
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${CMAKE_SOURCE_DIR}/${f} ${RRF_BUILD_DATADIR}/${f}
    DEPENDS ${CMAKE_SOURCE_DIR}/${f}
    COMMENT "Copying ${f} to ${RRF_INSTALL_DATADIR}/ in the build tree"
    VERBATIM)
  list(APPEND RRF_DATA_OUTPUTS ${RRF_BUILD_DATADIR}/${f})
  get_filename_component(dir ${f} DIRECTORY)
  install(FILES ${CMAKE_SOURCE_DIR}/${f} DESTINATION ${RRF_INSTALL_DATADIR}/${dir})
endforeach()
add_custom_target(rrf_data ALL DEPENDS ${RRF_DATA_OUTPUTS})
