# Precompiled headers (RRF_PCH, on by default). Most of the build's compile time is spent parsing
# the same large headers in every source — Eigen, nlohmann/json, GoogleTest, the standard library —
# and CI builds everything from scratch twice (Release and the sanitizer builds, scripts/test.sh),
# so each target parses them once instead. Nothing is added to what a source may use: the layering
# check (cmake/CheckLayers.cmake) reads the sources' own #include lines.
option(RRF_PCH "Precompile the large third-party and standard headers" ON)

if(RRF_PCH)
  set(rrf_pch_std <algorithm> <atomic> <cmath> <cstdint> <functional> <map> <memory> <mutex>
                  <optional> <sstream> <string> <vector>)
  set(rrf_pch_common ${rrf_pch_std} <nlohmann/json.hpp> <Eigen/Dense>)
  # panels/ must not parse JSON: its precompiled header leaves nlohmann out, so a panel that used it
  # without including it would not compile.
  if(TARGET rrf_panels)
    target_precompile_headers(rrf_panels PRIVATE ${rrf_pch_std} <Eigen/Dense>)
  endif()
  foreach(t rrf_core rrf rrf-workbench rrf_gl)
    if(TARGET ${t})
      target_precompile_headers(${t} PRIVATE ${rrf_pch_common})
    endif()
  endforeach()
  # The test executables share one precompiled header with GoogleTest added.
  foreach(t rrf_tests rrf_gui_tests rrf_gl_tests rrf_threaded_tests)
    if(TARGET ${t})
      target_precompile_headers(${t} PRIVATE ${rrf_pch_common} <gtest/gtest.h>)
    endif()
  endforeach()
endif()
