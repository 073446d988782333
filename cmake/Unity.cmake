# Unity builds (-DCMAKE_UNITY_BUILD=ON; CI passes it to every build it makes, scripts/test.sh and
# scripts/sanitize.sh). Batches of sources are compiled as one translation unit, so the large
# headers (Eigen, nlohmann/json, GoogleTest, the standard library) are parsed and their templates
# instantiated once per batch instead of once per source: measured in docs/design.md §22.
# A source that is part of a batch must not define file-local names that another source of the same
# target defines too; the test sources therefore keep their helpers in a namespace named after the
# file (tests/test_brdf.cpp: namespace test_brdf), and so do the panels' (panels/log_panel.cpp:
# namespace rrf::panels::log_panel_detail, called qualified from the file's public functions).
# These sources, whose file-local helpers share names with other sources', are compiled on their own.
set(CMAKE_UNITY_BUILD_BATCH_SIZE 16 CACHE STRING "Sources per unity batch")
set_source_files_properties(
  core/eval/reference_store.cpp core/nn/model_file.cpp core/nn/model_set_file.cpp core/project/scene_overrides.cpp
  tests/quad_reference.cpp
  PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
