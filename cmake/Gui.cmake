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
target_link_libraries(rrf_panels PUBLIC rrf_core PkgConfig::IMGUI)

# ---- rrf-workbench: window, GL, job runner, main ------------------------------------------------
file(GLOB RRF_GUI_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/app/gui/*.cpp)
add_executable(rrf-workbench ${RRF_GUI_SOURCES})
target_link_libraries(rrf-workbench PRIVATE rrf_panels rrf_glad glfw OpenGL::GL ${CMAKE_DL_LIBS})
