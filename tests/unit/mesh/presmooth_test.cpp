#include <catch2/catch.hpp>

#include "analytic_meshes.h"
#include "crestline/mesh/presmooth.h"
#include "crestline/mesh/repair.h"

using namespace crestline;

TEST_CASE("pre-smoothing removes normal noise and keeps boundaries fixed", "[presmooth]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 40;
  Mesh mesh = repair_mesh(testing::height_field([](double, double) { return 0.0; }, 1, 1, grid)).mesh;
  Mesh noisy = mesh;
  testing::add_normal_noise(noisy, 0.2 * mean_edge_length(mesh), 3);
  const Topology topo = build_topology(noisy);
  auto roughness = [&](const std::vector<Vec3>& x) {
    double sum = 0;
    for (size_t v = 0; v < x.size(); ++v)
      if (!topo.boundary_vertex[v]) sum += x[v].z() * x[v].z();
    return sum;
  };
  PresmoothOptions options;
  options.steps = 2;
  const std::vector<Vec3> smoothed = presmooth_surface(noisy, topo, options);
  CHECK(roughness(smoothed) < 0.1 * roughness(noisy.positions));
  for (size_t v = 0; v < smoothed.size(); ++v)
    if (topo.boundary_vertex[v]) CHECK(smoothed[v] == noisy.positions[v]);
  options.steps = 0;
  CHECK(presmooth_surface(noisy, topo, options) == noisy.positions);
}
