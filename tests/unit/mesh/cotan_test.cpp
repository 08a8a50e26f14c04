// Cotan weights and lumped masses (mesh/cotan.h).
#include "crestline/mesh/cotan.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"

using namespace crestline;

TEST_CASE("cotan weights of an equilateral pair: ½ cot 60° per angle, a third of the star's area", "[mesh]") {
  Mesh mesh;
  const double h = std::sqrt(3.0) / 2;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, h, 0), Vec3(0.5, -h, 0)};
  mesh.triangles = {{0, 1, 2}, {1, 0, 3}};
  const Topology topology = build_topology(mesh);
  const CotanWeights w = cotan_weights(mesh.positions, mesh, topology);
  const double half_cot = 0.5 / std::sqrt(3.0), area = h / 2;
  REQUIRE(w.edge_weight.size() == 5);
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const bool shared = (topology.edges[e][0] | topology.edges[e][1]) == 1;  // the edge 0–1
    CHECK(w.edge_weight[e] == Approx(shared ? 2 * half_cot : half_cot).epsilon(1e-14));
  }
  CHECK(w.vertex_mass[0] == Approx(2 * area / 3).epsilon(1e-14));
  CHECK(w.vertex_mass[2] == Approx(area / 3).epsilon(1e-14));
}

TEST_CASE("cotan weights equal, bit for bit, the corner-by-corner form they replaced", "[mesh]") {
  // cotan.cpp forms each triangle's sides once and negates their dot
  // products; IEEE negation is exact, so every weight and mass must be the
  // bits of the form that subtracted the corners anew for each angle (as
  // the extremality smoothing's and pre-smoothing's outputs depend on).
  testing::GridOptions grid;
  grid.nu = 40, grid.nv = 30;
  grid.jitter = 0.3;  // uneven triangles, obtuse angles among them
  Mesh mesh = repair_mesh(testing::torus(1.0, 0.35, grid)).mesh;
  testing::add_normal_noise(mesh, 0.02, 5);
  const Topology topology = build_topology(mesh);
  const CotanWeights w = cotan_weights(mesh.positions, mesh, topology);

  std::vector<double> weight(topology.edges.size(), 0.0), mass(mesh.positions.size(), 0.0);
  const std::vector<Vec3>& x = mesh.positions;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& f = mesh.triangles[t];
    const double twice_area = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]).norm();
    for (int k = 0; k < 3; ++k) mass[f[k]] += twice_area / 6.0;
    if (!(twice_area > 0)) continue;
    for (int k = 0; k < 3; ++k) {
      const Vec3& o = x[f[(k + 2) % 3]];
      weight[topology.triangle_edges[t][k]] += 0.5 * ((x[f[k]] - o).dot(x[f[(k + 1) % 3]] - o) / twice_area);
    }
  }
  for (double& v : weight) v = std::isfinite(v) ? std::clamp(v, 0.0, 5.0) : 0.0;
  CHECK(w.vertex_mass == mass);
  CHECK(w.edge_weight == weight);
}
