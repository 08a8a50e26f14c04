#pragma once
// Access to ../shared/meshes for tests. When the folder is absent, tests that
// need it call SKIP_WITHOUT_MESHES() and report the skip visibly.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

namespace crestline::testing {

inline std::filesystem::path meshes_dir() { return CRESTLINE_MESHES_DIR; }
inline bool have_meshes() { return std::filesystem::is_directory(meshes_dir()); }
inline std::string mesh_path(const std::string& relative) { return (meshes_dir() / relative).string(); }

}  // namespace crestline::testing

// Catch2 v2 has no SKIP: warn (shown in the output) and leave the test case.
#define SKIP_WITHOUT_MESHES()                                                         \
  do {                                                                                \
    if (!crestline::testing::have_meshes()) {                                         \
      WARN("SKIPPED: " << crestline::testing::meshes_dir().string() << " is absent"); \
      return;                                                                         \
    }                                                                                 \
  } while (0)
