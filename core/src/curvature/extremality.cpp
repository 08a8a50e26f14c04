#include "crestline/curvature/extremality.h"

#include <algorithm>

#include "crestline/mesh/cotan.h"
#include "crestline/numerics/parallel.h"
#include "vertex_scatter.h"

namespace crestline {

Extremality compute_extremality(const Mesh& mesh, const Curvature& curvature,
                                const std::function<void(double)>& progress) {
  const size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  Extremality out;
  out.e_max.assign(nv, 0.0);
  out.e_min.assign(nv, 0.0);
  // Each triangle's term for each of its corners is computed on every thread,
  // a block of triangles at a time, then added to the corners' vertices in
  // triangle order; that addition is split over the threads by vertex (runs
  // of 64 vertices dealt out in turn), each thread going through the block's
  // triangles in order: the sums are the same for any number of threads.
  // (Blocks of 8,192 kept the terms in a core's L2, but each block's two
  // loops wake the other threads: 272 wake-ups at 1.1M triangles instead of
  // 34, for terms that fit this machine's 32 MB L3 anyway.)
  constexpr size_t kBlock = size_t{1} << 16;
  std::vector<double> term_max(3 * std::min(nt, kBlock)), term_min(term_max.size());
  std::vector<uint8_t> adds(std::min(nt, kBlock));  // 0 for degenerate triangles, which add nothing
  // The arrays by address, captured by value: the byte store of `adds` may
  // alias anything, so the vectors' data would be reloaded after it.
  const Triangle* tris = mesh.triangles.data();
  const Vec3* x = mesh.positions.data();
  const Direction *dir_max = curvature.dir_max.data(), *dir_min = curvature.dir_min.data();
  const double *kappa_max = curvature.kappa_max.data(), *kappa_min = curvature.kappa_min.data();
  double *max_terms = term_max.data(), *min_terms = term_min.data();
  uint8_t* adding = adds.data();
  double *e_max = out.e_max.data(), *e_min = out.e_min.data();
  detail::scatter_to_vertices<8>(
      nt, kBlock,
      [=](size_t begin, size_t first, size_t last) {
        for (size_t i = first; i < last; ++i) {
          // The corners' fields lie anywhere in their arrays: those of the
          // triangle kAhead on are asked for now (natively; WASM has no
          // prefetch).
          constexpr size_t kAhead = 8;
          if (i + kAhead < last) {
            const Triangle& ahead = tris[begin + i + kAhead];
            for (int k = 0; k < 3; ++k) {
              __builtin_prefetch(&x[ahead[k]]);
              __builtin_prefetch(&kappa_max[ahead[k]]);
              __builtin_prefetch(&kappa_min[ahead[k]]);
              __builtin_prefetch(&dir_max[ahead[k]]);
              __builtin_prefetch(&dir_min[ahead[k]]);
            }
          }
          const Triangle& f = tris[begin + i];
          const Vec3 n = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
          const double twice_area = n.norm();
          adding[i] = twice_area > 0;
          if (!(twice_area > 0)) continue;
          // ∇κ(T) = Σ_k κ_k ∇φ_k with ∇φ_k = N × (opposite edge) / (2 area).
          const Vec3 unit = n / twice_area;
          Vec3 grad_max = Vec3::Zero(), grad_min = Vec3::Zero();
          for (int k = 0; k < 3; ++k) {
            const Vec3 g = unit.cross(x[f[(k + 2) % 3]] - x[f[(k + 1) % 3]]) / twice_area;
            grad_max += kappa_max[f[k]] * g;
            grad_min += kappa_min[f[k]] * g;
          }
          // Eq. (4): area-weighted, divided by area(star) below.
          const double area = 0.5 * twice_area;
          for (int k = 0; k < 3; ++k) {
            max_terms[3 * i + k] = area * grad_max.dot(widen(dir_max[f[k]]));
            min_terms[3 * i + k] = area * grad_min.dot(widen(dir_min[f[k]]));
          }
        }
      },
      [=](size_t t) {  // as above
        for (const uint32_t v : tris[t]) {
          __builtin_prefetch(&e_max[v]);
          __builtin_prefetch(&e_min[v]);
        }
      },
      [=](size_t t, const auto& mine) {
        const size_t i = t % kBlock;
        if (!adding[i]) return;
        const Triangle& f = tris[t];
        for (int k = 0; k < 3; ++k) {
          if (!mine(f[k])) continue;
          e_max[f[k]] += max_terms[3 * i + k];
          e_min[f[k]] += min_terms[3 * i + k];
        }
      },
      [&](size_t end) {
        if (progress) progress(double(end) / double(nt));
      });
  parallel_for(nv, [&](size_t first, size_t last) {
    for (size_t v = first; v < last; ++v) {
      const double star = curvature.star_area[v];
      out.e_max[v] = star > 0 ? out.e_max[v] / star : 0.0;
      out.e_min[v] = star > 0 ? out.e_min[v] / star : 0.0;
    }
  });
  return out;
}

}  // namespace crestline
