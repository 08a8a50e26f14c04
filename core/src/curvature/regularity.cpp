#include "crestline/curvature/regularity.h"

#include <atomic>

#include "crestline/numerics/parallel.h"

namespace crestline {

Regularity classify_triangles(const Mesh& mesh, const Curvature& curvature) {
  Regularity r;
  const size_t nt = mesh.triangles.size();
  r.regular_max.resize(nt);
  r.regular_min.resize(nt);
  // Each triangle writes only its own flags; the counts are integers, exact
  // in any order.
  std::atomic<size_t> singular_max{0}, singular_min{0};
  parallel_for(nt, [&](size_t begin, size_t end) {
    std::array<double, 3> signs;
    size_t count_max = 0, count_min = 0;
    for (size_t t = begin; t < end; ++t) {
      const Triangle& f = mesh.triangles[t];
      r.regular_max[t] = regularity_code(
          consistent_signs(curvature.dir_max[f[0]], curvature.dir_max[f[1]], curvature.dir_max[f[2]], signs), signs);
      r.regular_min[t] = regularity_code(
          consistent_signs(curvature.dir_min[f[0]], curvature.dir_min[f[1]], curvature.dir_min[f[2]], signs), signs);
      count_max += !r.regular_max[t];
      count_min += !r.regular_min[t];
    }
    singular_max += count_max;
    singular_min += count_min;
  });
  r.singular_max = singular_max;
  r.singular_min = singular_min;
  return r;
}

}  // namespace crestline
