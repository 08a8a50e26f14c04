#include "crestline/mesh/presmooth.h"

#include "crestline/mesh/cotan.h"
#include "crestline/numerics/sparse_solver.h"

namespace crestline {

std::vector<Vec3> presmooth_surface(const Mesh& mesh, const Topology& topology, const PresmoothOptions& options) {
  std::vector<Vec3> x = mesh.positions;
  if (options.steps <= 0 || options.time_step <= 0) return x;
  const size_t nv = x.size();
  const double h = mean_edge_length(mesh);
  const double t = options.time_step * h * h;
  const std::vector<uint8_t>& fixed = topology.boundary_vertex;

  for (int step = 0; step < options.steps; ++step) {
    // Weights from the current surface: mean-curvature flow, linearised per step.
    const CotanWeights cotan = cotan_weights(x, mesh, topology);
    // (M + tL) x' = M x on free vertices; fixed (boundary) ones move to the right side.
    std::vector<double> diagonal(cotan.vertex_mass);
    Eigen::MatrixXd rhs(nv, 3);
    for (size_t v = 0; v < nv; ++v) rhs.row(v) = cotan.vertex_mass[v] * x[v].transpose();
    Triplets triplets;
    triplets.reserve(nv + 2 * topology.edges.size());
    for (size_t e = 0; e < topology.edges.size(); ++e) {
      const double w = t * cotan.edge_weight[e];
      if (w == 0) continue;
      const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
      if (fixed[p] && fixed[q]) continue;
      diagonal[p] += w;
      diagonal[q] += w;
      if (fixed[q]) rhs.row(p) += w * x[q].transpose();
      else if (fixed[p]) rhs.row(q) += w * x[p].transpose();
      else {
        triplets.emplace_back(p, q, -w);
        triplets.emplace_back(q, p, -w);
      }
    }
    for (size_t v = 0; v < nv; ++v) {
      if (fixed[v]) {
        triplets.emplace_back(v, v, 1.0);
        rhs.row(v) = x[v].transpose();
      } else {
        triplets.emplace_back(v, v, diagonal[v]);
      }
    }
    SparseMatrix system(nv, nv);
    system.setFromTriplets(triplets.begin(), triplets.end());
    SpdSolver solver;
    solver.compute(std::move(system));
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::VectorXd guess(nv);
      for (size_t v = 0; v < nv; ++v) guess[v] = x[v][axis];
      const Eigen::VectorXd solved = solver.solve(rhs.col(axis), guess);
      for (size_t v = 0; v < nv; ++v) x[v][axis] = solved[v];
    }
  }
  return x;
}

}  // namespace crestline
