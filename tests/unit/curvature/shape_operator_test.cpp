#include "crestline/curvature/shape_operator.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "../../../core/src/curvature/vertex_scatter.h"
#include "analytic_meshes.h"
#include "crestline/curvature/extremality.h"
#include "crestline/curvature/regularity.h"
#include "crestline/mesh/cotan.h"
#include "crestline/mesh/repair.h"
#include "crestline/numerics/parallel.h"

using namespace crestline;

namespace {

struct Computed {
  Mesh mesh;
  Topology topology;
  Curvature curvature;
};

// The reference regularity_code is checked against: Definition 1 with
// branches, as core wrote it before 5dcdc28. The signs s_k with s_0 = +1 that
// make the three directions mutually positive, or false if the triangle is
// singular; and the code they give.
bool consistent_signs(const Vec3& d0, const Vec3& d1, const Vec3& d2, std::array<double, 3>& signs) {
  const double a = d0.dot(d1), b = d0.dot(d2);
  signs = {1.0, a >= 0 ? 1.0 : -1.0, b >= 0 ? 1.0 : -1.0};
  // Orienting d1 and d2 towards d0 is the only candidate (up to a global
  // flip); the triangle is regular when it makes them agree with each other.
  return a != 0 && b != 0 && signs[1] * signs[2] * d1.dot(d2) > 0;
}
uint8_t reference_code(bool regular, const std::array<double, 3>& signs) {
  return regular ? static_cast<uint8_t>(1u | (signs[1] < 0 ? 2u : 0u) | (signs[2] < 0 ? 4u : 0u)) : 0;
}

Computed compute(const TriangleSoup& soup) {
  Computed c;
  c.mesh = repair_mesh(soup).mesh;
  c.topology = build_topology(c.mesh);
  c.curvature = compute_curvature(c.mesh, c.topology);
  return c;
}

// Mean relative error of both principal curvatures against exact values.
template <class Exact>
double mean_error(const Computed& c, Exact exact, bool skip_boundary = true) {
  double sum = 0;
  size_t n = 0;
  for (size_t v = 0; v < c.mesh.vertex_count(); ++v) {
    if (skip_boundary && c.topology.boundary_vertex[v]) continue;
    const auto [k_max, k_min, scale] = exact(c.mesh.positions[v]);
    sum += (std::abs(c.curvature.kappa_max[v] - k_max) + std::abs(c.curvature.kappa_min[v] - k_min)) / scale;
    ++n;
  }
  return sum / n;
}

}  // namespace

TEST_CASE("sphere curvatures converge to 1/r, positive (convex)", "[curvature]") {
  const double r = 2.0;
  double previous = 1e9;
  for (int level = 2; level <= 5; ++level) {
    const Computed c = compute(testing::icosphere(level, r));
    const double err = mean_error(c, [&](const Vec3&) { return std::make_tuple(1 / r, 1 / r, 1 / r); });
    INFO("level " << level << " mean relative error " << err);
    CHECK(err < previous);
    previous = err;
  }
  CHECK(previous < 0.01);
}

TEST_CASE("cylinder: kappa_max = 1/r across the axis, kappa_min = 0 along it", "[curvature]") {
  const double r = 0.5;
  double previous = 1e9;
  for (int n : {24, 48, 96}) {
    testing::GridOptions grid;
    grid.nu = n;
    grid.nv = n / 2;
    const Computed c = compute(testing::cylinder(r, 2.0, grid));
    const double err = mean_error(c, [&](const Vec3&) { return std::make_tuple(1 / r, 0.0, 1 / r); });
    INFO("n " << n << " error " << err);
    CHECK((err < previous || err < 1e-12));  // exact on this triangulation
    previous = err;
    for (size_t v = 0; v < c.mesh.vertex_count(); ++v) {
      if (c.topology.boundary_vertex[v]) continue;
      CHECK(std::abs(c.curvature.dir_max[v].z()) < 0.05);
      CHECK(std::abs(c.curvature.dir_min[v].z()) > 0.99);
    }
  }
  CHECK(previous < 0.02);
}

