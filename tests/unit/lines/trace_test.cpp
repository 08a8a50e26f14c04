#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "analytic_meshes.h"
#include "crestline/numerics/parallel.h"
#include "run_pipeline.h"

using namespace crestline;

namespace {

// z = A cos(2πx/L) on [0,2L]²: ridges (crests) at x = kL, valleys at x = (k+½)L.
TriangleSoup sine_field(int n, double jitter, bool random_diagonals, unsigned seed = 1) {
  testing::GridOptions grid;
  grid.nu = grid.nv = n;
  grid.jitter = jitter;
  grid.random_diagonals = random_diagonals;
  grid.seed = seed;
  return testing::height_field([](double x, double) { return 0.08 * std::cos(2 * testing::kPi * x); }, 2, 2, grid);
}

// Distance in x from the nearest line of the family x = offset + k.
double off_by(double x, double offset) { return std::abs(x - offset - std::round(x - offset)); }

void check_sine_lines(const Pipeline& p) {
  const double h = p.stats().mean_edge_length;
  double ridge_length = 0, valley_length = 0;
  for (const Polyline& line : p.lines()) {
    const double offset = line.type == LineType::Ridge ? 0.0 : 0.5;
    for (const Vec3& q : line.points) {
      INFO(line_type_name(line.type) << " point x=" << q.x() << " edge " << h);
      CHECK(off_by(q.x(), offset) < 0.3 * h);
    }
    (line.type == LineType::Ridge ? ridge_length : valley_length) += line.length;
  }
  // One interior ridge (x = 1) and two valleys (x = ½, 3/2), each spanning
  // the height of the patch less the boundary band.
  CHECK(ridge_length > 2 - 12 * h);
  CHECK(ridge_length < 2.05);
  CHECK(valley_length > 2 * (2 - 12 * h));
  CHECK(valley_length < 2 * 2.05);
  CHECK(p.stats().ridges == 1);
  CHECK(p.stats().valleys == 2);
}

}  // namespace

TEST_CASE("sine height field: ridges at crests, valleys at troughs (regular grid)", "[trace]") {
  check_sine_lines(testing::run_pipeline(sine_field(60, 0.0, false)));
}

TEST_CASE("sine height field: lines stay put on an irregular mesh", "[trace]") {
  check_sine_lines(testing::run_pipeline(sine_field(60, 0.25, true, 5)));
}

TEST_CASE("no artefact lines along the boundary of an open mesh", "[trace]") {
  // κ is constant on a cylinder: no lines at all, in particular none along
  // its two rims.
  testing::GridOptions grid;
  grid.nu = 64;
  grid.nv = 32;
  const Pipeline p = testing::run_pipeline(testing::cylinder(0.5, 2.0, grid));
  CHECK(p.lines().empty());
}

TEST_CASE("a sphere and a plane have no feature lines", "[trace]") {
  CHECK(testing::run_pipeline(testing::icosphere(4)).lines().empty());
  testing::GridOptions grid;
  grid.nu = grid.nv = 30;
  grid.jitter = 0.2;
  CHECK(testing::run_pipeline(testing::height_field([](double, double) { return 0.0; }, 1, 1, grid)).lines().empty());
}

