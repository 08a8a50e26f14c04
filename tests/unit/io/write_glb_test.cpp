// GLB output: a valid glTF 2.0 binary that the project's own reader opens,
// with the lines as LINE_STRIP primitives in nodes "ridges" and "valleys".
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "crestline/io/write_lines.h"
#include "test_polylines.h"

using crestline::LineType;
using crestline::Polyline;
using crestline::Vec3;
using crestline::testing::test_line;

namespace {

uint32_t u32(const std::vector<uint8_t>& bytes, size_t offset) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = value << 8 | bytes.at(offset + i);
  return value;
}

// A unit cube's 8 corners and 12 triangles.
crestline::Mesh cube() {
  crestline::Mesh mesh;
  for (int i = 0; i < 8; ++i) mesh.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

std::vector<Polyline> lines() {
  return {test_line(LineType::Valley, {{0, 0, 0}, {1, 0, 0}}, false),
          test_line(LineType::Ridge, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, false),
          test_line(LineType::Ridge, {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}}, true),
          test_line(LineType::Ridge, {{5, 5, 5}}, false)};  // a single point: left out
}

// Checks the GLB framing and returns the JSON chunk parsed.
nlohmann::json parse_glb(const std::vector<uint8_t>& glb) {
  REQUIRE(glb.size() >= 20);
  CHECK(u32(glb, 0) == 0x46546C67);  // "glTF"
  CHECK(u32(glb, 4) == 2);
  CHECK(u32(glb, 8) == glb.size());
  const uint32_t json_length = u32(glb, 12);
  CHECK(u32(glb, 16) == 0x4E4F534A);  // "JSON"
  CHECK(json_length % 4 == 0);
  REQUIRE(20 + json_length <= glb.size());
  const size_t bin_chunk = 20 + json_length;
  if (bin_chunk < glb.size()) {
    const uint32_t bin_length = u32(glb, bin_chunk);
    CHECK(bin_length % 4 == 0);
    CHECK(u32(glb, bin_chunk + 4) == 0x004E4942);  // "BIN\0"
    CHECK(bin_chunk + 8 + bin_length == glb.size());
  }
  return nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + json_length);
}

// Index counts of the LINE_STRIP primitives of the node called `name`.
std::vector<size_t> strip_lengths(const nlohmann::json& gltf, const std::string& name) {
  std::vector<size_t> counts;
  for (const auto& node : gltf["nodes"]) {
    if (node["name"] != name || !node.contains("mesh")) continue;
    const auto& mesh = gltf["meshes"][node["mesh"].get<size_t>()];
    CHECK(mesh["name"] == name);
    for (const auto& primitive : mesh["primitives"]) {
      CHECK(primitive["mode"] == 3);
      const auto& positions = gltf["accessors"][primitive["attributes"]["POSITION"].get<size_t>()];
      CHECK(positions["componentType"] == 5126);
      CHECK(positions["type"] == "VEC3");
      CHECK(positions["min"].size() == 3);
      CHECK(positions["max"].size() == 3);
      const auto& indices = gltf["accessors"][primitive["indices"].get<size_t>()];
      CHECK(indices["componentType"] == 5125);
      counts.push_back(indices["count"].get<size_t>());
    }
  }
  return counts;
}

}  // namespace

