#include "crestline/mesh/topology.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "analytic_meshes.h"
#include "crestline/error.h"
#include "crestline/mesh/repair.h"
#include "on_threads.h"
#include "same_topology.h"

using namespace crestline;

namespace {

Topology topology_on(int threads, const Mesh& mesh) {
  return testing::on_threads(threads, [&] { return build_topology(mesh); });
}

// A wavy n × n grid with random diagonals (vertices of 3 to 9 triangles)
// and a boundary.
Mesh wavy_grid(int n) {
  testing::GridOptions grid;
  grid.nu = grid.nv = n;
  grid.random_diagonals = true;
  return repair_mesh(
             testing::height_field([](double x, double y) { return 0.1 * std::sin(4 * x + 2 * y); }, 2, 2, grid))
      .mesh;
}

}  // namespace

TEST_CASE("topology matches a map of the edges and is the same on 1, 2 and 3 threads", "[topology][threads]") {
  // 45,000 triangles with random diagonals and a boundary: enough for the
  // counting sorts and the edge numbering to split over threads.
  const Mesh mesh = wavy_grid(150);
  const Topology one = topology_on(1, mesh);

  // Reference: edges as (smaller, larger) in ascending order, their triangles
  // in triangle order.
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  REQUIRE(one.edges.size() == edges.size());
  size_t e = 0, mismatches = 0, boundary = 0;
  for (const auto& [ends, triangles] : edges) {
    mismatches += one.edges[e] != std::array<uint32_t, 2>{ends.first, ends.second};
    mismatches += one.edge_triangles[e][0] != triangles[0];
    mismatches += one.edge_triangles[e][1] != (triangles.size() == 2 ? triangles[1] : kNone);
    boundary += triangles.size() == 1;
    ++e;
  }
  CHECK(mismatches == 0);
  CHECK(boundary == 4 * 150);
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      mismatches += one.edges[one.triangle_edges[t][k]] != std::array<uint32_t, 2>{std::min(a, b), std::max(a, b)};
    }
  CHECK(mismatches == 0);
  // Each vertex's triangles in ascending order, every corner once.
  REQUIRE(one.vertex_offsets.size() == mesh.vertex_count() + 1);
  std::vector<std::vector<uint32_t>> around(mesh.vertex_count());
  for (uint32_t t = 0; t < mesh.triangle_count(); ++t)
    for (uint32_t v : mesh.triangles[t]) around[v].push_back(t);
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v)
    mismatches += !std::equal(around[v].begin(), around[v].end(), one.vertex_triangles.begin() + one.vertex_offsets[v],
                              one.vertex_triangles.begin() + one.vertex_offsets[v + 1]) ||
                  around[v].size() != one.vertex_offsets[v + 1] - one.vertex_offsets[v];
  CHECK(mismatches == 0);

  for (int threads : {2, 3}) {
    INFO("threads: " << threads);
    testing::check_same_topology(topology_on(threads, mesh), one);
  }
}

TEST_CASE("released triangle lists come back as build_topology's; the ring distance reads none of them", "[topology]") {
  const Mesh mesh = wavy_grid(40);
  const Topology built = build_topology(mesh);
  REQUIRE(has_triangle_lists(built));
  Topology topology = built;
  release_triangle_lists(topology);
  CHECK(!has_triangle_lists(topology));
  CHECK(topology.edge_triangles.capacity() == 0);
  CHECK(topology.vertex_triangles.capacity() == 0);
  CHECK(topology.edges == built.edges);
  CHECK(topology.boundary_vertex == built.boundary_vertex);

  // Rings by breadth-first search over the triangles around each vertex.
  for (uint32_t rings : {0u, 1u, 2u, 3u, 30u}) {
    INFO("rings: " << rings);
    std::vector<uint32_t> want(mesh.vertex_count(), rings), front;
    for (uint32_t v = 0; v < mesh.vertex_count(); ++v)
      if (built.boundary_vertex[v] && rings > 0) want[v] = 0, front.push_back(v);
    for (uint32_t ring = 1; ring < rings; ++ring) {
      std::vector<uint32_t> next;
      for (uint32_t v : front)
        for (uint32_t i = built.vertex_offsets[v]; i < built.vertex_offsets[v + 1]; ++i)
          for (uint32_t w : mesh.triangles[built.vertex_triangles[i]])
            if (want[w] > ring) want[w] = ring, next.push_back(w);
      front.swap(next);
    }
    CHECK(boundary_ring_distance(mesh, topology, rings) == want);
  }
  // 41 × 41 vertices: the centre 20 rings from the border, within 30.
  const std::vector<uint32_t> far = boundary_ring_distance(mesh, topology, 30);
  CHECK(*std::max_element(far.begin(), far.end()) == 20);

  restore_triangle_lists(mesh, topology);
  CHECK(has_triangle_lists(topology));
  testing::check_same_topology(topology, built);
  restore_triangle_lists(mesh, topology);  // present: unchanged
  testing::check_same_topology(topology, built);
}

