# Line writers (core/src/io/write_lines.cpp, write_glb.cpp, svg_writer.cpp).
target_sources(crestline_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/write_lines_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/write_glb_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/svg_writer_test.cpp
)
