// Numerics (issue 8): the lines do not depend on the model's unit or
// position, and degenerate geometry never produces NaN. Meshes without
// features draw nothing and raise no error.
#include <catch2/catch.hpp>
#include <cmath>

#include "analytic_meshes.h"
#include "run_pipeline.h"

using namespace crestline;
using crestline::testing::add_triangle;
using crestline::testing::add_vertex;

namespace {

// Two crossing waves on a 40×40 grid with jittered vertices and random
// diagonals: clear ridges and valleys, no symmetry to hide behind.
TriangleSoup waves() {
  testing::GridOptions grid;
  grid.nu = grid.nv = 40;
  grid.jitter = 0.25;
  grid.random_diagonals = true;
  grid.seed = 7;
  return testing::height_field(
      [](double x, double y) { return 0.12 * std::sin(4 * x + 1) * std::cos(3 * y) + 0.04 * std::cos(7 * y - 2 * x); },
      2, 2, grid);
}

TriangleSoup transformed(TriangleSoup s, double scale, const Vec3& shift) {
  for (size_t i = 0; i < s.positions.size(); ++i) s.positions[i] = s.positions[i] * scale + shift[i % 3];
  return s;
}

bool all_finite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

template <class Vector>
bool all_finite(const std::vector<Vector>& values) {
  for (const Vector& v : values)
    if (!v.allFinite()) return false;
  return true;
}

// Every per-vertex field and every line point of a finished pipeline.
void check_finite(const Pipeline& p) {
  const Curvature& c = p.curvature();
  CHECK(all_finite(c.kappa_max));
  CHECK(all_finite(c.kappa_min));
  CHECK(all_finite(c.dir_max));
  CHECK(all_finite(c.dir_min));
  // The pipeline keeps no normals (no stage after extremality reads them).
  CHECK(all_finite(compute_curvature(p.working_surface(), p.working_topology()).vertex_normals));
  CHECK(all_finite(p.raw_extremality().e_max));
  CHECK(all_finite(p.raw_extremality().e_min));
  CHECK(all_finite(p.extremality().e_max));
  CHECK(all_finite(p.extremality().e_min));
  for (const Polyline& line : p.all_lines()) {
    CHECK(all_finite(line.points));
    CHECK(all_finite(line.curvature));
    CHECK(std::isfinite(line.strength));
    CHECK(std::isfinite(line.length));
  }
}

}  // namespace

TEST_CASE("the same mesh at 1e-8, 1 and 1e8, and moved by 1e6, gives the same lines", "[hardening][scale]") {
  const Pipeline reference = testing::run_pipeline(waves());
  const std::vector<Polyline> expected = reference.lines();
  REQUIRE(expected.size() > 2);
  struct Case {
    double scale;
    Vec3 shift;
  };
  const Case cases[] = {{1e-8, Vec3::Zero()},
                        {1e8, Vec3::Zero()},
                        {1, Vec3(1e6, 1e6, 1e6)},
                        {1e-8, Vec3(1e-2, 0, 0)},
                        {1e8, Vec3(0, -1e14, 1e14)}};
  for (const Case& c : cases) {
    INFO("scale " << c.scale << ", shift " << c.shift.transpose());
    const Pipeline p = testing::run_pipeline(transformed(waves(), c.scale, c.shift));
    check_finite(p);
    const std::vector<Polyline> lines = p.lines();
    REQUIRE(lines.size() == expected.size());
    // A shift of 1e6 model sizes leaves ~1e-10 of relative precision in the
    // input coordinates; the lines may move by far less than an edge (0.05).
    const double tolerance = c.shift.norm() / c.scale > 1e3 ? 1e-4 : 1e-7;
    double worst = 0;
    for (size_t i = 0; i < lines.size(); ++i) {
      CHECK(lines[i].type == expected[i].type);
      REQUIRE(lines[i].points.size() == expected[i].points.size());
      CHECK(lines[i].strength == Approx(expected[i].strength).epsilon(1e-4));
      for (size_t k = 0; k < lines[i].points.size(); ++k)
        worst = std::max(worst, ((lines[i].points[k] - c.shift) / c.scale - expected[i].points[k]).norm());
    }
    CHECK(worst < tolerance);
  }
}