TEST_CASE("topology refuses an edge of three triangles on any thread count", "[topology][threads]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 150;
  Mesh mesh = repair_mesh(testing::height_field([](double, double) { return 0.0; }, 1, 1, grid)).mesh;
  // A fin on an interior edge late in the vertex order.
  const Triangle last = mesh.triangles[mesh.triangle_count() / 2 + 77];
  mesh.positions.push_back(Vec3(0.5, 0.5, 1));
  mesh.triangles.push_back({last[0], last[1], uint32_t(mesh.vertex_count() - 1)});
  for (int threads : {1, 2}) {
    INFO("threads: " << threads);
    CHECK_THROWS_WITH(topology_on(threads, mesh), "the mesh has an edge shared by more than two triangles.");
  }
}

TEST_CASE("topology of several components in random order is the same on 1, 2 and 3 threads", "[topology][threads]") {
  // An icosphere numbers its coarse vertices first, and half-edges are
  // grouped under their smaller end: the first vertices hold most of them,
  // so the threads split the grouping by half-edges, not by vertices. With
  // an open patch (boundary vertices) and a torus, triangles shuffled.
  Mesh mesh;
  testing::GridOptions grid;
  grid.nu = grid.nv = 60;
  grid.random_diagonals = true;
  for (const TriangleSoup& part : {testing::icosphere(5, 1), testing::torus(3, 1, grid),
                                   testing::height_field([](double x, double y) { return 0.1 * x * y; }, 1, 1, grid)}) {
    const uint32_t base = uint32_t(mesh.vertex_count());
    for (size_t v = 0; v < part.vertex_count(); ++v)
      mesh.positions.push_back(Vec3(part.positions[3 * v], part.positions[3 * v + 1], part.positions[3 * v + 2]));
    for (size_t t = 0; t < part.triangle_count(); ++t)
      mesh.triangles.push_back(
          {base + part.indices[3 * t], base + part.indices[3 * t + 1], base + part.indices[3 * t + 2]});
  }
  std::mt19937 random(9);
  std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), random);
  const Topology one = topology_on(1, mesh);
  // Boundary vertices: the patch's rim, as its edges of one triangle say.
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  std::vector<uint8_t> boundary(mesh.vertex_count(), 0);
  for (const auto& [edge, n] : uses)
    if (n == 1) boundary[edge.first] = boundary[edge.second] = 1;
  CHECK(one.boundary_vertex == boundary);
  CHECK(std::count(boundary.begin(), boundary.end(), 1) == 4 * 60);
  CHECK(one.edges.size() == uses.size());
  for (int threads : {2, 3}) {
    INFO("threads: " << threads);
    testing::check_same_topology(topology_on(threads, mesh), one);
  }
}

