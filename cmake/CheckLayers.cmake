# Layering check for core/: every stage folder may include only itself and the stages below it.
# Run as a CTest test (core_layering): cmake -DRRF_ROOT=<source dir> -P cmake/CheckLayers.cmake
#
#   util < scene < render < data < nn < predict < eval < project < pipeline
#
# and nothing in core/ may include app/, panels/, tests/ or GL/GLFW/ImGui headers; every quoted
# include names its path from the source root ("core/<stage>/…"; <…> system and library includes are
# not checked further). A subfolder belongs to its stage (core/nn/encodings/… is nn). Fails listing
# every offending include (file and the include) so the fix is obvious.
if(NOT RRF_ROOT)
  message(FATAL_ERROR "CheckLayers.cmake: pass -DRRF_ROOT=<source dir>")
endif()

set(stages util scene render data nn predict eval project pipeline)
file(GLOB_RECURSE files RELATIVE ${RRF_ROOT} ${RRF_ROOT}/core/*.h ${RRF_ROOT}/core/*.cpp)
set(problems "")
foreach(f ${files})
  string(REGEX MATCH "^core/([a-z_]+)/" _ ${f})
  set(own ${CMAKE_MATCH_1})
  list(FIND stages "${own}" ownRank)
  if(ownRank EQUAL -1)
    string(APPEND problems "  ${f}: not inside a stage folder (${stages})\n")
    continue()
  endif()
  # Only the #include lines: other C++ lines may hold unbalanced '[' that would break CMake lists.
  file(STRINGS ${RRF_ROOT}/${f} lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*([<\"])([^>\"]+)[>\"]")
      set(delim "${CMAKE_MATCH_1}")
      set(inc ${CMAKE_MATCH_2})
      if(inc MATCHES "^core/([a-z_]+)/")
        set(dep ${CMAKE_MATCH_1})
        list(FIND stages "${dep}" depRank)
        if(depRank EQUAL -1)
          string(APPEND problems "  ${f}: includes ${inc}, which is in no stage folder\n")
        elseif(depRank GREATER ownRank)
          string(APPEND problems "  ${f}: stage '${own}' includes ${inc} from the higher stage '${dep}'\n")
        endif()
      elseif(inc MATCHES "^core/")
        string(APPEND problems "  ${f}: includes ${inc}, which is in no stage folder\n")
      elseif(inc MATCHES "^(app|panels|tests|shaders)/" OR inc MATCHES "^(imgui|GLFW/|glad/|GL/|backends/)")
        string(APPEND problems "  ${f}: core may not include ${inc}\n")
      elseif(delim STREQUAL "\"")
        # A quoted include is a project file and must name its stage; a bare or relative name would
        # slip past the stage check above.
        string(APPEND problems "  ${f}: quoted include \"${inc}\" does not start with core/<stage>/\n")
      endif()
    endif()
  endforeach()
endforeach()

if(problems)
  message(FATAL_ERROR "core/ layering violations (allowed: each stage includes only itself and lower stages; "
                      "order: ${stages}):\n${problems}")
endif()
list(LENGTH files n)
message(STATUS "core/ layering: ${n} files, every include goes to the same or a lower stage")

# Only core/pipeline chains stages (docs/design.md §2): outside core/nn, which defines it, and
# core/pipeline, no program or library file calls trainNetworks (tests may).
file(GLOB_RECURSE callers RELATIVE ${RRF_ROOT} ${RRF_ROOT}/core/*.cpp ${RRF_ROOT}/core/*.h ${RRF_ROOT}/app/*.cpp
     ${RRF_ROOT}/app/*.h ${RRF_ROOT}/panels/*.cpp ${RRF_ROOT}/panels/*.h ${RRF_ROOT}/bench/*.cpp)
set(chained "")
foreach(f ${callers})
  if(f MATCHES "^core/(nn|pipeline)/")
    continue()
  endif()
  file(STRINGS ${RRF_ROOT}/${f} calls REGEX "trainNetworks[ \t]*\\(")
  if(calls)
    string(APPEND chained "  ${f}: calls trainNetworks; train through core/pipeline/train_stage.h\n")
  endif()
endforeach()
if(chained)
  message(FATAL_ERROR "stages chained outside core/pipeline:\n${chained}")
endif()
