// Large polygons (issue 18, item 2): one OBJ face of 2·10^5 corners took 60 s
// with the quadratic ear clipper. The z-order-hashed clipper must cost
// O(n log n) on convex and star-shaped outlines and still cut every simple
// polygon into n - 2 triangles that cover exactly its area with its
// orientation.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <string>

#include "crestline/io/read_mesh.h"

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

// Checks the triangulation and returns the seconds it took to read.
double read_and_check(size_t n, double inner) {
  INFO(n << " corners, inner radius " << inner);
  const std::string text = polygon_obj(n, inner);
  const auto start = std::chrono::steady_clock::now();
  const TriangleSoup soup = io::read_mesh_bytes("polygon.obj", std::vector<uint8_t>(text.begin(), text.end()));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  return seconds;
}

}  // namespace

TEST_CASE("large polygons are triangulated in O(n log n)", "[hardening][limits][complexity]") {
  for (const double inner : {1.0, 0.8}) {
    // Best of two each; a quadratic clipper costs 100 times more for 10
    // times the corners, n log n about 12 times.
    double small = INFINITY, large = INFINITY;
    for (int run = 0; run < 2; ++run) {
      small = std::min(small, read_and_check(20'000, inner));
      large = std::min(large, read_and_check(200'000, inner));
    }
    INFO("inner radius " << inner << ": 2e4 corners " << small << " s, 2e5 corners " << large << " s");
    CHECK(large < 35 * small + 0.05);
  }
}

TEST_CASE("small concave polygons keep n - 2 positive triangles covering their area", "[hardening][io]") {
  for (size_t n : {4, 5, 6, 7, 10, 31, 64, 81, 200})
    for (const double inner : {1.0, 0.9, 0.5, 0.1}) read_and_check(2 * n, inner);
}
