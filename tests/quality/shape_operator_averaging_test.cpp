#include "crestline/curvature/shape_operator_averaging.h"

#include <catch2/catch.hpp>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"

using namespace crestline;

TEST_CASE("averaging the shape operator over a ring removes the checkerboard bias on a cylinder", "[curvature]") {
  // Radius ½: κ_max = 2 along the circles, κ_min = 0 along the axis.
  testing::GridOptions grid;
  grid.nu = 64;
  grid.nv = 32;
  grid.diagonals = testing::Diagonals::Alternating;
  const Mesh mesh = repair_mesh(testing::cylinder(0.5, 2.0, grid)).mesh;
  const Topology topology = build_topology(mesh);
  const Curvature raw = compute_curvature(mesh, topology);
  const Curvature averaged = average_shape_operator(mesh, topology, raw, 1);
  const std::vector<uint32_t> rim = boundary_ring_distance(mesh, topology, 3);
  double raw_lo = 9, raw_hi = 0, lo = 9, hi = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (rim[v] < 3) continue;
    raw_lo = std::min(raw_lo, raw.kappa_max[v]), raw_hi = std::max(raw_hi, raw.kappa_max[v]);
    lo = std::min(lo, averaged.kappa_max[v]), hi = std::max(hi, averaged.kappa_max[v]);
    CHECK(std::abs(averaged.kappa_max[v] - 2) < 0.4);
    CHECK(std::abs(averaged.dir_max[v].z()) < 1e-6);  // around the cylinder
    CHECK(std::abs(averaged.kappa_min[v]) < 0.05);
  }
  // Measured: 1.5 … 3.0 raw, 1.66 … 1.92 averaged. The alternation goes; a
  // bias of the integrated estimator towards low κ on this mesh remains.
  CHECK(raw_hi - raw_lo > 1.0);
  CHECK(hi - lo < 0.3);
  CHECK(average_shape_operator(mesh, topology, raw, 0).kappa_max == raw.kappa_max);
}