TEST_CASE("torus curvatures converge, with the negative curvature inside", "[curvature]") {
  const double R = 3, r = 1;
  auto exact = [&](const Vec3& p) {
    const double rho = std::hypot(p.x(), p.y());
    const double cos_b = (rho - R) / r;
    const double ring = cos_b / (R + r * cos_b), tube = 1 / r;
    return std::make_tuple(std::max(ring, tube), std::min(ring, tube), 1 / r);
  };
  double previous = 1e9;
  for (int n : {32, 64, 128}) {
    testing::GridOptions grid;
    grid.nu = 2 * n;
    grid.nv = n;
    const Computed c = compute(testing::torus(R, r, grid));
    const double err = mean_error(c, exact);
    INFO("n " << n << " error " << err);
    CHECK(err < previous);
    previous = err;
  }
  CHECK(previous < 0.02);
}

TEST_CASE("on a checkerboard triangulation curvature is right on average", "[curvature]") {
  // Valence 4 and 8 vertices alternate: the one-ring estimate of §3 is
  // biased per vertex there (it converges as a measure, not pointwise), but
  // the area-weighted mean over the surface is the true curvature.
  const double r = 0.5;
  testing::GridOptions grid;
  grid.nu = 96;
  grid.nv = 48;
  grid.diagonals = testing::Diagonals::Alternating;
  const Computed c = compute(testing::cylinder(r, 2.0, grid));
  double weighted = 0, area = 0;
  for (size_t v = 0; v < c.mesh.vertex_count(); ++v) {
    if (c.topology.boundary_vertex[v]) continue;
    weighted += c.curvature.star_area[v] * c.curvature.kappa_max[v];
    area += c.curvature.star_area[v];
  }
  CHECK(weighted / area == Approx(1 / r).epsilon(0.01));
}

TEST_CASE("integrated shape operator scales: pointwise curvature is 1/length", "[curvature]") {
  const Computed unit = compute(testing::icosphere(3, 1.0));
  const Computed big = compute(testing::icosphere(3, 1000.0));
  for (size_t v = 0; v < unit.mesh.vertex_count(); v += 17) {
    CHECK(big.curvature.kappa_max[v] * 1000 == Approx(unit.curvature.kappa_max[v]).epsilon(1e-9));
    CHECK(big.curvature.kappa_min[v] * 1000 == Approx(unit.curvature.kappa_min[v]).epsilon(1e-9));
  }
}

TEST_CASE("extremality vanishes where curvature is constant along its lines", "[curvature][extremality]") {
  // On a torus the tube curvature 1/r (= κ_max) is constant, and the ring
  // curvature cos b/(R + r cos b) (= κ_min) changes only across its own
  // direction: both extremalities vanish identically.
  testing::GridOptions grid;
  grid.nu = 128;
  grid.nv = 64;
  const Computed c = compute(testing::torus(3, 1, grid));
  const Extremality e = compute_extremality(c.mesh, c.curvature);
  double max_abs = 0, min_abs = 0;
  for (double v : e.e_max) max_abs = std::max(max_abs, std::abs(v));
  for (double v : e.e_min) min_abs = std::max(min_abs, std::abs(v));
  CHECK(max_abs < 0.05);
  CHECK(min_abs < 0.05);
}

TEST_CASE("regularity codes follow Definition 1", "[regularity]") {
  // d1 flipped against d0 and d2: regular, s_1 = −1, s_2 = +1.
  const uint8_t code = regularity_code(Vec3(1, 0, 0), Vec3(-1, 0.1, 0), Vec3(1, -0.1, 0));
  CHECK(code == (1u | 2u));
  const std::array<double, 3> s = code_signs(code);
  CHECK(s[0] == 1);
  CHECK(s[1] == -1);
  CHECK(s[2] == 1);
  // Three directions 60° apart as line fields (a trisector): no consistent choice.
  const double c = std::cos(testing::kPi / 3), d = std::sin(testing::kPi / 3);
  CHECK(regularity_code(Vec3(1, 0, 0), Vec3(c, d, 0), Vec3(-c, d, 0)) == 0);
}

