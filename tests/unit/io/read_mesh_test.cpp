// Every file of ../shared/meshes/{glb,gltf,robust,large} with its expected
// outcome, written down here: the soup as read (vertices and triangles,
// unwelded) or the kind of error. The counts are the MANIFEST's stored V and
// T columns unless a comment says why they differ.
#include "crestline/io/read_mesh.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "crestline/error.h"
#include "test_meshes.h"

using crestline::Error;
using crestline::ErrorKind;
using crestline::TriangleSoup;
using crestline::io::read_mesh;
namespace fs = std::filesystem;

namespace {

struct Case {
  const char* path;
  size_t vertices;
  size_t triangles;
  std::optional<ErrorKind> error;
};

Case ok(const char* path, size_t vertices, size_t triangles) { return {path, vertices, triangles, std::nullopt}; }
Case bad(const char* path, ErrorKind kind) { return {path, 0, 0, kind}; }

const std::vector<Case>& cases() {
  static const std::vector<Case> table = {
      // glb/
      ok("glb/Box.glb", 24, 12),
      ok("glb/Box-draco.glb", 24, 12),
      ok("glb/BoxMeshopt.glb", 24, 12),
      ok("glb/BoxTextured.glb", 24, 12),
      ok("glb/DamagedHelmet.glb", 14556, 15452),
      ok("glb/Duck.glb", 2399, 4212),
      ok("glb/Duck-quantized.glb", 2399, 4212),
      ok("glb/OrientationTest.glb", 1048, 524),
      ok("glb/VertexColorTest.glb", 72, 36),
      ok("glb/bunny-mcguire.glb", 72027, 144046),
      ok("glb/fandisk.glb", 6475, 12946),
      ok("glb/feline.glb", 49864, 99732),
      ok("glb/occt-motor.glb", 6635, 13506),
      ok("glb/occt-motor-soup.glb", 40518, 13506),
      ok("glb/pirate-meshopt.glb", 2887, 5010),
      ok("glb/pmndrs-bunny-draco.glb", 2826, 5648),
      ok("glb/pmndrs-suzi-draco.glb", 7503, 14842),
      ok("glb/stanford-bunny.glb", 35947, 69451),
      // gltf/
      ok("gltf/Box-draco/Box.gltf", 24, 12),
      ok("gltf/BoxTextured/BoxTextured.gltf", 24, 12),
      // The wheels mesh (586 vertices, 768 triangles) is instanced by two
      // nodes; the MANIFEST counts it once (2978 / 2856).
      ok("gltf/CesiumMilkTruck/CesiumMilkTruck.gltf", 2978 + 586, 2856 + 768),
      ok("gltf/DamagedHelmet/DamagedHelmet.gltf", 14556, 15452),
      ok("gltf/DracoSparseMesh/DracoSparseMesh.gltf", 62, 102),
      ok("gltf/Duck/Duck.gltf", 2399, 4212),
      ok("gltf/OrientationTest/OrientationTest.gltf", 1048, 524),
      ok("gltf/SimpleSparseAccessor/SimpleSparseAccessor.gltf", 14, 12),
      ok("gltf/TriangleWithoutIndices/TriangleWithoutIndices.gltf", 3, 1),
      // large/
      ok("large/dragon.glb", 437645, 871414),
      ok("large/dragon-draco.glb", 435545, 871306),
      // robust/gltf/: modes 00-03 and 07-10 are points and lines only.
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf", ErrorKind::InvalidInput),
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf", 4, 2),  // strip
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf", 4, 2),  // fan
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf", 6, 2),
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_07.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_08.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_09.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_10.gltf", ErrorKind::InvalidInput),
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_11.gltf", 4, 2),
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf", 4, 2),
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_13.gltf", 4, 2),
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_14.gltf", 4, 2),
      ok("robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_15.gltf", 4, 2),
      bad("robust/gltf/IndexOutOfRange/IndexOutOfRange.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/IndexOutOfRange/AllIndicesOutOfRange.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/BoxWithInfinites.glb", ErrorKind::InvalidInput),  // every vertex infinite
      ok("robust/gltf/BoxBadNormals.glb", 24, 12),
      bad("robust/gltf/RecursiveNodes.gltf", ErrorKind::InvalidInput),  // node cycle
      bad("robust/gltf/NoScene.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/SceneWithoutNodes.gltf", ErrorKind::InvalidInput),
      bad("robust/gltf/MissingBin/BoxTextured.gltf", ErrorKind::Io),
      ok("robust/gltf/ZeroLengthBufferView/ZeroLengthBufferView.gltf", 4, 2),
      // 4 of its 8 primitives are LINES; their 142 vertices are not read.
      ok("robust/gltf/IncorrectVertexArrays/Cube.gltf", 284 - 142, 46),
      // robust/obj/: vertices are the `v` lines, triangles n - 2 per n-gon.
      ok("robust/obj/nonmanifold-cubes-edge.obj", 14, 24),
      ok("robust/obj/nonmanifold-cubes-vertex.obj", 15, 24),
      ok("robust/obj/nonmanifold-hourglass.obj", 23, 40),
      ok("robust/obj/nonmanifold-triple-vierbein.obj", 75, 108),
      ok("robust/obj/nonmanifold-wrap.obj", 10, 12),
      ok("robust/obj/nonmanifold-test_nm.obj", 114, 170),
      ok("robust/obj/nonmanifold-back-to-back.obj", 6, 10),
      ok("robust/obj/boundary-box-notclosed.obj", 9, 12),
      ok("robust/obj/moebius.obj", 280, 448),
      ok("robust/obj/boundary-plane-holes.obj", 8519, 16747),
      ok("robust/obj/boundary-cube-no-bottom.obj", 25, 40),
      ok("robust/obj/boundary-elephant-holes.obj", 2798, 4463),
      ok("robust/obj/degenerate-faces.obj", 6, 4),
      ok("robust/obj/degenerate-all-coincident.obj", 3, 1),
      ok("robust/obj/degenerate-sliding.obj", 8, 8),
      ok("robust/obj/degenerate-zero-area-stl.obj", 9, 14),
      bad("robust/obj/nan-inf-coords.obj", ErrorKind::InvalidInput),  // every vertex non-finite
      ok("robust/obj/shared-vertices-two-groups.obj", 4, 2),
      ok("robust/obj/components-hundred-cubes.obj", 800, 1200),
      ok("robust/obj/components-isolated-triangles.obj", 15, 5),
      ok("robust/obj/components-tetrahedrons.obj", 20, 20),
      ok("robust/obj/components-platonic-shelf.obj", 50, 80),
      ok("robust/obj/components-blobby-3cc.obj", 1820, 3417),
      ok("robust/obj/polygon-concave.obj", 64, 64),
      ok("robust/obj/polygon-concave-o2g.obj", 10, 16),
      ok("robust/obj/polygon-octagon.obj", 8, 6),
      ok("robust/obj/polygon-dodecahedron.obj", 20, 36),
      ok("robust/obj/quads-pirate.obj", 2889, 5010),
      ok("robust/obj/quads-sword.obj", 22293, 44582),
      ok("robust/obj/quads-suzanne.obj", 507, 968),
      ok("robust/obj/negative-indices-box.obj", 8, 12),
      ok("robust/obj/negative-indices-triangle.obj", 3, 1),
      ok("robust/obj/attrs-normals-only.obj", 8, 12),
      ok("robust/obj/attrs-uvs-only.obj", 8, 12),
      ok("robust/obj/attrs-positions-only.obj", 8, 12),
      ok("robust/obj/attrs-mixed.obj", 8, 12),
      ok("robust/obj/attrs-incomplete-normals.obj", 8, 12),
      ok("robust/obj/box-objects-groups.obj", 24, 36),
      ok("robust/obj/box-uncleaned.obj", 8, 12),
      ok("robust/obj/box-with-tabs.obj", 8, 12),
      ok("robust/obj/syntax-number-formats.obj", 15, 1),
      ok("robust/obj/syntax-multiple-spaces.obj", 4, 1),
      ok("robust/obj/syntax-no-final-newline.obj", 8, 12),
      // UTF-16 is decoded (the MANIFEST's parser did not): the same box.
      ok("robust/obj/syntax-utf16be.obj", 8, 12),
      ok("robust/obj/syntax-long-line.obj", 8, 944),  // one 936-gon
      ok("robust/obj/vertex-colors.obj", 8, 12),
      ok("robust/obj/lines-points-mixed.obj", 8, 12),
      bad("robust/obj/lines-only.obj", ErrorKind::InvalidInput),
      bad("robust/obj/points-only.obj", ErrorKind::InvalidInput),
      bad("robust/obj/empty.obj", ErrorKind::InvalidInput),
      bad("robust/obj/malformed.obj", ErrorKind::InvalidInput),  // index 0 and 12 of 8
      ok("robust/obj/malformed2.obj", 8, 10),                    // an empty "f" line
      ok("robust/obj/badstl-tardis.obj", 1796, 3636),
      ok("robust/obj/badstl-wing.obj", 423, 842),
      ok("robust/obj/badstl-pcbvicebar.obj", 132, 260),
  };
  return table;
}

bool all_finite(const TriangleSoup& soup) {
  return std::all_of(soup.positions.begin(), soup.positions.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

TEST_CASE("every shared mesh reads with its expected outcome", "[io][meshes]") {
  SKIP_WITHOUT_MESHES();
  for (const Case& c : cases()) {
    const std::string name = fs::path(c.path).filename().string();
    INFO("mesh: " << c.path);
    if (c.error) {
      try {
        read_mesh(crestline::testing::mesh_path(c.path));
        FAIL("no error for " << c.path);
      } catch (const Error& e) {
        INFO("message: " << e.what());
        CHECK(e.kind() == *c.error);
        // One sentence that names the file.
        const std::string message = e.what();
        CHECK(message.rfind(name + ": ", 0) == 0);
        CHECK(message.back() == '.');
      }
      continue;
    }
    TriangleSoup soup;
    REQUIRE_NOTHROW(soup = read_mesh(crestline::testing::mesh_path(c.path)));
    CHECK(soup.vertex_count() == c.vertices);
    CHECK(soup.triangle_count() == c.triangles);
    CHECK(soup.positions.size() % 3 == 0);
    CHECK(std::all_of(soup.indices.begin(), soup.indices.end(), [&](uint32_t i) { return i < soup.vertex_count(); }));
    if (std::string(c.path) != "robust/obj/syntax-number-formats.obj") CHECK(all_finite(soup));
  }
}

TEST_CASE("the table covers every file of glb, gltf, robust and large", "[io][meshes]") {
  SKIP_WITHOUT_MESHES();
  std::set<std::string> listed;
  for (const Case& c : cases()) listed.insert(c.path);
  for (const char* folder : {"glb", "gltf", "robust", "large"}) {
    for (const auto& entry : fs::recursive_directory_iterator(crestline::testing::meshes_dir() / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".obj" && ext != ".gltf" && ext != ".glb") continue;
      const std::string relative = fs::relative(entry.path(), crestline::testing::meshes_dir()).generic_string();
      INFO("file without an expected outcome: " << relative);
      CHECK(listed.count(relative) == 1);
    }
  }
}

namespace {

std::array<double, 6> bounds(const TriangleSoup& soup) {
  std::array<double, 6> b = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (size_t v = 0; v < soup.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) {
      b[size_t(c)] = std::min(b[size_t(c)], soup.positions[3 * v + size_t(c)]);
      b[size_t(c) + 3] = std::max(b[size_t(c) + 3], soup.positions[3 * v + size_t(c)]);
    }
  }
  return b;
}

void check_same_bounds(const char* a, const char* b, double tolerance) {
  INFO(a << " vs " << b);
  const auto ba = bounds(read_mesh(crestline::testing::mesh_path(a)));
  const auto bb = bounds(read_mesh(crestline::testing::mesh_path(b)));
  for (size_t k = 0; k < 6; ++k) CHECK(ba[k] == Approx(bb[k]).margin(tolerance));
}

}  // namespace

TEST_CASE("compressed and quantized glTF decode to the same geometry", "[io][meshes]") {
  SKIP_WITHOUT_MESHES();
  // Box is the unit cube centred at the origin in every variant.
  check_same_bounds("glb/Box.glb", "glb/Box-draco.glb", 1e-3);
  check_same_bounds("glb/Box.glb", "glb/BoxMeshopt.glb", 1e-3);
  check_same_bounds("glb/Box.glb", "gltf/Box-draco/Box.gltf", 1e-3);
  // Quantized positions are dequantized by the node transform.
  check_same_bounds("glb/Duck.glb", "glb/Duck-quantized.glb", 0.05);
  check_same_bounds("glb/Duck.glb", "gltf/Duck/Duck.gltf", 1e-9);
  check_same_bounds("large/dragon.glb", "large/dragon-draco.glb", 1e-2);
  const auto box = bounds(read_mesh(crestline::testing::mesh_path("glb/Box.glb")));
  CHECK(box[0] == Approx(-0.5));
  CHECK(box[3] == Approx(0.5));
}

TEST_CASE("robust OBJ files: negative indices and index errors", "[io][meshes]") {
  SKIP_WITHOUT_MESHES();
  const TriangleSoup triangle = read_mesh(crestline::testing::mesh_path("robust/obj/negative-indices-triangle.obj"));
  CHECK(triangle.indices == std::vector<uint32_t>{0, 1, 2});
  try {
    read_mesh(crestline::testing::mesh_path("robust/gltf/IndexOutOfRange/IndexOutOfRange.gltf"));
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) ==
          "IndexOutOfRange.gltf: mesh 0 primitive 0 refers to vertex 255 but has only 24 vertices.");
  }
}
