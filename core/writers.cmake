# Line writers (OBJ, JSON, SVG, GLB): pure text, no filesystem.
add_library(crestline_writers
  src/io/write_lines.cpp
  src/io/write_glb.cpp
  src/io/svg_writer.cpp
)
target_link_libraries(crestline_writers PUBLIC crestline_core)
target_compile_options(crestline_writers PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra>)
# fast_float reads each number back where the standard library has no
# floating-point to_chars (Emscripten's libc++; write_lines.cpp says why).
if(EMSCRIPTEN)
  set(CRESTLINE_WRITERS_INCLUDE ${CMAKE_CURRENT_BINARY_DIR}/writers-include)
  file(COPY /usr/include/fast_float DESTINATION ${CRESTLINE_WRITERS_INCLUDE})
  target_include_directories(crestline_writers SYSTEM PRIVATE ${CRESTLINE_WRITERS_INCLUDE})
else()
  find_package(FastFloat REQUIRED CONFIG)  # Debian libfast-float-dev
  target_link_libraries(crestline_writers PRIVATE FastFloat::fast_float)
endif()
