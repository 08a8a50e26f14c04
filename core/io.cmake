# Readers and writers. Owned by the IO work; writers are format-free text.
add_library(crestline_io
  src/io/write_lines.cpp
  src/io/svg_writer.cpp
)
target_link_libraries(crestline_io PUBLIC crestline_core)
