# Line writers (OBJ, JSON, SVG, GLB): pure text, no filesystem.
add_library(crestline_writers
  src/io/write_lines.cpp
  src/io/write_glb.cpp
  src/io/svg_writer.cpp
)
target_link_libraries(crestline_writers PUBLIC crestline_core)
target_compile_options(crestline_writers PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra>)
# {fmt}'s Dragonbox gives each number's shortest digits (header-only, so
# native and WASM run the same code); fast_float reads back the few numbers
# formatted by precision (write_lines.cpp says why).
if(EMSCRIPTEN)
  set(CRESTLINE_WRITERS_INCLUDE ${CMAKE_CURRENT_BINARY_DIR}/writers-include)
  file(COPY /usr/include/fast_float /usr/include/fmt DESTINATION ${CRESTLINE_WRITERS_INCLUDE})
  target_include_directories(crestline_writers SYSTEM PRIVATE ${CRESTLINE_WRITERS_INCLUDE})
  target_compile_definitions(crestline_writers PRIVATE FMT_HEADER_ONLY=1)
else()
  find_package(FastFloat REQUIRED CONFIG)  # Debian libfast-float-dev
  find_package(fmt 9 REQUIRED CONFIG)  # Debian libfmt-dev
  target_link_libraries(crestline_writers PRIVATE FastFloat::fast_float fmt::fmt-header-only)
endif()
