# CTest isa_symbols: the instruction-set builds of the MLP passes (core/nn/mlp_isa.h) and of the
# path tracer's lanes (core/render/path_lanes.h) may define global or weak symbols only in their own
# namespaces (rrf::mlp_isa::<isa> with Eigen renamed rrf_eigen_<isa>; rrf::path_lanes::<isa>). Any
# other such symbol is an inline function or template compiled with AVX2 or AVX-512 that the linker
# may pick for the portable code's callers, which would then fail with an illegal instruction on a
# CPU without them.
#   cmake -DRRF_NM=<nm> -DRRF_LIBRARY=<librrf_core.a> -P CheckIsaSymbols.cmake
execute_process(COMMAND ${RRF_NM} -A --defined-only ${RRF_LIBRARY} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "isa_symbols: ${RRF_NM} failed on ${RRF_LIBRARY}")
endif()
string(REPLACE "\n" ";" lines "${out}")
set(bad "")

# The symbols of object `unit`.cpp.o: those matching `own` are its namespace's, of which `expected`
# must match `count` (its entry points); anything else shared goes to `bad`.
function(check_unit unit own expected count what)
  set(found 0)
  foreach(line IN LISTS lines)
    # GNU nm prints "lib.a:obj.o:ADDR T name", llvm-nm "lib.a:obj.o: ADDR T name".
    if(NOT line MATCHES ":${unit}\\.cpp\\.o: ?[0-9a-f]* (.) (.*)$")
      continue()
    endif()
    set(type "${CMAKE_MATCH_1}")
    set(name "${CMAKE_MATCH_2}")
    # Local symbols (t, d, b, r, s, g, a, n) and debugging entries cannot be shared; everything else
    # can: capitals, 'u' (unique global), 'i' (ifunc), 'v'/'w' and unknown types ('?').
    if(type MATCHES "^[abdgnrstN-]$")
      continue()
    endif()
    if(name MATCHES "${own}")
      if(name MATCHES "${expected}")
        math(EXPR found "${found} + 1")
      endif()
      continue()
    endif()
    # The personality routine's reference is data (a pointer to libstdc++'s), not code; so are
    # type-info objects and their names.
    if(name MATCHES "^DW\\.ref\\.__g(xx|cc)_personality_v0$" OR name MATCHES "^_ZT[IS]")
      continue()
    endif()
    list(APPEND bad "${unit}.cpp.o: ${type} ${name}")
  endforeach()
  if(NOT found EQUAL count)
    list(APPEND bad "${unit}.cpp.o: expected ${what}, found ${found}")
  endif()
  set(bad "${bad}" PARENT_SCOPE)
endfunction()

foreach(isa avx2 avx512)
  check_unit(mlp_isa_${isa} "rrf_eigen_${isa}|7mlp_isa[0-9]+${isa}" "^_ZN3rrf7mlp_isa[0-9]+${isa}(7forward|8backward)" 4
             "its 4 passes (forward, backward for float and double)")
  string(LENGTH "${isa}" len)
  check_unit(path_lanes_${isa} "^_ZN3rrf10path_lanes${len}${isa}" "^_ZN3rrf10path_lanes${len}${isa}(4step|5start)" 2
             "its step and start")
endforeach()
if(bad)
  string(REPLACE ";" "\n  " text "${bad}")
  message(FATAL_ERROR "isa_symbols: symbols outside the instruction-set namespaces:\n  ${text}")
endif()
message(STATUS "isa_symbols: ok")
