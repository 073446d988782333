# JSON stays in the file codecs (issue 27: typed state everywhere else). Run as a CTest test
# (json_confined): cmake -DRRF_ROOT=<source dir> -P cmake/CheckJsonConfined.cmake
#
# In core/, app/ and panels/, only a file codec may name nlohmann (an include or a use): a file whose
# name ends in _json.h/.cpp or _file.h/.cpp, and core/util/json_reader.* (the validating reader they
# share). Every other file works on typed structs; keys a build does not know travel as JsonText
# (core/util/json_text.h). Fails listing every other file that names nlohmann.
if(NOT RRF_ROOT)
  message(FATAL_ERROR "CheckJsonConfined.cmake: pass -DRRF_ROOT=<source dir>")
endif()
get_filename_component(RRF_ROOT "${RRF_ROOT}" ABSOLUTE)

file(GLOB_RECURSE files RELATIVE ${RRF_ROOT} ${RRF_ROOT}/core/*.h ${RRF_ROOT}/core/*.cpp ${RRF_ROOT}/app/*.h
     ${RRF_ROOT}/app/*.cpp ${RRF_ROOT}/panels/*.h ${RRF_ROOT}/panels/*.cpp)
set(problems "")
set(codecs 0)
foreach(f ${files})
  if(f MATCHES "_(json|file)\\.(h|cpp)$" OR f MATCHES "^core/util/json_reader\\.(h|cpp)$")
    math(EXPR codecs "${codecs} + 1")
    continue()
  endif()
  file(STRINGS ${RRF_ROOT}/${f} uses REGEX "nlohmann")
  if(uses)
    list(GET uses 0 first)
    string(STRIP "${first}" first)
    string(APPEND problems "  ${f}: ${first}\n")
  endif()
endforeach()
if(problems)
  message(FATAL_ERROR "nlohmann outside the file codecs (move the JSON code to a <name>_json.h/.cpp "
                      "beside the type; unknown keys travel as JsonText):\n${problems}")
endif()
get_filename_component(RRF_ROOT "${RRF_ROOT}" ABSOLUTE)
list(LENGTH files n)
message(STATUS "json confined: ${n} files, nlohmann only in the ${codecs} file codecs")