TEST_CASE("traced nodes: numbered along the segments, placed on every thread, the same on 1, 2 and 3 threads",
          "[trace][threads]") {
  // An egg-crate field of 180k triangles: tens of thousands of crossing
  // nodes, so their placement splits over the threads.
  testing::GridOptions grid;
  grid.nu = grid.nv = 300;
  grid.jitter = 0.2;
  grid.random_diagonals = true;
  const Mesh mesh =
      repair_mesh(testing::height_field(
                      [](double x, double y) {
                        return 0.02 * std::cos(2 * testing::kPi * 6 * x) * std::cos(2 * testing::kPi * 5 * y);
                      },
                      2, 2, grid))
          .mesh;
  const int before = max_threads();
  std::vector<TraceResult> traced;
  for (int threads : {1, 2, 3}) {
    set_max_threads(threads);
    Pipeline p(mesh);
    p.run();
    traced.push_back(p.segments().lines);
    if (threads > 1) continue;
    const Mesh& surface = p.working_surface();
    const Topology& topology = p.working_topology();
    for (const FeatureGraph* g : {&traced[0].ridges, &traced[0].valleys}) {
      INFO(line_type_name(g->type));
      REQUIRE(g->points.size() > 4 * 2048);
      // Edge crossings first, numbered in the order the segments reach them.
      uint32_t next = 0;
      for (const auto& s : g->segments)
        for (uint32_t n : s)
          if (!g->trisector[n] && n >= next) REQUIRE(n == next++);
      for (uint32_t n = 0; n < next; ++n) {
        const auto& e = topology.edges[g->source[n]];
        const double t = g->edge_parameter[n];
        REQUIRE(g->points[n] == (1 - t) * surface.positions[e[0]] + t * surface.positions[e[1]]);
      }
    }
  }
  set_max_threads(before);
  for (int i = 1; i < 3; ++i)
    for (auto graph : {&TraceResult::ridges, &TraceResult::valleys}) {
      const FeatureGraph &a = traced[0].*graph, &b = traced[i].*graph;
      CHECK(a.points == b.points);
      CHECK(a.curvature == b.curvature);
      CHECK(a.source == b.source);
      CHECK(a.edge_parameter == b.edge_parameter);
      CHECK(a.trisector == b.trisector);
      CHECK(a.segments == b.segments);
    }
}

TEST_CASE("tracer: a vertex's e of +0 or -0 counts as a tiny positive value, whatever its direction's sign",
          "[trace]") {
  // A flat 8×8 grid on [0, 1]², the principal direction ±x (flipped at
  // every other vertex, so that the triangles' consistent signs take both
  // values) and e = ±(½ − x) with the direction's sign: a ridge at x = ½ (e
  // falls along the direction), through the vertex column there, whose e is
  // exactly +0 or −0.
  testing::GridOptions grid;
  grid.nu = grid.nv = 8;
  grid.random_diagonals = true;
  const Mesh mesh = repair_mesh(testing::height_field([](double, double) { return 0.0; }, 1, 1, grid)).mesh;
  const Topology topology = build_topology(mesh);
  const size_t nv = mesh.positions.size();
  auto sign = [](size_t v) { return v % 2 ? -1.0 : 1.0; };
  Curvature curvature;
  curvature.vertex_normals.assign(nv, Vec3::UnitZ());
  curvature.kappa_max.assign(nv, 1.0), curvature.kappa_min.assign(nv, 0.0);
  curvature.dir_min.assign(nv, Direction::UnitY()), curvature.star_area.assign(nv, 1.0);
  for (size_t v = 0; v < nv; ++v) curvature.dir_max.push_back(float(sign(v)) * Direction::UnitX());
  const Regularity regularity = classify_triangles(mesh, curvature);
  TraceOptions options;
  options.boundary_rings = 0;
  auto trace = [&](const std::function<double(size_t v)>& e) {
    Extremality extremality;
    extremality.e_min.assign(nv, 1.0);  // no valleys
    for (size_t v = 0; v < nv; ++v) extremality.e_max.push_back(e(v));
    return trace_regular_triangles(mesh, topology, curvature, extremality, regularity, options).ridges;
  };
  auto on_line = [&](size_t v) { return mesh.positions[v].x() == 0.5; };
  size_t zeros = 0, negative_zeros = 0;
  auto signed_zeros = [&](size_t v) { return sign(v) * (0.5 - mesh.positions[v].x()); };
  for (size_t v = 0; v < nv; ++v)
    if (on_line(v)) ++zeros, negative_zeros += std::signbit(signed_zeros(v));
  REQUIRE(zeros == 9);
  REQUIRE(negative_zeros > 0);
  REQUIRE(negative_zeros < zeros);
  const FeatureGraph with_zeros = trace(signed_zeros);
  const FeatureGraph with_tiny =
      trace([&](size_t v) { return on_line(v) ? std::numeric_limits<double>::denorm_min() : signed_zeros(v); });
  CHECK(with_zeros.segments.size() >= 8);
  CHECK(with_zeros.segments == with_tiny.segments);
  CHECK(with_zeros.source == with_tiny.source);
  CHECK(with_zeros.edge_parameter == with_tiny.edge_parameter);
  CHECK(with_zeros.points == with_tiny.points);
}