TEST_CASE("regularity_code from three directions is the reference's code", "[regularity]") {
  // Coordinates from a few values, zeros of both signs and a NaN among them,
  // so that the dot products take every sign, ±0 and NaN.
  const double values[] = {1.0, -1.0, 0.5, -0.25, 0.0, -0.0, std::nan("")};
  std::mt19937 random(3);
  std::uniform_int_distribution<int> pick(0, 6), pick_finite(0, 5);
  size_t regular = 0, singular = 0, nan_seen = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3 d[3];
    for (Vec3& v : d)
      for (int k = 0; k < 3; ++k) v[k] = values[i % 10 == 0 ? pick(random) : pick_finite(random)];
    std::array<double, 3> s;
    const uint8_t expected = reference_code(consistent_signs(d[0], d[1], d[2], s), s);
    REQUIRE(regularity_code(d[0], d[1], d[2]) == expected);
    (expected ? regular : singular) += 1;
    nan_seen += std::isnan(d[0].dot(d[1]) + d[0].dot(d[2]) + d[1].dot(d[2]));
  }
  CHECK(regular > 1000);
  CHECK(singular > 1000);
  CHECK(nan_seen > 100);
}

TEST_CASE("classify_triangles keeps each regular triangle's signs for the tracer", "[regularity]") {
  // A noisy sphere: regular and singular triangles of both fields, both signs.
  Mesh mesh = repair_mesh(testing::icosphere(4)).mesh;
  testing::add_normal_noise(mesh, 0.01, 5);
  const Curvature curvature = compute_curvature(mesh, build_topology(mesh));
  const Regularity reg = classify_triangles(mesh, curvature);
  size_t singular[2] = {0, 0}, negative[2][3] = {{0, 0, 0}, {0, 0, 0}};
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& f = mesh.triangles[t];
    for (int field = 0; field < 2; ++field) {
      const std::vector<Direction>& dir = field == 0 ? curvature.dir_max : curvature.dir_min;
      const uint8_t code = (field == 0 ? reg.regular_max : reg.regular_min)[t];
      std::array<double, 3> s;
      const bool regular = consistent_signs(widen(dir[f[0]]), widen(dir[f[1]]), widen(dir[f[2]]), s);
      REQUIRE((code != 0) == regular);
      if (!regular) {
        ++singular[field];
        continue;
      }
      REQUIRE(code_signs(code) == s);
      for (int k = 0; k < 3; ++k) negative[field][k] += s[k] < 0;
    }
  }
  CHECK(singular[0] == reg.singular_max);
  CHECK(singular[1] == reg.singular_min);
  for (int field = 0; field < 2; ++field) {
    CHECK(singular[field] > 0);
    CHECK(negative[field][0] == 0);  // s_0 = +1 always
    CHECK(negative[field][1] > 0);
    CHECK(negative[field][2] > 0);
  }
}

TEST_CASE("a sphere-free smooth surface has few singular triangles", "[regularity]") {
  testing::GridOptions grid;
  grid.nu = 128;
  grid.nv = 64;
  const Computed c = compute(testing::torus(3, 1, grid));
  const Regularity reg = classify_triangles(c.mesh, c.curvature);
  CHECK(reg.singular_max == 0);
  CHECK(reg.singular_min == 0);
}

