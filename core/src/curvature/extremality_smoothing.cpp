#include "crestline/curvature/extremality_smoothing.h"

#include <algorithm>
#include <cmath>

#include "crestline/error.h"
#include "crestline/mesh/cotan.h"
#include "crestline/numerics/sparse_solver.h"

namespace crestline {
namespace {

// One field: (M − t L_σ) with L_σ e(p) = Σ_q w_pq (σ_pq e(q) − e(p)).
Eigen::VectorXd smooth_field(const Topology& topology, const CotanWeights& cotan,
                             const std::vector<double>& edge_strength, const std::vector<Vec3>& directions,
                             const std::vector<double>& values, int steps) {
  const size_t nv = values.size();
  Triplets triplets;
  triplets.reserve(nv + 2 * topology.edges.size());
  std::vector<double> diagonal(cotan.vertex_mass);
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const double w = edge_strength[e];
    if (w == 0) continue;
    const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
    const double sigma = directions[p].dot(directions[q]) >= 0 ? 1.0 : -1.0;
    diagonal[p] += w;
    diagonal[q] += w;
    triplets.emplace_back(p, q, -sigma * w);
    triplets.emplace_back(q, p, -sigma * w);
  }
  for (size_t v = 0; v < nv; ++v) triplets.emplace_back(v, v, diagonal[v]);
  SparseMatrix system(nv, nv);
  system.setFromTriplets(triplets.begin(), triplets.end());
  SpdSolver solver;
  solver.compute(std::move(system));

  const Eigen::Map<const Eigen::VectorXd> mass(cotan.vertex_mass.data(), nv);
  Eigen::VectorXd e = Eigen::Map<const Eigen::VectorXd>(values.data(), nv);
  for (int step = 0; step < steps; ++step) e = solver.solve(mass.cwiseProduct(e), e);
  return e;
}

}  // namespace

Extremality smooth_extremality(const Mesh& mesh, const Topology& topology, const Curvature& curvature,
                               const Extremality& extremality, const ExtremalitySmoothingOptions& options) {
  if (options.steps <= 0 || options.time_step <= 0) return extremality;
  const size_t nv = mesh.positions.size();
  const std::vector<double>& weights = options.vertex_weights;
  if (!weights.empty() && weights.size() != nv)
    throw Error(ErrorKind::InvalidInput, "the smoothing weights have " + std::to_string(weights.size()) +
                                             " values but the mesh has " + std::to_string(nv) + " vertices.");
  for (double w : weights)
    if (!(w >= 0) || !std::isfinite(w))
      throw Error(ErrorKind::InvalidInput, "smoothing weights must be finite and not negative.");

  const CotanWeights cotan = cotan_weights(mesh.positions, mesh, topology);
  const double h = mean_edge_length(mesh);
  const double t = options.time_step * h * h;
  // An edge is smoothed as strongly as its weaker end, so a region with
  // weight 0 is frozen and exchanges nothing with its surroundings.
  std::vector<double> edge_strength(topology.edges.size());
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const double s = weights.empty() ? 1.0 : std::min(weights[topology.edges[e][0]], weights[topology.edges[e][1]]);
    edge_strength[e] = t * s * cotan.edge_weight[e];
  }

  Extremality out;
  const Eigen::VectorXd e_max =
      smooth_field(topology, cotan, edge_strength, curvature.dir_max, extremality.e_max, options.steps);
  const Eigen::VectorXd e_min =
      smooth_field(topology, cotan, edge_strength, curvature.dir_min, extremality.e_min, options.steps);
  out.e_max.assign(e_max.data(), e_max.data() + nv);
  out.e_min.assign(e_min.data(), e_min.data() + nv);
  return out;
}

}  // namespace crestline