TEST_CASE("GLB with the mesh reads back with its triangles; lines are LINE_STRIPs", "[io][writers][glb]") {
  const crestline::Mesh mesh = cube();
  const std::vector<uint8_t> glb = crestline::io::write_glb(&mesh, lines());

  const nlohmann::json gltf = parse_glb(glb);
  CHECK(gltf["asset"]["version"] == "2.0");
  REQUIRE(gltf["buffers"].size() == 1);
  CHECK(strip_lengths(gltf, "ridges") == std::vector<size_t>{3, 5});  // closed: first index repeated
  CHECK(strip_lengths(gltf, "valleys") == std::vector<size_t>{2});
  // Ridges red, valleys blue.
  const auto color_of = [&gltf](const std::string& name) {
    for (const auto& node : gltf["nodes"])
      if (node["name"] == name) {
        const size_t material = gltf["meshes"][node["mesh"].get<size_t>()]["primitives"][0]["material"];
        return gltf["materials"][material]["pbrMetallicRoughness"]["baseColorFactor"].get<std::vector<double>>();
      }
    FAIL("no node " << name);
    return std::vector<double>{};
  };
  const std::vector<double> red = color_of("ridges"), blue = color_of("valleys");
  CHECK(red[0] > red[2]);
  CHECK(blue[2] > blue[0]);
  // The surface's bounds are the cube's.
  for (const auto& node : gltf["nodes"])
    if (node["name"] == "surface") {
      const auto& primitive = gltf["meshes"][node["mesh"].get<size_t>()]["primitives"][0];
      CHECK(primitive["mode"] == 4);
      const auto& positions = gltf["accessors"][primitive["attributes"]["POSITION"].get<size_t>()];
      CHECK(positions["min"] == nlohmann::json::array({0, 0, 0}));
      CHECK(positions["max"] == nlohmann::json::array({1, 1, 1}));
    }

  // The project's reader skips the lines (with a note) and gets the cube back.
  const crestline::TriangleSoup soup = crestline::io::read_mesh_bytes("out.glb", glb);
  CHECK(soup.triangle_count() == mesh.triangle_count());
  CHECK(soup.vertex_count() == mesh.vertex_count());
  CHECK_FALSE(soup.notes.empty());
  CHECK(crestline::io::detect_format("out.bin", glb.data(), glb.size()) == crestline::io::MeshFormat::Glb);
}

TEST_CASE("GLB of lines only has no surface and no triangles", "[io][writers][glb]") {
  const std::vector<uint8_t> glb = crestline::io::write_glb(nullptr, lines());
  const nlohmann::json gltf = parse_glb(glb);
  for (const auto& node : gltf["nodes"]) CHECK(node["name"] != "surface");
  CHECK(strip_lengths(gltf, "ridges").size() == 2);
  CHECK(strip_lengths(gltf, "valleys").size() == 1);
  CHECK_THROWS_AS(crestline::io::read_mesh_bytes("lines.glb", glb), crestline::Error);
}

TEST_CASE("GLB without lines is still a valid file with both nodes", "[io][writers][glb]") {
  const std::vector<uint8_t> glb = crestline::io::write_glb(nullptr, {});
  const nlohmann::json gltf = parse_glb(glb);
  REQUIRE(gltf["nodes"].size() == 2);
  CHECK(gltf["nodes"][0]["name"] == "ridges");
  CHECK(gltf["nodes"][1]["name"] == "valleys");
  CHECK_FALSE(gltf.contains("meshes"));
  CHECK(glb.size() == 20 + u32(glb, 12));  // no BIN chunk
}

TEST_CASE("GLB: creases in node \"creases\", each primitive with extras.convex", "[io][writers][glb][creases]") {
  std::vector<crestline::Polyline> with_creases = lines();
  with_creases.push_back(test_line(LineType::Crease, {{0, 0, 0}, {0, 0, 1}}, false));
  with_creases.back().convex = true;
  with_creases.push_back(test_line(LineType::Crease, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}}, false));
  const nlohmann::json gltf = parse_glb(crestline::io::write_glb(nullptr, with_creases));
  CHECK(strip_lengths(gltf, "creases") == std::vector<size_t>{2, 3});
  for (const auto& node : gltf["nodes"])
    if (node["name"] == "creases") {
      const auto& primitives = gltf["meshes"][node["mesh"].get<size_t>()]["primitives"];
      CHECK(primitives[0]["extras"]["convex"] == true);
      CHECK(primitives[1]["extras"]["convex"] == false);
      const size_t material = primitives[0]["material"];
      CHECK(gltf["materials"][material]["name"] == "crease");
    }
  // No creases: no node for them.
  // Named: a range-for over a member of a temporary would read freed memory.
  const nlohmann::json without = parse_glb(crestline::io::write_glb(nullptr, lines()));
  for (const auto& node : without["nodes"]) CHECK(node["name"] != "creases");
}
