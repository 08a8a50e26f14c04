// Every input that ever crashed a fuzz target (fuzz/), replayed through the
// same check the target runs: inputs/<target>/<name>, one file per finding,
// named after the bug. A regression shows as a sanitizer report, a crash, an
// exception that is not crestline::Error, or a broken contract.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "fuzz_inputs.h"
#include "triangulate_polygon.h"

using crestline::io::MeshFormat;

namespace {

std::vector<uint8_t> load(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// Runs `check` on every file of inputs/<target>; returns how many there were.
template <typename Check>
size_t replay(const std::string& target, Check check) {
  const std::filesystem::path dir = std::filesystem::path(CRESTLINE_HARDENING_INPUTS) / target;
  size_t count = 0;
  if (!std::filesystem::is_directory(dir)) return 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::vector<uint8_t> bytes = load(entry.path());
    INFO(target << " input " << entry.path().filename().string());
    CHECK(check(bytes.data(), bytes.size()) == "");
    ++count;
  }
  return count;
}

TEST_CASE("fuzzer findings stay fixed: readers", "[hardening][fuzz]") {
  const std::pair<const char*, MeshFormat> targets[] = {{"obj", MeshFormat::Obj},
                                                        {"gltf", MeshFormat::Gltf},
                                                        {"ply", MeshFormat::Ply},
                                                        {"stl", MeshFormat::Stl},
                                                        {"off", MeshFormat::Off}};
  for (const auto& [target, format] : targets) {
    replay(target, [format = format](const uint8_t* data, size_t size) {
      return crestline::fuzz::check_read(format, data, size);
    });
  }
}

TEST_CASE("fuzzer findings stay fixed: whole pipeline", "[hardening][fuzz]") {
  CHECK(replay("pipeline", crestline::fuzz::check_pipeline) > 0);
}

// The ear clipper's work for reading `text` (an OBJ whose longest face has
// `corners` corners), checked to give corners - 2 triangles.
crestline::io::detail::PolygonWork clipping_work(const std::string& text, size_t corners) {
  crestline::io::detail::polygon_work() = {};
  const crestline::TriangleSoup soup =
      crestline::io::read_mesh_bytes("face.obj", std::vector<uint8_t>(text.begin(), text.end()));
  CHECK(soup.triangle_count() >= corners - 2);
  return crestline::io::detail::polygon_work();
}

// The longest face of an OBJ in inputs/obj, `copies` times over, after the
// eight corners of a cube; and its number of corners.
std::string longest_face_repeated(const char* name, int copies, size_t& corners) {
  std::ifstream file(std::filesystem::path(CRESTLINE_HARDENING_INPUTS) / "obj" / name);
  std::string line, face;
  while (std::getline(file, line))
    if (line.rfind("f ", 0) == 0 && line.size() > face.size() + 1) face = line.substr(1);  // the longest
  REQUIRE(!face.empty());
  std::string text =
      "v -0.5 -0.5 0.5\nv -0.5 -0.5 -0.5\nv -0.5 0.5 -0.5\nv -0.5 0.5 0.5\n"
      "v 0.5 -0.5 0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv 0.5 0.5 0.5\nf";
  for (int copy = 0; copy < copies; ++copy) text += face;
  text += "\n";
  std::istringstream words(text.substr(text.find('f') + 1));
  corners = 0;
  for (std::string w; words >> w;) ++corners;
  return text;
}

}  // namespace

// The OBJ fuzz target hung on one face of 493 corners cycling through the
// four corners of a cube side with a few slips. Ear clipping found no ear,
// clipped a forced corner and searched a whole turn again, each turn
// costing O(n) ear tests: 1.6 s for this face four times over. A later run
// timed out on a face of 6,017 corners winding one square 1,500 times.
// Counted, not timed: such faces may cost no more ear tests, index nodes and
// points per corner than a convex face (the cubic clipper made n ear tests
// per corner).
TEST_CASE("a face without ears costs no more than a convex one", "[hardening][fuzz][complexity]") {
  for (const auto& [name, copies] : {std::pair<const char*, int>{"long-face-repeated-corners-cubic-clipping.obj", 4},
                                     {"square-wound-1500-times-slow-clipping.obj", 4}}) {
    size_t corners = 0;
    const std::string earless = longest_face_repeated(name, copies, corners);
    std::string convex, convex_face = "f";
    for (size_t i = 0; i < corners; ++i) {
      const double a = 2 * 3.14159265358979 * double(i) / double(corners);
      convex += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
      convex_face += " " + std::to_string(i + 1);
    }
    convex += convex_face + "\n";
    const crestline::io::detail::PolygonWork base = clipping_work(convex, corners),
                                             cycled = clipping_work(earless, corners);
    INFO(name << " x" << copies << ", " << corners << " corners: ear tests " << cycled.ear_tests << " (convex "
              << base.ear_tests << "), nodes " << cycled.nodes << " (" << base.nodes << "), points " << cycled.points
              << " (" << base.points << ")");
    CHECK(cycled.ear_tests <= 4 * corners);
    CHECK(cycled.nodes <= 2 * base.nodes);
    CHECK(cycled.points <= 2 * base.points);
  }
}
