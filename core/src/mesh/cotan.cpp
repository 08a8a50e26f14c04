#include "crestline/mesh/cotan.h"

#include <algorithm>
#include <cmath>

#include "crestline/numerics/parallel.h"

namespace crestline {

// Slivers give edges weights of up to 2·10⁵ (large/dragon.glb; 1 % of its
// edges above 45), and conjugate gradients then need 800–950 iterations per
// smoothing solve instead of ~30. Capped at 5 (both opposite angles about
// 11°) they need ~110; well-shaped meshes have no weight above 3 and are
// unchanged (the bunny's 0.1 % above 3 are slivers too).
constexpr double kMaxCotanWeight = 5.0;

namespace {

// The unit normals, and ½ the cross product's length into areas if given:
// one loop for both callers, so their bits are the same.
void fill_triangle_normals(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                           std::vector<Vec3>& normals, double* areas) {
  normals.resize(triangles.size());
  parallel_for(triangles.size(), [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      // The corners lie anywhere in the positions: those of the triangle
      // kAhead on are asked for now (natively; WASM has no prefetch).
      constexpr size_t kAhead = 8;
      if (t + kAhead < end)
        for (uint32_t v : triangles[t + kAhead]) __builtin_prefetch(&positions[v]);
      const Triangle& f = triangles[t];
      const double area = 0.5 * triangle_normal(positions[f[0]], positions[f[1]], positions[f[2]], normals[t]);
      if (areas != nullptr) areas[t] = area;
    }
  });
}

}  // namespace

void triangle_areas_normals(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                            std::vector<double>& areas, std::vector<Vec3>& normals) {
  areas.resize(triangles.size());
  fill_triangle_normals(positions, triangles, normals, areas.data());
}

void triangle_normals(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                      std::vector<Vec3>& normals) {
  fill_triangle_normals(positions, triangles, normals, nullptr);
}

CotanWeights cotan_weights(const std::vector<Vec3>& positions, const Mesh& mesh, const Topology& topology) {
  CotanWeights out;
  out.edge_weight.assign(topology.edges.size(), 0.0);
  out.vertex_mass.assign(positions.size(), 0.0);
  // Each triangle's mass and cotangents are computed on every thread, a
  // block of triangles at a time, then added up on the calling thread in
  // triangle order: the same sums for any number of threads. (Split over
  // the threads by vertex and edge, as detail::scatter_to_vertices splits
  // its sums, the addition cost more on 2 threads than this loop: 1.1M
  // triangles, load 6, 73-84 -> 97-112 ms.)
  const size_t nt = mesh.triangles.size();
  constexpr size_t kBlock = size_t{1} << 16;
  struct Terms {
    double mass;    // twice the area / 6
    double cot[3];  // ½ cot of the angle opposite edge k
    bool has_area;  // without, it adds no weight
  };
  std::vector<Terms> terms(std::min(nt, kBlock));
  // The corners and the sums lie anywhere in their arrays: those of the
  // triangle kAhead on are asked for now (natively; WASM has no prefetch).
  constexpr size_t kAhead = 8;
  for (size_t begin = 0; begin < nt; begin += kBlock) {
    const size_t end = std::min(nt, begin + kBlock);
    parallel_for(end - begin, [&](size_t first, size_t last) {
      for (size_t i = first; i < last; ++i) {
        if (i + kAhead < last)
          for (const uint32_t v : mesh.triangles[begin + i + kAhead]) __builtin_prefetch(&positions[v]);
        const Triangle& f = mesh.triangles[begin + i];
        // The sides once: e[k] runs from corner k to corner k+1. The angle
        // at corner k+2 is opposite side k and its cosine's numerator is
        // (p_k − p_{k+2})·(p_{k+1} − p_{k+2}) = −e[k+2]·e[k+1]; IEEE
        // negation is exact, so these are the bits of that form (and of
        // |(p1 − p0) × (p2 − p0)| = |e[0] × e[2]|), with 9 subtractions
        // instead of 24.
        const Vec3 &p0 = positions[f[0]], &p1 = positions[f[1]], &p2 = positions[f[2]];
        const Vec3 e[3] = {p1 - p0, p2 - p1, p0 - p2};
        const double twice_area = e[0].cross(e[2]).norm();
        Terms& term = terms[i];
        term.mass = twice_area / 6.0;
        term.has_area = twice_area > 0;
        for (int k = 0; k < 3; ++k) term.cot[k] = -(0.5 * (e[(k + 2) % 3].dot(e[(k + 1) % 3]) / twice_area));
      }
    });
    for (size_t t = begin; t < end; ++t) {
      if (t + kAhead < end)
        for (int k = 0; k < 3; ++k) {
          __builtin_prefetch(&out.vertex_mass[mesh.triangles[t + kAhead][k]]);
          __builtin_prefetch(&out.edge_weight[topology.triangle_edges[t + kAhead][k]]);
        }
      const Terms& term = terms[t - begin];
      const Triangle& f = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) out.vertex_mass[f[k]] += term.mass;
      if (!term.has_area) continue;
      for (int k = 0; k < 3; ++k) out.edge_weight[topology.triangle_edges[t][k]] += term.cot[k];
    }
  }
  parallel_for(out.edge_weight.size(), [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e) {
      double& w = out.edge_weight[e];
      w = std::isfinite(w) ? std::clamp(w, 0.0, kMaxCotanWeight) : 0.0;
    }
  });
  return out;
}

}  // namespace crestline
