#include "crestline/curvature/shape_operator.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "../mesh/parts.h"
#include "crestline/mesh/cotan.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/symmetric_eigen3.h"

namespace crestline {

Curvature compute_curvature(const Mesh& mesh, const Topology& topology, const std::function<void(double)>& progress) {
  // The stage's parts by share of its time (1.1M triangles): normals, edge
  // terms, eigen-decompositions.
  constexpr double kNormalsDone = 0.1, kEdgesDone = 0.55;
  const auto report = [&](double fraction) {
    if (progress) progress(fraction);
  };
  const size_t nv = mesh.positions.size();
  const std::vector<Vec3>& x = mesh.positions;
  std::vector<double> areas;
  std::vector<Vec3> normals;
  triangle_areas_normals(x, mesh.triangles, areas, normals);

  Curvature c;
  c.vertex_normals.resize(nv);
  c.star_area.resize(nv);
  // Gathered over each vertex's triangles, which the topology lists in
  // ascending order: the sums of a scatter over the triangles, bit for bit,
  // on any number of threads.
  parallel_for(nv, [&](size_t begin, size_t end) {
    const uint32_t last_entry = topology.vertex_offsets[end];
    for (size_t v = begin; v < end; ++v) {
      Vec3 n = Vec3::Zero();
      double star = 0;
      for (uint32_t i = topology.vertex_offsets[v]; i < topology.vertex_offsets[v + 1]; ++i) {
        // The triangles lie anywhere in their arrays: those of the entry
        // kAhead on are asked for now (natively; see the edge loop below).
        constexpr uint32_t kAhead = 16;
        if (i + kAhead < last_entry) {
          const uint32_t ahead = topology.vertex_triangles[i + kAhead];
          __builtin_prefetch(&normals[ahead]);
          __builtin_prefetch(&areas[ahead]);
        }
        const uint32_t t = topology.vertex_triangles[i];
        n += areas[t] * normals[t];
        star += areas[t];
      }
      const double len = n.norm();
      c.vertex_normals[v] = len > 0 ? Vec3(n / len) : Vec3::UnitZ();
      c.star_area[v] = star;
    }
  });
  report(kNormalsDone);

  // S(p) = ½ Σ_{e∋p} ⟨N_p, N_e⟩ S(e), S(e) = H_e (ē×N_e)(ē×N_e)^T.
  // Each edge's S(e) and its two weights ½⟨N_p, N_e⟩ are computed on every
  // thread, a block of edges at a time, then added to its two vertices in
  // edge order; that addition is split over the threads by vertex (runs of
  // 64 vertices dealt out in turn), each thread going through the block's
  // edges in order: every vertex's sum in edge order, the same for any
  // number of threads. Only the lower triangles are kept, (0,0) (1,0) (2,0)
  // (1,1) (2,1) (2,2): all that the eigen-solver reads.
  using Lower = SymmetricLower3;
  std::vector<Lower> shape(nv, Lower{});
  struct EdgeTerm {
    Lower s_e;
    double weight[2];  // of its two ends
    bool used;         // false on boundary and degenerate edges
  };
  const size_t ne = topology.edges.size();
  constexpr size_t kBlock = size_t{1} << 14;
  std::vector<EdgeTerm> terms(std::min(ne, kBlock));
  const size_t parts = ne < 4 * kBlock ? 1 : std::min<size_t>(size_t(max_threads()), 8);
  for (size_t begin = 0; begin < ne; begin += kBlock) {
    const size_t end = std::min(ne, begin + kBlock);
    parallel_for(end - begin, [&](size_t first, size_t last) {
      for (size_t i = first; i < last; ++i) {
        const size_t e = begin + i;
        // An edge's inputs lie wherever its triangles and larger end are in
        // the arrays (only the smaller end follows the edge order): each a
        // likely cache miss, which the divisions and roots between them keep
        // from overlapping. So edge e asks for those of edge e + kAhead (t1's
        // corners for e + 2 kAhead, to find its far corner then). Natively
        // only: WASM has no prefetch (__builtin_prefetch compiles to
        // nothing). Written in the loop: GCC drops a call to a lambda made of
        // prefetches as if it had no effect.
        constexpr size_t kAhead = 8;
        if (i + 2 * kAhead < last) {
          const uint32_t t1 = topology.edge_triangles[e + 2 * kAhead][1];
          if (t1 != kNone) __builtin_prefetch(&mesh.triangles[t1]);
        }
        if (i + kAhead < last) {
          const auto [t0, t1] = topology.edge_triangles[e + kAhead];
          if (t1 != kNone) {
            const uint32_t a = topology.edges[e + kAhead][0], b = topology.edges[e + kAhead][1];
            __builtin_prefetch(&normals[t0]);
            __builtin_prefetch(&normals[t1]);
            __builtin_prefetch(&x[b]);
            __builtin_prefetch(&c.vertex_normals[b]);
            // t1's corners are a, b and the far one (distinct after
            // repair_mesh): found without the branches below, which would
            // mispredict here; kept inside the array whatever the triangle.
            const Triangle& f = mesh.triangles[t1];
            __builtin_prefetch(&x[std::min<size_t>(f[0] ^ f[1] ^ f[2] ^ a ^ b, nv - 1)]);
          }
        }
        EdgeTerm& term = terms[i];
        term.used = false;
        const auto [t0, t1] = topology.edge_triangles[e];
        if (t1 == kNone) continue;
        const uint32_t a = topology.edges[e][0], b = topology.edges[e][1];
        const Vec3 edge = x[b] - x[a];
        const double length = edge.norm();
        const Vec3 n_sum = normals[t0] + normals[t1];
        const double n_sum_norm2 = n_sum.squaredNorm();
        if (!(length > 0) || !(n_sum_norm2 > 0)) continue;
        const Vec3 n_e = n_sum / std::sqrt(n_sum_norm2);  // normalized(), with its one square root
        // H_e = 2|e| cos(θ_e/2) with θ_e the interior dihedral angle; the angle
        // between the normals is π − θ_e, so cos(θ_e/2) = |N_1 − N_2| / 2.
        // Convex (positive) when t1's far corner lies below t0's plane.
        const Triangle& f1 = mesh.triangles[t1];
        const uint32_t far = f1[0] != a && f1[0] != b ? f1[0] : (f1[1] != a && f1[1] != b ? f1[1] : f1[2]);
        const double side = normals[t0].dot(x[far] - x[a]);
        const double h_e = (side > 0 ? -1.0 : 1.0) * length * (normals[t0] - normals[t1]).norm();
        const Vec3 w = (edge / length).cross(n_e);
        // (H_e w_i) w_j: the products, and so the bits, Eigen formed for H_e (w w^T).
        const Vec3 hw = h_e * w;
        term.s_e = {hw[0] * w[0], hw[1] * w[0], hw[2] * w[0], hw[1] * w[1], hw[2] * w[1], hw[2] * w[2]};
        term.weight[0] = 0.5 * c.vertex_normals[a].dot(n_e);
        term.weight[1] = 0.5 * c.vertex_normals[b].dot(n_e);
        term.used = true;
      }
    });
    parallel_for(
        parts,
        [&](size_t first_part, size_t last_part) {
          for (size_t part = first_part; part < last_part; ++part)
            for (size_t e = begin; e < end; ++e) {
              // The larger ends' sums lie anywhere (see the loop above).
              constexpr size_t kAhead = 16;
              if (e + kAhead < end) __builtin_prefetch(&shape[topology.edges[e + kAhead][1]]);
              const EdgeTerm& term = terms[e - begin];
              if (!term.used) continue;
              for (int end_k = 0; end_k < 2; ++end_k) {
                const uint32_t v = topology.edges[e][end_k];
                if (!detail::in_vertex_part(v, part, parts)) continue;
                // The products first, in locals, then the sums: the same
                // operations, which the compiler can pair up in vector
                // registers once the stores cannot alias the terms.
                const double w = term.weight[end_k];
                double add[6];
                for (int k = 0; k < 6; ++k) add[k] = w * term.s_e[k];
                double* sum = shape[v].data();
                for (int k = 0; k < 6; ++k) sum[k] += add[k];
              }
            }
        },
        1);
    report(kNormalsDone + (kEdgesDone - kNormalsDone) * double(end) / double(ne));
  }
  // The triangles' normals and areas are done with: freed before the four
  // fields below are made (32 bytes per triangle, the stage's peak).
  std::vector<Vec3>().swap(normals);
  std::vector<double>().swap(areas);
  std::vector<EdgeTerm>().swap(terms);

  c.kappa_max.resize(nv);
  c.kappa_min.resize(nv);
  c.dir_max.resize(nv);
  c.dir_min.resize(nv);
  // One eigen-decomposition per vertex, each writing only its own vertex:
  // the same results on any number of threads. In blocks, for progress, and
  // a run of vertices at a time in each, which the solver takes in pairs.
  constexpr size_t kVertexBlock = size_t{1} << 16;
  for (size_t block = 0; block < nv; block += kVertexBlock) {
    const size_t block_end = std::min(nv, block + kVertexBlock);
    parallel_for(block_end - block, [&](size_t first, size_t last) {
      constexpr size_t kRun = 64;
      SymmetricEigen3 run[kRun];
      for (size_t run_begin = block + first; run_begin < block + last; run_begin += kRun) {
        const size_t count = std::min(kRun, block + last - run_begin);
        symmetric_eigen3(&shape[run_begin], count, run);
        for (size_t i = 0; i < count; ++i) {
          const size_t v = run_begin + i;
          const Eigen::Vector3d& lambda = run[i].values;  // ascending
          const Eigen::Matrix3d& vectors = run[i].vectors;
          // The paper keeps the two eigenvalues of largest magnitude; the third
          // belongs (up to noise) to the normal. On a flat patch all three vanish
          // and "largest" is noise, so we drop the eigenvector closest to the
          // vertex normal instead: the same choice on curved surfaces, and the
          // directions stay tangent on flat ones.
          int drop = 0;
          double best = -1;
          for (int k = 0; k < 3; ++k) {
            const double along = std::abs(vectors.col(k).dot(c.vertex_normals[v]));
            if (along > best) best = along, drop = k;
          }
          const int i_min = drop == 0 ? 1 : 0, i_max = drop == 2 ? 1 : 2;
          const double scale = c.star_area[v] > 0 ? 3.0 / c.star_area[v] : 0.0;
          c.kappa_max[v] = scale * lambda[i_max];
          c.kappa_min[v] = scale * lambda[i_min];
          c.dir_max[v] = vectors.col(i_max).cast<float>();
          c.dir_min[v] = vectors.col(i_min).cast<float>();
        }
      }
    });
    report(kEdgesDone + (1 - kEdgesDone) * double(block_end) / double(nv));
  }
  return c;
}

}  // namespace crestline
