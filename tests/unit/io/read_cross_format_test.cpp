// The same mesh through every format gives the same triangles: the shared
// fandisk as OBJ and GLB, and that soup written here as PLY (ASCII and both
// binary byte orders), STL (binary and ASCII) and OFF, then read back.
// Triangles are compared corner by corner, so STL's unshared vertices and
// float precision do not matter.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "crestline/io/read_mesh.h"
#include "read_test_bytes.h"
#include "run_pipeline.h"
#include "test_meshes.h"

using crestline::TriangleSoup;
using crestline::io::read_mesh_bytes;
using crestline::testing::bytes_of;
using crestline::testing::put;

namespace {

std::string text_numbers(const TriangleSoup& soup, const std::string& face_prefix) {
  std::ostringstream s;
  s.precision(17);
  for (size_t v = 0; v < soup.vertex_count(); ++v) {
    s << soup.positions[3 * v] << ' ' << soup.positions[3 * v + 1] << ' ' << soup.positions[3 * v + 2] << '\n';
  }
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    s << face_prefix << soup.indices[3 * t] << ' ' << soup.indices[3 * t + 1] << ' ' << soup.indices[3 * t + 2] << '\n';
  }
  return s.str();
}

std::vector<uint8_t> to_ply(const TriangleSoup& soup, const std::string& format) {
  const std::string header = "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(soup.vertex_count()) +
                             "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                             std::to_string(soup.triangle_count()) +
                             "\nproperty list uchar uint vertex_indices\nend_header\n";
  if (format == "ascii") return bytes_of(header + text_numbers(soup, "3 "));
  const bool big = format == "binary_big_endian";
  std::vector<uint8_t> out = bytes_of(header);
  for (double c : soup.positions) put(out, c, big);
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    put(out, uint8_t(3), big);
    for (int k = 0; k < 3; ++k) put(out, soup.indices[3 * t + size_t(k)], big);
  }
  return out;
}

std::vector<uint8_t> to_off(const TriangleSoup& soup) {
  return bytes_of("OFF\n# written by a test\n" + std::to_string(soup.vertex_count()) + " " +
                  std::to_string(soup.triangle_count()) + " 0\n" + text_numbers(soup, "3 "));
}

std::vector<uint8_t> to_binary_stl(const TriangleSoup& soup) {
  std::vector<uint8_t> out = bytes_of("solid but binary");
  out.resize(80, ' ');
  put(out, uint32_t(soup.triangle_count()));
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) put(out, 0.0f);
    for (int k = 0; k < 9; ++k)
      put(out, float(soup.positions[3 * soup.indices[3 * t + size_t(k / 3)] + size_t(k % 3)]));
    put(out, uint16_t(0));
  }
  return out;
}

std::vector<uint8_t> to_ascii_stl(const TriangleSoup& soup) {
  std::ostringstream s;
  s.precision(9);
  s << "solid fandisk\n";
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    s << "facet normal 0 0 0\nouter loop\n";
    for (int k = 0; k < 3; ++k) {
      const double* p = &soup.positions[3 * soup.indices[3 * t + size_t(k)]];
      s << "vertex " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
    s << "endloop\nendfacet\n";
  }
  s << "endsolid fandisk\n";
  return bytes_of(s.str());
}

// Largest difference between corresponding triangle corners.
double corner_distance(const TriangleSoup& a, const TriangleSoup& b) {
  REQUIRE(a.triangle_count() == b.triangle_count());
  double worst = 0;
  for (size_t k = 0; k < a.indices.size(); ++k) {
    for (size_t c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(a.positions[3 * a.indices[k] + c] - b.positions[3 * b.indices[k] + c]));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("the same mesh gives the same triangles in every format", "[io][meshes]") {
  SKIP_WITHOUT_MESHES();
  const TriangleSoup obj = crestline::io::read_mesh(crestline::testing::mesh_path("cad/fandisk.obj"));
  const TriangleSoup glb = crestline::io::read_mesh(crestline::testing::mesh_path("glb/fandisk.glb"));
  REQUIRE(obj.triangle_count() == 12946);
  CHECK(corner_distance(obj, glb) < 1e-5);  // GLB stores float

  struct Variant {
    const char* name;
    std::vector<uint8_t> bytes;
    double tolerance;
  };
  const Variant variants[] = {
      {"fandisk.ply", to_ply(obj, "ascii"), 1e-12},
      {"fandisk-le.ply", to_ply(obj, "binary_little_endian"), 0},
      {"fandisk-be.ply", to_ply(obj, "binary_big_endian"), 0},
      {"fandisk.off", to_off(obj), 1e-12},
      {"fandisk.stl", to_binary_stl(obj), 1e-5},
      {"fandisk-ascii.stl", to_ascii_stl(obj), 1e-5},
  };
  for (const Variant& v : variants) {
    INFO("format: " << v.name);
    const TriangleSoup soup = read_mesh_bytes(v.name, v.bytes);
    CHECK(corner_distance(obj, soup) <= v.tolerance);
  }
}

TEST_CASE("the same mesh in every format gives the same welded mesh and the same lines", "[io][meshes][pipeline]") {
  SKIP_WITHOUT_MESHES();
  const TriangleSoup obj = crestline::io::read_mesh(crestline::testing::mesh_path("cad/fandisk.obj"));
  const crestline::Pipeline reference = crestline::testing::run_pipeline(obj);
  const crestline::PipelineStats ref = reference.stats();
  // 39 creases; with --crease-boundaries the smooth lines stop at them (5 remain).
  REQUIRE(ref.ridges + ref.valleys >= 3);
  REQUIRE(ref.creases > 30);

  struct Variant {
    const char* name;
    TriangleSoup soup;
    bool exact;  // stores the OBJ's doubles exactly; otherwise float32
  };
  const Variant variants[] = {
      {"fandisk.glb", crestline::io::read_mesh(crestline::testing::mesh_path("glb/fandisk.glb")), false},
      {"fandisk-le.ply", read_mesh_bytes("fandisk-le.ply", to_ply(obj, "binary_little_endian")), true},
      {"fandisk.off", read_mesh_bytes("fandisk.off", to_off(obj)), true},
      {"fandisk.stl", read_mesh_bytes("fandisk.stl", to_binary_stl(obj)), false},
  };
  for (const Variant& v : variants) {
    INFO("format: " << v.name);
    const crestline::Pipeline p = crestline::testing::run_pipeline(v.soup);
    const crestline::PipelineStats s = p.stats();
    // STL has no shared vertices: welding must rebuild the same mesh.
    CHECK(s.vertices == ref.vertices);
    CHECK(s.triangles == ref.triangles);
    CHECK(s.creases == ref.creases);
    if (v.exact) {
      CHECK(s.ridges == ref.ridges);
      CHECK(s.valleys == ref.valleys);
      CHECK(s.ridge_length == Approx(ref.ridge_length).epsilon(1e-9));
      CHECK(s.valley_length == Approx(ref.valley_length).epsilon(1e-9));
    } else {
      // float32 coordinates move crossings by round-off; the lines stay.
      CHECK(s.ridge_length == Approx(ref.ridge_length).epsilon(0.02));
      CHECK(s.valley_length == Approx(ref.valley_length).epsilon(0.02));
    }
  }
}
