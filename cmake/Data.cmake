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

# One copy command per file, so an edited shader or project reaches the build tree at the next build
# (and only changed files are copied); CONFIGURE_DEPENDS picks up added or removed files.
file(GLOB_RECURSE RRF_DATA_FILES CONFIGURE_DEPENDS RELATIVE ${CMAKE_SOURCE_DIR}
     ${CMAKE_SOURCE_DIR}/shaders/* ${CMAKE_SOURCE_DIR}/projects/*)
set(RRF_DATA_OUTPUTS "")
foreach(f ${RRF_DATA_FILES})
  add_custom_command(
    OUTPUT ${RRF_BUILD_DATADIR}/${f}
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${CMAKE_SOURCE_DIR}/${f} ${RRF_BUILD_DATADIR}/${f}
    DEPENDS ${CMAKE_SOURCE_DIR}/${f}
    COMMENT "Copying ${f} to ${RRF_INSTALL_DATADIR}/ in the build tree"
    VERBATIM)
  list(APPEND RRF_DATA_OUTPUTS ${RRF_BUILD_DATADIR}/${f})
endforeach()
add_custom_target(rrf_data ALL DEPENDS ${RRF_DATA_OUTPUTS})

install(DIRECTORY ${CMAKE_SOURCE_DIR}/shaders ${CMAKE_SOURCE_DIR}/projects DESTINATION ${RRF_INSTALL_DATADIR})
