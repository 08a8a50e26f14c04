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
  // The arrays by address: a byte store may alias anything, so the vectors'
  // data would be reloaded after each.
  parallel_for(nt,
               [&, tris = mesh.triangles.data(), dir_max = curvature.dir_max.data(), dir_min = curvature.dir_min.data(),
                regular_max = r.regular_max.data(), regular_min = r.regular_min.data()](size_t begin, size_t end) {
                 size_t count_max = 0, count_min = 0;
                 for (size_t t = begin; t < end; ++t) {
                   // The corners' directions lie anywhere in their arrays:
                   // those of the triangle kAhead on are asked for now
                   // (natively; WASM has no prefetch).
                   constexpr size_t kAhead = 8;
                   if (t + kAhead < end) {
                     const Triangle& ahead = tris[t + kAhead];
                     for (int k = 0; k < 3; ++k) {
                       __builtin_prefetch(&dir_max[ahead[k]]);
                       __builtin_prefetch(&dir_min[ahead[k]]);
                     }
                   }
                   const Triangle f = tris[t];
                   const uint8_t code_max = regularity_code(dir_max[f[0]], dir_max[f[1]], dir_max[f[2]]);
                   const uint8_t code_min = regularity_code(dir_min[f[0]], dir_min[f[1]], dir_min[f[2]]);
                   regular_max[t] = code_max, regular_min[t] = code_min;
                   count_max += !code_max;
                   count_min += !code_min;
                 }
                 singular_max += count_max;
                 singular_min += count_min;
               });
  r.singular_max = singular_max;
  r.singular_min = singular_min;
  return r;
}

}  // namespace crestline
