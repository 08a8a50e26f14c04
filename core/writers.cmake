# Line writers (OBJ, JSON, SVG, GLB): pure text, no filesystem.
add_library(crestline_writers
  src/io/write_lines.cpp
  src/io/write_glb.cpp
  src/io/svg_writer.cpp
)
target_link_libraries(crestline_writers PUBLIC crestline_core)
target_compile_options(crestline_writers PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra>)