TEST_CASE("slivers, zero-area triangles and duplicated vertices give no NaN", "[hardening][degenerate]") {
  SECTION("heavily jittered grid: needles and caps everywhere") {
    testing::GridOptions grid;
    grid.nu = grid.nv = 24;
    grid.jitter = 0.499;  // vertices almost reach their neighbours
    grid.random_diagonals = true;
    check_finite(testing::run_pipeline(
        testing::height_field([](double x, double y) { return 0.2 * std::sin(5 * x) * std::sin(4 * y); }, 1, 1, grid)));
  }
  SECTION("zero-area triangles, exact and near-duplicate vertices") {
    TriangleSoup s = waves();
    const uint32_t n = static_cast<uint32_t>(s.vertex_count());
    for (uint32_t v = 0; v + 2 < n; v += 37) {
      const Vec3 p(s.positions[3 * v], s.positions[3 * v + 1], s.positions[3 * v + 2]);
      add_vertex(s, p);                                            // an exact duplicate, welded
      add_vertex(s, p + Vec3(1e-12, 0, 1e-12));                    // below the weld tolerance
      add_triangle(s, v, n + (v / 37) * 2, n + (v / 37) * 2 + 1);  // zero area
      add_triangle(s, v, v + 1, v + 1);                            // repeated corner
    }
    // Collinear triangles along the first row of the grid.
    add_triangle(s, 0, 1, 2);
    add_triangle(s, 1, 2, 3);
    const RepairResult repaired = repair_mesh(s);
    CHECK(repaired.report.welded_vertices > 0);
    CHECK(repaired.report.degenerate_triangles > 0);
    check_finite(testing::run_pipeline(s));
  }
  SECTION("a polygon soup: every triangle with its own vertices") {
    const TriangleSoup grid = waves();
    TriangleSoup s;
    for (size_t t = 0; t < grid.triangle_count(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = grid.indices[3 * t + k];
        add_vertex(s, Vec3(grid.positions[3 * v], grid.positions[3 * v + 1], grid.positions[3 * v + 2]));
      }
      add_triangle(s, uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2));
    }
    const Pipeline p = testing::run_pipeline(s);
    CHECK(p.input_mesh().vertex_count() == grid.vertex_count());
    check_finite(p);
  }
  SECTION("needle triangles of aspect ratio above 10,000 in a fan") {
    TriangleSoup s;
    add_vertex(s, Vec3(0, 0, 0));
    const int n = 64;
    for (int i = 0; i <= n; ++i) {
      const double a = 1e-3 * i / n;  // the whole fan spans a thousandth of a radian
      add_vertex(s, Vec3(std::cos(a), std::sin(a), 0.01 * (i % 2)));
    }
    for (uint32_t i = 1; i <= uint32_t(n); ++i) add_triangle(s, 0, i, i + 1);
    check_finite(testing::run_pipeline(s));
  }
}

TEST_CASE("a flat plane and a perfect sphere give no lines and no error", "[hardening][featureless]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 30;
  grid.jitter = 0.3;
  grid.random_diagonals = true;
  const Pipeline plane = testing::run_pipeline(testing::height_field([](double, double) { return 0.0; }, 1, 1, grid));
  check_finite(plane);
  CHECK(plane.lines().empty());

  const Pipeline sphere = testing::run_pipeline(testing::icosphere(4));
  check_finite(sphere);
  CHECK(sphere.lines().empty());

  const Pipeline tilted = testing::run_pipeline(
      transformed(testing::height_field([](double x, double y) { return 0.3 * x - 0.7 * y; }, 1, 1, grid), 1e5,
                  Vec3(3e6, -1e6, 2e6)));
  check_finite(tilted);
  CHECK(tilted.lines().empty());
}
