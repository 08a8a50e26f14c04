# Reader tests: the shared meshes table and small in-memory files per format.
target_sources(crestline_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/read_mesh_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/read_formats_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/read_obj_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/read_cross_format_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/read_robust_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/weights_file_test.cpp
  # The CLI's weights reader, tested through its own source.
  ${PROJECT_SOURCE_DIR}/cli/files.cpp
)
