// mean_edge_length (mesh/mesh.h): the length unit of every unitless
// parameter, so its bits decide the output's.
#include "crestline/mesh/mesh.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"
#include "on_threads.h"

using namespace crestline;

TEST_CASE("mean_edge_length: a grid of unit squares, and the same bits on any number of threads", "[mesh][threads]") {
  // 150 × 150 unit squares, each split by one diagonal: per triangle two
  // sides of 1 and one of √2.
  testing::GridOptions grid;
  grid.nu = grid.nv = 150;
  const Mesh squares = repair_mesh(testing::height_field([](double, double) { return 0.0; }, 150, 150, grid)).mesh;
  REQUIRE(squares.triangle_count() == 2 * 150 * 150);
  CHECK(mean_edge_length(squares) == Approx((2 + std::sqrt(2.0)) / 3).epsilon(1e-12));

  // A jittered, curved grid of 45k triangles (three blocks of the parallel
  // loop): the sum in triangle order, bit for bit, whatever the threads.
  grid.jitter = 0.3;
  grid.random_diagonals = true;
  const Mesh bumpy =
      repair_mesh(testing::height_field([](double x, double y) { return std::sin(x) * std::cos(2 * y); }, 3, 3, grid))
          .mesh;
  double serial = 0;
  for (const Triangle& t : bumpy.triangles)
    for (int k = 0; k < 3; ++k) serial += (bumpy.positions[t[(k + 1) % 3]] - bumpy.positions[t[k]]).norm();
  serial /= 3.0 * bumpy.triangle_count();
  for (int threads : {1, 2, 3}) CHECK(testing::on_threads(threads, [&] { return mean_edge_length(bumpy); }) == serial);
  CHECK(mean_edge_length(Mesh{}) == 0);
}
