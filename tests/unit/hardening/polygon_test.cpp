// Large polygons (issue 18, item 2): one OBJ face of 2·10^5 corners took 60 s
// with the quadratic ear clipper. The indexed clipper must cost O(n log n)
// on convex and star-shaped outlines, counted in ear tests and in the index
// nodes and points they examine (no timings: the project checks speed with
// benchmarks), and still cut every simple polygon into n - 2 triangles that
// cover exactly its area with its orientation.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "crestline/io/read_mesh.h"
#include "triangulate_polygon.h"

using namespace crestline;

namespace {

// An OBJ face of `n` corners on a circle in the plane z = 0; every other
// corner is pulled in to `inner` (1: convex; below: a star, every other
// corner reflex).
std::string polygon_obj(size_t n, double inner) {
  std::string text;
  text.reserve(n * 40);
  char line[96];
  for (size_t i = 0; i < n; ++i) {
    const double a = 2 * M_PI * double(i) / double(n), r = i % 2 ? inner : 1.0;
    std::snprintf(line, sizeof line, "v %.17g %.17g 0\n", r * std::cos(a), r * std::sin(a));
    text += line;
  }
  text += "f";
  for (size_t i = 1; i <= n; ++i) text += " " + std::to_string(i);
  return text + "\n";
}

// Shoelace area of the outline as read (positions in file order).
double outline_area(const TriangleSoup& soup) {
  const size_t n = soup.vertex_count();
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const double* p = &soup.positions[3 * i];
    const double* q = &soup.positions[3 * ((i + 1) % n)];
    sum += p[0] * q[1] - q[0] * p[1];
  }
  return sum / 2;
}

// Checks the triangulation and returns the clipper's work for it.
io::detail::PolygonWork read_and_check(size_t n, double inner) {
  INFO(n << " corners, inner radius " << inner);
  const std::string text = polygon_obj(n, inner);
  io::detail::polygon_work() = {};
  const TriangleSoup soup = io::read_mesh_bytes("polygon.obj", std::vector<uint8_t>(text.begin(), text.end()));
  const io::detail::PolygonWork work = io::detail::polygon_work();
  REQUIRE(soup.triangle_count() == n - 2);
  double area = 0, smallest = INFINITY;
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    const double* a = &soup.positions[3 * soup.indices[3 * t]];
    const double* b = &soup.positions[3 * soup.indices[3 * t + 1]];
    const double* c = &soup.positions[3 * soup.indices[3 * t + 2]];
    const double signed_area = ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2;
    smallest = std::min(smallest, signed_area);
    area += signed_area;
  }
  CHECK(smallest > 0);  // every triangle counter-clockwise like the outline, none degenerate
  CHECK(area == Approx(outline_area(soup)).epsilon(1e-9));  // the outline covered once: no overlap, no gap
  return work;
}

}  // namespace

// The clipper's work on the outline of polygon_obj, called directly, so
// that the count is the clipper's alone (the OBJ text of 2·10^5 corners on
// one line cost tinyobjloader quadratic time under ASan; the reader's own
// parse is linear, read_and_check below).
io::detail::PolygonWork clip(size_t n, double inner) {
  TriangleSoup soup;
  std::vector<uint32_t> outline(n);
  for (size_t i = 0; i < n; ++i) {
    const double a = 2 * M_PI * double(i) / double(n), r = i % 2 ? inner : 1.0;
    soup.positions.insert(soup.positions.end(), {r * std::cos(a), r * std::sin(a), 0.0});
    outline[i] = uint32_t(i);
  }
  io::detail::polygon_work() = {};
  io::detail::add_polygon(soup, outline.data(), n);
  CHECK(soup.indices.size() == 3 * (n - 2));
  return io::detail::polygon_work();
}

TEST_CASE("large polygons are triangulated in O(n log n)", "[hardening][limits][complexity]") {
  // Each corner is tested about once, and each test examines O(log n) nodes
  // of the index and O(1) points. A quadratic clipper examines every corner
  // per ear (2·10^10 points here) or tests every corner per ear.
  for (const double inner : {1.0, 0.8}) {
    for (const size_t n : {2'000, 20'000, 200'000}) {
      const io::detail::PolygonWork work = clip(n, inner);
      INFO("inner radius " << inner << ", " << n << " corners: " << work.ear_tests << " ear tests, " << work.nodes
                           << " nodes, " << work.points << " points");
      CHECK(work.ear_tests <= 2 * n);
      CHECK(double(work.nodes) <= 4 * double(n) * std::log2(double(n)));
      CHECK(work.points <= 32 * n);  // a few leaves of up to 8 points per test
    }
  }
  // The OBJ reader clips through the same path, counted the same way.
  CHECK(read_and_check(20'000, 0.8).nodes <= 4 * 20'000 * 15);
}

TEST_CASE("small concave polygons keep n - 2 positive triangles covering their area", "[hardening][io]") {
  for (size_t n : {4, 5, 6, 7, 10, 31, 64, 81, 200})
    for (const double inner : {1.0, 0.9, 0.5, 0.1}) read_and_check(2 * n, inner);
}

TEST_CASE("a face winding many times round the same points costs linear ear tests", "[hardening][limits][complexity]") {
  // Found by the OBJ fuzzer: a face of 5,003 corners going round a square's
  // 4 points, and once through a fifth point off the square's plane that
  // projects near its centre. Ears are rare on such an outline, and the
  // clipper went a whole turn per ear: quadratic (4·10^4 corners took 8 s).
  TriangleSoup soup;
  soup.positions = {0,         -0.627972, 0.613591, 0,         0.600884, 0.613591, 0, -0.627972,
                    -0.615265, 0,         0.600884, -0.615265, 7.2,      0,        0};
  for (const size_t turns : {1'250, 10'000}) {
    const size_t n = 4 * turns + 1;
    std::vector<uint32_t> outline(n);
    for (size_t i = 0; i + 1 < n; ++i) outline[i] = std::array<uint32_t, 4>{0, 1, 3, 2}[i % 4];
    outline[n / 2] = 4;
    soup.indices.clear();
    io::detail::polygon_work() = {};
    io::detail::add_polygon(soup, outline.data(), n);
    const io::detail::PolygonWork work = io::detail::polygon_work();
    INFO(n << " corners: " << work.ear_tests << " ear tests");
    CHECK(soup.indices.size() == 3 * (n - 2));
    CHECK(work.ear_tests <= 16 * n);
    CHECK(std::all_of(soup.indices.begin(), soup.indices.end(), [](uint32_t index) { return index < 5; }));
  }
}