TEST_CASE(
    "curvature and extremality: the terms added on every thread, in edge or triangle order, the same bits on 1, 2 and "
    "3 threads",
    "[curvature][extremality][threads]") {
  // A noisy sphere of 123k edges and 82k triangles: blocks of 16,384 edges
  // and 65,536 triangles, each vertex's sum split over the threads by vertex.
  Mesh mesh = testing::repaired_in_input_order(testing::icosphere(6));
  testing::add_normal_noise(mesh, 0.002, 11);
  const Topology topology = build_topology(mesh);
  const int before = max_threads();
  std::vector<Curvature> results;
  std::vector<Extremality> extremality;
  for (int threads : {1, 2, 3}) {
    set_max_threads(threads);
    results.push_back(compute_curvature(mesh, topology));
    extremality.push_back(compute_extremality(mesh, results.back()));
  }
  set_max_threads(before);
  double sum_max = 0, sum_min = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    sum_max += results[0].kappa_max[v], sum_min += results[0].kappa_min[v];
  // As the serial scatters over the edges and triangles computed them before this change (printed with %a).
  CHECK(sum_max == 0x1.6499d015208e4p+18);
  CHECK(sum_min == -0x1.16f9d460664f2p+18);
  CHECK(results[0].kappa_max[1000] == -0x1.18564c66a18b3p+1);
  CHECK(results[0].dir_min[2000][1] == -0x1.5997e4p-1f);  // the double -0x1.5997e3e65a139p-1 rounded
  // The extremalities read the directions rounded to float (before: 0x1.ef1a7ca148bb8p+6, 0x1.e80c6727d0f2cp+7).
  CHECK(extremality[0].e_max[1000] == 0x1.ef1a7d0e7482p+6);
  CHECK(extremality[0].e_min[3000] == 0x1.e80c669708324p+7);
  for (int i = 1; i < 3; ++i) {
    CHECK(results[i].kappa_max == results[0].kappa_max);
    CHECK(results[i].kappa_min == results[0].kappa_min);
    CHECK(results[i].dir_max == results[0].dir_max);
    CHECK(results[i].dir_min == results[0].dir_min);
    CHECK(extremality[i].e_max == extremality[0].e_max);
    CHECK(extremality[i].e_min == extremality[0].e_min);
  }
}

TEST_CASE(
    "curvature: vertex normals and star areas summed in triangle order, the bits of a gather over each vertex's "
    "triangles, on 1, 2 and 3 threads",
    "[curvature][threads]") {
  // 328k triangles: five blocks of 65,536, each vertex's sums split over
  // the threads by vertex; and a triangle of zero area, whose normal is zero.
  Mesh mesh = repair_mesh(testing::icosphere(7)).mesh;
  testing::add_normal_noise(mesh, 0.002, 3);
  const Triangle& flat = mesh.triangles[1000];
  mesh.positions[flat[2]] = mesh.positions[flat[0]];
  const Topology topology = build_topology(mesh);
  // The definition: each vertex's triangles in ascending order, Σ area · unit
  // normal normalized, and Σ area, from triangle_areas_normals.
  std::vector<double> areas;
  std::vector<Vec3> normals;
  triangle_areas_normals(mesh.positions, mesh.triangles, areas, normals);
  std::vector<Vec3> vertex_normals(mesh.positions.size());
  std::vector<double> star_area(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    Vec3 n = Vec3::Zero();
    double star = 0;
    for (uint32_t i = topology.vertex_offsets[v]; i < topology.vertex_offsets[v + 1]; ++i) {
      const uint32_t t = topology.vertex_triangles[i];
      n += areas[t] * normals[t];
      star += areas[t];
    }
    vertex_normals[v] = n.norm() > 0 ? Vec3(n / n.norm()) : Vec3::UnitZ();
    star_area[v] = star;
  }
  REQUIRE(areas[1000] == 0);
  const int before = max_threads();
  for (int threads : {1, 2, 3}) {
    set_max_threads(threads);
    const Curvature curvature = compute_curvature(mesh, topology);
    CHECK(curvature.vertex_normals == vertex_normals);
    CHECK(curvature.star_area == star_area);
  }
  set_max_threads(before);
}

TEST_CASE("the scatters' vertex parts are in_vertex_part's, without its division", "[curvature][threads]") {
  // Every run of 64 vertices for 1 to 8 parts, strided (all 2^26 runs take
  // seconds in a debug build), the first and last runs, and each run's ends.
  for (size_t parts = 1; parts <= 8; ++parts) {
    const detail::VertexParts of(parts);
    size_t wrong = 0;
    for (uint64_t run = 0; run < (uint64_t{1} << 26); run += run < 4096 || run > (uint64_t{1} << 26) - 4096 ? 1 : 997)
      for (const uint32_t v : {uint32_t(run << 6), uint32_t(run << 6 | 63)}) {
        const size_t part = of.of(v);
        wrong += part >= parts || !detail::in_vertex_part(v, part, parts);
      }
    CHECK(wrong == 0);
  }
  CHECK(detail::VertexParts(7).of(0xffffffffu) == (0xffffffffu >> 6) % 7);
}
