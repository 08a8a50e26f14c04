# Hardening (issue 8): replays of every input a fuzz target crashed on,
# scale and degenerate-input numerics, size limits and complexity guards.
target_sources(crestline_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/replay_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/numerics_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/limits_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/hostile_files_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/polygon_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mutator_test.cpp
)
# The replay test decodes inputs exactly as the fuzz targets do.
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/replay_test.cpp PROPERTIES
  INCLUDE_DIRECTORIES "${PROJECT_SOURCE_DIR}/fuzz;${PROJECT_SOURCE_DIR}/core/src/io"
  COMPILE_DEFINITIONS CRESTLINE_HARDENING_INPUTS="${CMAKE_CURRENT_LIST_DIR}/inputs")
# The mutator test runs the fuzzers' text mutator on their seeds.
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/mutator_test.cpp PROPERTIES
  INCLUDE_DIRECTORIES "${PROJECT_SOURCE_DIR}/fuzz;${PROJECT_SOURCE_DIR}/core/src/io"
  COMPILE_DEFINITIONS CRESTLINE_FUZZ_SEEDS="${PROJECT_SOURCE_DIR}/fuzz/seeds")
# The polygon test counts the ear clipper's work (triangulate_polygon.h).
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/polygon_test.cpp PROPERTIES
  INCLUDE_DIRECTORIES ${PROJECT_SOURCE_DIR}/core/src/io)
