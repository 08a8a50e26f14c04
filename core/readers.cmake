# Mesh readers, one file per format behind io::read_mesh. tinygltf is
# compiled from its header (TINYGLTF_IMPLEMENTATION in read_gltf.cpp) and
# fast_float (OBJ numbers, read_obj.cpp) is header-only, so the same sources
# build with em++; Draco and meshoptimizer decode compressed glTF in the
# native build only (the browser decodes with three.js).
add_library(crestline_readers
  src/io/read_mesh.cpp
  src/io/read_obj.cpp
  src/io/read_gltf.cpp
  src/io/read_ply.cpp
  src/io/read_stl.cpp
  src/io/read_off.cpp
  src/io/triangulate_polygon.cpp
)
target_link_libraries(crestline_readers PUBLIC crestline_core)
target_compile_options(crestline_readers PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra>)
if(NOT EMSCRIPTEN)
  find_package(draco REQUIRED CONFIG)
  find_package(meshoptimizer REQUIRED CONFIG)
  find_package(FastFloat REQUIRED CONFIG)  # Debian libfast-float-dev
  target_link_libraries(crestline_readers PRIVATE draco::draco meshoptimizer::meshoptimizer FastFloat::fast_float)
endif()
if(EMSCRIPTEN)
  # The single-header libraries live in /usr/include, outside Emscripten's
  # sysroot; copy just them so no host system header leaks in.
  set(CRESTLINE_READERS_INCLUDE ${CMAKE_CURRENT_BINARY_DIR}/readers-include)
  file(COPY /usr/include/tiny_gltf.h /usr/include/nlohmann /usr/include/fast_float
       DESTINATION ${CRESTLINE_READERS_INCLUDE})
  target_include_directories(crestline_readers SYSTEM PRIVATE ${CRESTLINE_READERS_INCLUDE})
  # Readers report errors as exceptions, like the core (see wasm/CMakeLists.txt:
  # native WebAssembly exceptions, JavaScript-based ones in the threaded build).
  if(CRESTLINE_THREADS)
    target_compile_options(crestline_readers PRIVATE -fexceptions)
  else()
    target_compile_options(crestline_readers PRIVATE -fwasm-exceptions)
  endif()
endif()
