#include "crestline/curvature/extremality.h"

#include "crestline/mesh/cotan.h"

namespace crestline {

Extremality compute_extremality(const Mesh& mesh, const Curvature& curvature) {
  const size_t nv = mesh.positions.size();
  const std::vector<Vec3>& x = mesh.positions;
  Extremality out;
  out.e_max.assign(nv, 0.0);
  out.e_min.assign(nv, 0.0);
  for (const Triangle& f : mesh.triangles) {
    const Vec3 n = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
    const double twice_area = n.norm();
    if (!(twice_area > 0)) continue;
    // ∇κ(T) = Σ_k κ_k ∇φ_k with ∇φ_k = N × (opposite edge) / (2 area).
    const Vec3 unit = n / twice_area;
    Vec3 grad_max = Vec3::Zero(), grad_min = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const Vec3 g = unit.cross(x[f[(k + 2) % 3]] - x[f[(k + 1) % 3]]) / twice_area;
      grad_max += curvature.kappa_max[f[k]] * g;
      grad_min += curvature.kappa_min[f[k]] * g;
    }
    // Eq. (4): area-weighted, divided by area(star) below.
    const double area = 0.5 * twice_area;
    for (uint32_t v : f) {
      out.e_max[v] += area * grad_max.dot(curvature.dir_max[v]);
      out.e_min[v] += area * grad_min.dot(curvature.dir_min[v]);
    }
  }
  for (size_t v = 0; v < nv; ++v) {
    const double star = curvature.star_area[v];
    out.e_max[v] = star > 0 ? out.e_max[v] / star : 0.0;
    out.e_min[v] = star > 0 ? out.e_min[v] / star : 0.0;
  }
  return out;
}

}  // namespace crestline
