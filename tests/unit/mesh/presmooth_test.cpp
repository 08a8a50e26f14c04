#include "crestline/mesh/presmooth.h"

#include <catch2/catch.hpp>

#include "analytic_meshes.h"
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

TEST_CASE("noise level measures normal noise in edge lengths, not curvature", "[presmooth]") {
  for (int level : {3, 4}) {
    Mesh sphere = repair_mesh(testing::icosphere(level)).mesh;
    const double h = mean_edge_length(sphere);
    CHECK(surface_noise_level(sphere, build_topology(sphere)) < 0.01);
    for (double sigma : {0.1, 0.25}) {
      Mesh noisy = sphere;
      testing::add_normal_noise(noisy, sigma * h, 5);
      const double level_measured = surface_noise_level(noisy, build_topology(noisy));
      INFO("level " << level << " sigma " << sigma << " measured " << level_measured);
      CHECK(level_measured > 0.7 * sigma);
      CHECK(level_measured < 1.1 * sigma);
      CHECK(automatic_presmooth_steps(level_measured) == kNoisySurfaceSteps);
    }
  }
  CHECK(automatic_presmooth_steps(0.01) == 0);
}
