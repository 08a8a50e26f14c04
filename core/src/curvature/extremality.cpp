#include "crestline/curvature/extremality.h"

#include <algorithm>

#include "crestline/mesh/cotan.h"
#include "crestline/numerics/parallel.h"

namespace crestline {

Extremality compute_extremality(const Mesh& mesh, const Curvature& curvature,
                                const std::function<void(double)>& progress) {
  const size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  const std::vector<Vec3>& x = mesh.positions;
  Extremality out;
  out.e_max.assign(nv, 0.0);
  out.e_min.assign(nv, 0.0);
  // Each triangle's term for each of its corners is computed on every thread,
  // a block of triangles at a time, then added up on the calling thread in
  // triangle order: the sums are the same for any number of threads.
  constexpr size_t kBlock = size_t{1} << 16;
  std::vector<double> term_max(3 * std::min(nt, kBlock)), term_min(term_max.size());
  std::vector<uint8_t> adds(std::min(nt, kBlock));  // 0 for degenerate triangles, which add nothing
  for (size_t begin = 0; begin < nt; begin += kBlock) {
    const size_t end = std::min(nt, begin + kBlock);
    parallel_for(end - begin, [&](size_t first, size_t last) {
      for (size_t i = first; i < last; ++i) {
        const Triangle& f = mesh.triangles[begin + i];
        const Vec3 n = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
        const double twice_area = n.norm();
        adds[i] = twice_area > 0;
        if (!adds[i]) continue;
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
        for (int k = 0; k < 3; ++k) {
          term_max[3 * i + k] = area * grad_max.dot(curvature.dir_max[f[k]]);
          term_min[3 * i + k] = area * grad_min.dot(curvature.dir_min[f[k]]);
        }
      }
    });
    for (size_t t = begin; t < end; ++t) {
      if (!adds[t - begin]) continue;
      const Triangle& f = mesh.triangles[t];
      const size_t i = 3 * (t - begin);
      for (int k = 0; k < 3; ++k) {
        out.e_max[f[k]] += term_max[i + k];
        out.e_min[f[k]] += term_min[i + k];
      }
    }
    if (progress) progress(double(end) / double(nt));
  }
  for (size_t v = 0; v < nv; ++v) {
    const double star = curvature.star_area[v];
    out.e_max[v] = star > 0 ? out.e_max[v] / star : 0.0;
    out.e_min[v] = star > 0 ? out.e_min[v] / star : 0.0;
  }
  return out;
}

}  // namespace crestline
