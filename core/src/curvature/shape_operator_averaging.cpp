#include "crestline/curvature/shape_operator_averaging.h"

#include "crestline/numerics/symmetric_eigen3.h"

namespace crestline {

Curvature average_shape_operator(const Mesh& mesh, const Topology& topology, const Curvature& curvature, int rings) {
  Curvature out = curvature;
  const size_t nv = mesh.positions.size();
  if (rings <= 0 || nv == 0) return out;
  // Integrated tensors S(p) (units of length) and lumped areas area(star)/3.
  std::vector<Eigen::Matrix3d> shape(nv);
  std::vector<double> area(nv);
  for (size_t v = 0; v < nv; ++v) {
    area[v] = curvature.star_area[v] / 3;
    const Vec3 a = widen(curvature.dir_max[v]), b = widen(curvature.dir_min[v]);
    shape[v] = area[v] * (curvature.kappa_max[v] * a * a.transpose() + curvature.kappa_min[v] * b * b.transpose());
  }
  // Each pass adds every neighbour's sum to a vertex's own: k passes reach k rings.
  for (int r = 0; r < rings; ++r) {
    std::vector<Eigen::Matrix3d> next = shape;
    std::vector<double> next_area = area;
    for (const auto& e : topology.edges) {
      next[e[0]] += shape[e[1]], next[e[1]] += shape[e[0]];
      next_area[e[0]] += area[e[1]], next_area[e[1]] += area[e[0]];
    }
    shape.swap(next);
    area.swap(next_area);
  }
  // As in compute_curvature: drop the eigenvector closest to the normal.
  for (size_t v = 0; v < nv; ++v) {
    if (!(area[v] > 0)) continue;
    const Vec3& n = curvature.vertex_normals[v];
    const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - n * n.transpose();
    const SymmetricEigen3 eigen = symmetric_eigen3(tangent * shape[v] * tangent / area[v]);
    const Eigen::Vector3d& lambda = eigen.values;
    const Eigen::Matrix3d& vectors = eigen.vectors;
    int drop = 0;
    double best = -1;
    for (int i = 0; i < 3; ++i) {
      const double along = std::abs(vectors.col(i).dot(n));
      if (along > best) best = along, drop = i;
    }
    const int i_min = drop == 0 ? 1 : 0, i_max = drop == 2 ? 1 : 2;
    out.kappa_max[v] = lambda[i_max];
    out.kappa_min[v] = lambda[i_min];
    out.dir_max[v] = vectors.col(i_max).cast<float>();
    out.dir_min[v] = vectors.col(i_min).cast<float>();
  }
  return out;
}

}  // namespace crestline
