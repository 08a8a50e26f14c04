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
  // Heavier noise, more steps (issue 13): one per 0.02 above 0.24, at most 6.
  CHECK(automatic_presmooth_steps(0.24) == kNoisySurfaceSteps);
  CHECK(automatic_presmooth_steps(0.25) == 4);
  CHECK(automatic_presmooth_steps(0.29) == 6);
  CHECK(automatic_presmooth_steps(0.5) == kVeryNoisySurfaceSteps);
}

TEST_CASE("a boundary edge far shorter than the rest neither overflows nor stops pre-smoothing", "[presmooth]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 10;
  RepairOptions keep_all;
  keep_all.weld_tolerance = 0;  // keeps the near-coincident pair below
  Mesh mesh = repair_mesh(testing::height_field([](double, double) { return 0.0; }, 1, 1, grid), keep_all).mesh;
  const Topology topo = build_topology(mesh);
  // Two neighbours on the side y = 0, away from the corners: with the mesh
  // scaled by 1e75 (t ≈ 1e148), b at the origin and a moved to 1e-161 from it
  // along the side (the shortest length whose square is not 0), t / length
  // overflows.
  uint32_t a = kNone, b = kNone;
  for (uint32_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3& p = mesh.positions[v];
    if (p.y() != 0) continue;
    if (std::abs(p.x() - 0.3) < 1e-9) b = v;
    if (std::abs(p.x() - 0.4) < 1e-9) a = v;
  }
  REQUIRE((a != kNone && b != kNone));
  const Vec3 origin = mesh.positions[b];
  for (Vec3& p : mesh.positions) p = 1e75 * (p - origin);
  mesh.positions[a] = Vec3(1e-161, 0, 0);
  PresmoothOptions options;
  options.steps = 2;
  std::vector<Vec3> smoothed;
  REQUIRE_NOTHROW(smoothed = presmooth_surface(mesh, topo, options));
  for (const Vec3& p : smoothed) CHECK(p.allFinite());
}
