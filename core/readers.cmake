# Mesh readers, one file per format behind io::read_mesh.
add_library(crestline_readers
  src/io/read_mesh.cpp
)
target_link_libraries(crestline_readers PUBLIC crestline_core)