TEST_CASE("is_closed_outward: closed, consistently oriented surfaces facing out, anywhere in space", "[topology]") {
  const auto mesh_of = [](const TriangleSoup& soup, const Vec3& offset = Vec3::Zero()) {
    Mesh mesh;
    for (size_t v = 0; v < soup.vertex_count(); ++v)
      mesh.positions.push_back(Vec3(soup.positions[3 * v], soup.positions[3 * v + 1], soup.positions[3 * v + 2]) +
                               offset);
    for (size_t t = 0; t < soup.triangle_count(); ++t)
      mesh.triangles.push_back({soup.indices[3 * t], soup.indices[3 * t + 1], soup.indices[3 * t + 2]});
    return mesh;
  };
  const auto outward = [](const Mesh& mesh) { return is_closed_outward(mesh, build_topology(mesh)); };
  testing::GridOptions grid;
  grid.nu = grid.nv = 24;
  Mesh sphere = mesh_of(testing::icosphere(3, 1));
  CHECK(outward(sphere));
  CHECK(outward(mesh_of(testing::torus(3, 1, grid))));
  // Far from the origin and tiny: the volume is taken about a vertex.
  CHECK(outward(mesh_of(testing::icosphere(3, 1e-3), Vec3(1e6, -2e6, 3e6))));
  // Facing in.
  Mesh inward = sphere;
  for (Triangle& t : inward.triangles) std::swap(t[1], t[2]);
  CHECK_FALSE(outward(inward));
  // One triangle flipped: two of its edges run the same way as their neighbours'.
  Mesh flipped = sphere;
  std::swap(flipped.triangles[7][1], flipped.triangles[7][2]);
  CHECK_FALSE(outward(flipped));
  // A hole: one triangle missing.
  Mesh holed = sphere;
  holed.triangles.pop_back();
  CHECK_FALSE(outward(holed));
  // Open surfaces and the empty mesh.
  CHECK_FALSE(outward(mesh_of(testing::height_field([](double x, double y) { return 0.1 * x * y; }, 1, 1, grid))));
  CHECK_FALSE(outward(Mesh{}));
  // Two closed parts, both facing out.
  Mesh two = mesh_of(testing::icosphere(2, 2));
  const Mesh small = mesh_of(testing::icosphere(2, 1), Vec3(5, 0, 0));
  const uint32_t base = uint32_t(two.positions.size());
  two.positions.insert(two.positions.end(), small.positions.begin(), small.positions.end());
  for (Triangle t : small.triangles) two.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  CHECK(outward(two));
  // Any scale, any vertex numbering, any triangle order.
  CHECK(outward(mesh_of(testing::icosphere(3, 1e-8))));
  CHECK(outward(mesh_of(testing::icosphere(3, 1e8))));
  Mesh renumbered = sphere;
  const uint32_t last = uint32_t(sphere.positions.size()) - 1;
  std::reverse(renumbered.positions.begin(), renumbered.positions.end());
  for (Triangle& t : renumbered.triangles)
    for (uint32_t& v : t) v = last - v;
  CHECK(outward(renumbered));
  Mesh rotated = sphere;
  std::rotate(rotated.triangles.begin(), rotated.triangles.begin() + 7, rotated.triangles.end());
  CHECK(outward(rotated));
  // A cube facing out, with a small sphere inside it (nested parts, both out).
  Mesh cube;
  for (int v = 0; v < 8; ++v) cube.positions.push_back(Vec3(v & 1, (v >> 1) & 1, (v >> 2) & 1));
  cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  CHECK(outward(cube));
  const auto with = [](Mesh a, const Mesh& b) {
    const uint32_t base = uint32_t(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    for (Triangle t : b.triangles) a.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    return a;
  };
  CHECK(outward(with(cube, mesh_of(testing::icosphere(2, 0.2), Vec3(0.5, 0.5, 0.5)))));
  // A cube without a face (two triangles), and a cube with a stray triangle beside it.
  Mesh open_cube = cube;
  open_cube.triangles.resize(10);
  CHECK_FALSE(outward(open_cube));
  Mesh stray;
  stray.positions = {Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(5, 1, 0)};
  stray.triangles = {{0, 1, 2}};
  CHECK_FALSE(outward(with(cube, stray)));
}
