#include "crestline/curvature/shape_operator.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "crestline/mesh/cotan.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/symmetric_eigen3.h"
#include "crestline/numerics/uninitialised.h"
#include "vertex_scatter.h"

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
  const size_t nt = mesh.triangles.size();

  Curvature c;
  // Sized without a fill (Eigen's vectors construct uninitialised), zeroed
  // on every thread.
  c.vertex_normals.resize(nv);
  parallel_for(nv, [&](size_t begin, size_t end) {
    std::fill(c.vertex_normals.begin() + begin, c.vertex_normals.begin() + end, Vec3::Zero());
  });
  c.star_area.assign(nv, 0.0);
  // No per-triangle arrays (they were the run's peak, 32 bytes a triangle):
  // each triangle's area and area-weighted normal are formed on every
  // thread, a block of triangles at a time, then added to its corners in
  // triangle order, split over the threads by vertex as the edge terms are
  // below: each vertex's sums in ascending triangle order, the same for any
  // number of threads, and the same as a gather over its triangle list.
  constexpr size_t kTriangleBlock = size_t{1} << 16;
  struct TriangleTerm {
    Vec3 weighted;  // area · unit normal
    double area;
  };
  std::vector<TriangleTerm> triangle_terms(std::min(nt, kTriangleBlock));
  detail::scatter_to_vertices<8>(
      nt, kTriangleBlock,
      [&](size_t begin, size_t first, size_t last) {
        for (size_t i = first; i < last; ++i) {
          // The corners lie anywhere in the positions: those of the triangle
          // kAhead on are asked for now (natively; see the edge loop below).
          constexpr size_t kAhead = 8;
          if (i + kAhead < last) {
            const Triangle& ahead = mesh.triangles[begin + i + kAhead];
            __builtin_prefetch(&x[ahead[0]]);
            __builtin_prefetch(&x[ahead[1]]);
            __builtin_prefetch(&x[ahead[2]]);
          }
          const Triangle& f = mesh.triangles[begin + i];
          Vec3 normal;
          const double area = 0.5 * triangle_normal(x[f[0]], x[f[1]], x[f[2]], normal);
          triangle_terms[i] = {area * normal, area};
        }
      },
      [&](size_t t) {  // the corners' sums lie anywhere too
        for (const uint32_t v : mesh.triangles[t]) {
          __builtin_prefetch(&c.vertex_normals[v]);
          __builtin_prefetch(&c.star_area[v]);
        }
      },
      // The arrays by address, captured by value: loaded once, not per triangle.
      [tris = mesh.triangles.data(), terms = triangle_terms.data(), normals = c.vertex_normals.data(),
       areas = c.star_area.data()](size_t t, const auto& mine) {
        const TriangleTerm& term = terms[t % kTriangleBlock];
        for (const uint32_t v : tris[t]) {
          if (!mine(v)) continue;
          normals[v] += term.weighted;
          areas[v] += term.area;
        }
      },
      [](size_t) {});
  std::vector<TriangleTerm>().swap(triangle_terms);
  parallel_for(nv, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      Vec3& n = c.vertex_normals[v];
      const double len = n.norm();
      n = len > 0 ? Vec3(n / len) : Vec3::UnitZ();
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
  UninitialisedVector<Lower> shape = filled_on_every_thread(nv, Lower{});
  struct EdgeTerm {
    Lower s_e;
    double weight[2];  // of its two ends
    bool used;         // false on boundary and degenerate edges
  };
  const size_t ne = topology.edges.size();
  constexpr size_t kBlock = size_t{1} << 14;
  std::vector<EdgeTerm> terms(std::min(ne, kBlock));
  detail::scatter_to_vertices<16>(
      ne, kBlock,
      [&](size_t begin, size_t first, size_t last) {
        for (size_t i = first; i < last; ++i) {
          const size_t e = begin + i;
          // An edge's inputs lie wherever its triangles and larger end are in
          // the arrays (only the smaller end follows the edge order): each a
          // likely cache miss, which the divisions and roots between them keep
          // from overlapping. So edge e asks for those of edge e + kAhead (the
          // triangles' corners for e + 2 kAhead, to find their far corners
          // then). Natively only: WASM has no prefetch (__builtin_prefetch
          // compiles to nothing).
          constexpr size_t kAhead = 8;
          if (i + 2 * kAhead < last) {
            const auto [t0, t1] = topology.edge_triangles[e + 2 * kAhead];
            if (t1 != kNone) {
              __builtin_prefetch(&mesh.triangles[t0]);
              __builtin_prefetch(&mesh.triangles[t1]);
            }
          }
          if (i + kAhead < last) {
            const auto [t0, t1] = topology.edge_triangles[e + kAhead];
            if (t1 != kNone) {
              const uint32_t a = topology.edges[e + kAhead][0], b = topology.edges[e + kAhead][1];
              __builtin_prefetch(&x[b]);
              __builtin_prefetch(&c.vertex_normals[b]);
              // Each triangle's corners are a, b and a far one (distinct after
              // repair_mesh): found without the branches below, which would
              // mispredict here; kept inside the array whatever the triangle.
              const Triangle &f0 = mesh.triangles[t0], &f1 = mesh.triangles[t1];
              __builtin_prefetch(&x[std::min<size_t>(f0[0] ^ f0[1] ^ f0[2] ^ a ^ b, nv - 1)]);
              __builtin_prefetch(&x[std::min<size_t>(f1[0] ^ f1[1] ^ f1[2] ^ a ^ b, nv - 1)]);
            }
          }
          EdgeTerm& term = terms[i];
          term.used = false;
          const auto [t0, t1] = topology.edge_triangles[e];
          if (t1 == kNone) continue;
          const uint32_t a = topology.edges[e][0], b = topology.edges[e][1];
          const Vec3 edge = x[b] - x[a];
          const double length = edge.norm();
          // The two triangles' normals, formed here from their corners (the
          // bits triangle_areas_normals gives; each triangle's three times).
          const Triangle &f0 = mesh.triangles[t0], &f1 = mesh.triangles[t1];
          Vec3 normal0, normal1;
          triangle_normal(x[f0[0]], x[f0[1]], x[f0[2]], normal0);
          triangle_normal(x[f1[0]], x[f1[1]], x[f1[2]], normal1);
          const Vec3 n_sum = normal0 + normal1;
          const double n_sum_norm2 = n_sum.squaredNorm();
          if (!(length > 0) || !(n_sum_norm2 > 0)) continue;
          const Vec3 n_e = n_sum / std::sqrt(n_sum_norm2);  // normalized(), with its one square root
          // H_e = 2|e| cos(θ_e/2) with θ_e the interior dihedral angle; the angle
          // between the normals is π − θ_e, so cos(θ_e/2) = |N_1 − N_2| / 2.
          // Convex (positive) when t1's far corner lies below t0's plane.
          const uint32_t far = f1[0] != a && f1[0] != b ? f1[0] : (f1[1] != a && f1[1] != b ? f1[1] : f1[2]);
          const double side = normal0.dot(x[far] - x[a]);
          const double h_e = (side > 0 ? -1.0 : 1.0) * length * (normal0 - normal1).norm();
          const Vec3 w = (edge / length).cross(n_e);
          // (H_e w_i) w_j: the products, and so the bits, Eigen formed for H_e (w w^T).
          const Vec3 hw = h_e * w;
          term.s_e = {hw[0] * w[0], hw[1] * w[0], hw[2] * w[0], hw[1] * w[1], hw[2] * w[1], hw[2] * w[2]};
          term.weight[0] = 0.5 * c.vertex_normals[a].dot(n_e);
          term.weight[1] = 0.5 * c.vertex_normals[b].dot(n_e);
          term.used = true;
        }
      },
      // The larger ends' sums lie anywhere (see the loop above).
      [&](size_t e) { __builtin_prefetch(&shape[topology.edges[e][1]]); },
      [edges = topology.edges.data(), block_terms = terms.data(), sums = shape.data()](size_t e, const auto& mine) {
        const EdgeTerm& term = block_terms[e % kBlock];
        if (!term.used) return;
        for (int end_k = 0; end_k < 2; ++end_k) {
          const uint32_t v = edges[e][end_k];
          if (!mine(v)) continue;
          // The products first, in locals, then the sums: the same
          // operations, which the compiler can pair up in vector
          // registers once the stores cannot alias the terms.
          const double w = term.weight[end_k];
          double add[6];
          for (int k = 0; k < 6; ++k) add[k] = w * term.s_e[k];
          double* sum = sums[v].data();
          for (int k = 0; k < 6; ++k) sum[k] += add[k];
        }
      },
      [&](size_t end) { report(kNormalsDone + (kEdgesDone - kNormalsDone) * double(end) / double(ne)); });
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
