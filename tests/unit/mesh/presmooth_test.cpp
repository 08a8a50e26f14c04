#include "crestline/mesh/presmooth.h"

#include <catch2/catch.hpp>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"

using namespace crestline;

TEST_CASE("pre-smoothing removes normal noise, also along boundaries, without shrinking them", "[presmooth]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 40;
  Mesh mesh = repair_mesh(testing::height_field([](double, double) { return 0.0; }, 1, 1, grid)).mesh;
  Mesh noisy = mesh;
  testing::add_normal_noise(noisy, 0.2 * mean_edge_length(mesh), 3);
  const Topology topo = build_topology(noisy);
  auto roughness = [&](const std::vector<Vec3>& x, bool boundary) {
    double sum = 0;
    for (size_t v = 0; v < x.size(); ++v)
      if (bool(topo.boundary_vertex[v]) == boundary) sum += x[v].z() * x[v].z();
    return sum;
  };
  PresmoothOptions options;
  options.steps = 2;
  const std::vector<Vec3> smoothed = presmooth_surface(noisy, topo, options);
  CHECK(roughness(smoothed, false) < 0.1 * roughness(noisy.positions, false));
  // The boundary is smoothed along itself (a fixed noisy boundary pins its
  // noise into the surface next to it)...
  CHECK(roughness(smoothed, true) < 0.5 * roughness(noisy.positions, true));
  // ...and does not move inwards: on the unit square's straight sides the
  // coordinate across the side stays put (corners round off, so are skipped).
  auto on_side = [](double c) { return c < 1e-12 || c > 1 - 1e-12; };
  for (size_t v = 0; v < smoothed.size(); ++v) {
    const Vec3& p = noisy.positions[v];
    if (!topo.boundary_vertex[v] || (on_side(p.x()) && on_side(p.y()))) continue;
    const int across = on_side(p.x()) ? 0 : 1;
    CHECK(smoothed[v][across] == Approx(p[across]).margin(1e-9));
  }
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
