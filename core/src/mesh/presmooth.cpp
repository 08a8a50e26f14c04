#include "crestline/mesh/presmooth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "../curvature/vertex_scatter.h"
#include "../numerics/select.h"
#include "crestline/error.h"
#include "crestline/mesh/cotan.h"
#include "crestline/mesh/frame.h"
#include "crestline/numerics/constants.h"
#include "crestline/numerics/paired_cg.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/portable_math.h"
#include "crestline/numerics/sparse_solver.h"
#include "crestline/numerics/uninitialised.h"
#include "half_edges.h"

namespace crestline {

// Vertices on a clean sharp edge or corner: at least two of their edges turn
// by kCleanCreaseTurn or more, at least two are flat (turn at most
// kFlatTurn: the faces on either side are planar) and none turns in between.
// Their offset comes from the crease, not from noise, and on a coarse CAD
// tessellation nearly every vertex is one (a face's vertices lie on its
// border), so their jumps read as noise (issue 16). Noise turns edges by every
// angle, so a noisy vertex seldom qualifies: on tests/quality, σ = 0.1 to
// 0.5, a median of 1 vertex per mesh, at most 0.5 % (long thin cells tilt
// little), and no level moved by more than 0.0024.
constexpr double kCleanCreaseTurn = 40 * kPi / 180;
constexpr double kFlatTurn = 1 * kPi / 180;
// A coarse cylinder's rim vertex also has wall edges turning by 5-15°, what
// noise makes too; but the wall turns by the same total at every vertex along
// the rim (the rim polygon's exterior angle), while noise turns each ring by
// its own. Such a vertex counts as on a clean crease when its total turn over
// the in-between edges equals that of at least two neighbours along its sharp
// edges within kEqualTurn (relative) and at least one edge is flat. On
// tests/quality's 810 noisy meshes this moved 115 levels, by at most 0.0014;
// 5 % moved 409 (the same maximum) and the noisy icosphere test's level.
constexpr double kEqualTurn = 0.02;

// A vertex's edges in ascending order, from its triangles' (a few).
static void edges_at(const Mesh& mesh, const Topology& topology, uint32_t v, std::vector<uint32_t>& out) {
  out.clear();
  for (uint32_t i = topology.vertex_offsets[v]; i < topology.vertex_offsets[v + 1]; ++i) {
    const uint32_t t = topology.vertex_triangles[i];
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] == v)
        out.push_back(topology.triangle_edges[t][k]), out.push_back(topology.triangle_edges[t][(k + 2) % 3]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

namespace {
// A triangle's unnormalised normal (twice its area) and its norm, side by
// side: an edge's test and a vertex's normal find both in one cache line.
struct alignas(32) FaceNormal {
  Vec3 n;
  double norm;
};
using FaceNormals = UninitialisedVector<FaceNormal>;
// A vertex's sum over the neighbours a sweep (sweep_edges) has met, and their count.
template <typename T>
struct alignas(sizeof(T) > 8 ? 32 : 16) NeighbourSum {
  T sum;
  uint32_t count;
};
}  // namespace

// The angle between an edge's two face normals as its cosine; 0 where a
// normal vanishes (degenerate), 1 on the boundary.
static double edge_cosine(const Topology& topology, const FaceNormals& n, uint32_t e, bool& degenerate) {
  const auto& tt = topology.edge_triangles[e];
  degenerate = false;
  if (tt[1] == kNone) return 1.0;
  const double norms = n[tt[0]].norm * n[tt[1]].norm;
  degenerate = !(norms > 0);
  return norms > 0 ? n[tt[0]].n.dot(n[tt[1]].n) / norms : 0.0;
}

static double cos_clean_crease_turn() { return portable_cos(kCleanCreaseTurn); }

// Whether an edge is sharp enough for a clean crease: only a vertex with one
// can be on a clean crease or a wall (below).
static bool sharp_edge(const Topology& topology, const FaceNormals& n, uint32_t e, double cos_sharp) {
  bool degenerate;
  const double c = edge_cosine(topology, n, e, degenerate);
  return topology.edge_triangles[e][1] != kNone && !degenerate && c <= cos_sharp;
}

enum : uint8_t { kOnWall = 1, kClean = 2, kCleanIfEqual = 4 };

// A candidate vertex's state: at least two sharp edges, at least two flat
// ones and none in between (counts up to 2; a degenerate edge means never
// clean), or on a wall (a sharp edge and one in between), where `turn` is
// set to the total turn over the in-between edges, added in edge order.
static uint8_t crease_state(const Mesh& mesh, const Topology& topology, const FaceNormals& n, double cos_sharp,
                            double cos_flat, uint32_t v, std::vector<uint32_t>& edges, double& turn) {
  edges_at(mesh, topology, v, edges);
  int sharp = 0, flat = 0, between = 0;
  double sum = 0.0;
  for (uint32_t e : edges) {
    bool degenerate;
    const double c = edge_cosine(topology, n, e, degenerate);
    if (topology.edge_triangles[e][1] == kNone) continue;
    if (degenerate) {
      between = 2;
    } else if (c < cos_flat && c > cos_sharp) {
      between += between < 1;
      sum += portable_acos_of_complement(1 - c);
    } else if (c <= cos_sharp) {
      sharp += sharp < 2;
    } else {
      flat += flat < 2;
    }
  }
  const bool on_wall = sharp > 0 && between == 1;
  if (on_wall) turn = sum;
  return uint8_t((on_wall ? kOnWall : 0) | (sharp == 2 && flat == 2 && !between ? kClean : 0) |
                 (sharp == 2 && flat >= 1 && between == 1 ? kCleanIfEqual : 0));
}

// sharp: the sharp edges (sharp_edge) in ascending order; few on a smooth
// mesh, so the rest is found only at their vertices.
static std::vector<uint8_t> clean_crease_vertices(const Mesh& mesh, const Topology& topology, const FaceNormals& n,
                                                  const std::vector<uint32_t>& sharp) {
  const double cos_sharp = cos_clean_crease_turn(), cos_flat = portable_cos(kFlatTurn);
  const size_t nv = mesh.positions.size();
  std::vector<uint8_t> out(nv, 0);
  if (sharp.empty()) return out;
  auto cosine = [&](uint32_t e, bool& degenerate) { return edge_cosine(topology, n, e, degenerate); };
  // Their vertices, gathered in ascending order on every thread.
  std::vector<uint8_t> state(nv, 0);  // 1 for a candidate, then its state (below)
  for (uint32_t e : sharp) state[topology.edges[e][0]] = state[topology.edges[e][1]] = 1;
  const std::vector<uint32_t> candidates = detail::indices_where(nv, [&](size_t v) { return state[v] != 0; });
  // Each one's state (crease_state), its turn in turn[i] for candidates[i].
  std::vector<double> turn(candidates.size(), 0.0);
  auto turn_at = [&](uint32_t v) {
    return turn[std::lower_bound(candidates.begin(), candidates.end(), v) - candidates.begin()];
  };
  // Each candidate on its own, on every thread (a scratch list per chunk).
  parallel_for(
      candidates.size(),
      [&](size_t begin, size_t end) {
        std::vector<uint32_t> edges;
        for (size_t i = begin; i < end; ++i)
          state[candidates[i]] = crease_state(mesh, topology, n, cos_sharp, cos_flat, candidates[i], edges, turn[i]);
      },
      256);
  // Clean where it qualified outright, or where two neighbours along sharp
  // edges turn by the same total.
  parallel_for(
      candidates.size(),
      [&](size_t begin, size_t end) {
        std::vector<uint32_t> edges;
        for (size_t i = begin; i < end; ++i) {
          const uint32_t v = candidates[i];
          if (state[v] & kClean) out[v] = 1;
          if (!(state[v] & kCleanIfEqual)) continue;
          edges_at(mesh, topology, v, edges);
          int equal = 0;
          const double turn_v = turn[i];
          for (uint32_t e : edges) {
            bool degenerate;
            const uint32_t w = topology.edges[e][0] ^ topology.edges[e][1] ^ v;
            if (topology.edge_triangles[e][1] == kNone || !(cosine(e, degenerate) <= cos_sharp) ||
                !(state[w] & kOnWall))
              continue;
            const double turn_w = turn_at(w);
            equal += equal < 2 && std::abs(turn_v - turn_w) <= kEqualTurn * std::max(turn_v, turn_w);
          }
          out[v] = equal == 2;
        }
      },
      256);
  return out;
}

// The edges' sums onto their ends, taken in one sweep over the edges in
// order rather than gathered over grouped neighbour lists (no grouping,
// 13 MB at 1.1M triangles): the edges run by smaller end, ascending, then
// by larger end (build_topology's and repair_mesh's order), so vertex v
// meets its smaller neighbours first, from the edges (w, v) the runs of the
// vertices before it scatter to it, then its larger ones in its own run:
// ascending order, that of the gather. own(part, v, first, last, mine) is
// called for v with [first, last) its run, after every edge (w, v) has been
// scattered, scatter(v, w) for an edge (v, w) in another part's run whose w
// is this part's. Split over the threads by vertex (VertexParts): each goes
// through every edge and adds only to its own vertices, so every sum is in
// edge order for any thread count.
template <typename Own, typename Scatter>
static void sweep_edges(const Topology& topology, size_t nv, size_t parts_wanted, const Own& own,
                        const Scatter& scatter) {
  const detail::VertexParts parts(parts_wanted);
  const size_t ne = topology.edges.size();
  parallel_for(
      parts.parts,
      [&](size_t first_part, size_t last_part) {
        const auto* edges = topology.edges.data();
        const auto run = [&](size_t part, const auto& mine) {
          size_t e = 0;
          for (uint32_t v = 0; v < nv; ++v) {
            const size_t first = e;
            while (e < ne && edges[e][0] == v) ++e;
            if (mine(v)) {
              own(part, v, first, e, mine);
            } else {
              for (size_t i = first; i < e; ++i)
                if (mine(edges[i][1])) scatter(v, edges[i][1]);
            }
          }
          if (e != ne) throw Error(ErrorKind::InvalidInput, "the adjacency's edges are not in ascending order.");
        };
        // One part tests nothing.
        if (parts.parts == 1) return run(0, [](uint32_t) { return true; });
        for (size_t part = first_part; part < last_part; ++part)
          run(part, [part, parts](uint32_t v) { return parts.of(v) == part; });
      },
      1);
}

std::vector<double> surface_noise_levels(const Mesh& mesh, const Topology& topology,
                                         const std::vector<uint32_t>& vertex_component, size_t components) {
  // Signed offset of each vertex from its neighbours' centroid along its
  // normal: curvature makes it vary smoothly, noise makes it jump. The jump,
  // offset minus its neighbours' mean offset, measures the noise alone.
  // Every per-vertex sum is over the vertex's triangles (gathered) or its
  // neighbours (swept: sweep_edges) in ascending order (the order of a
  // scatter over the triangles or the edges), on every thread: the same
  // bits for any count.
  const size_t nv = mesh.positions.size(), nt = mesh.triangles.size(), ne = topology.edges.size();
  const std::vector<Vec3>& x = mesh.positions;
  const std::vector<uint8_t>& boundary = topology.boundary_vertex;
  const auto* edges = topology.edges.data();
  const auto* edge_triangles = topology.edge_triangles.data();
  const uint32_t* fan = topology.vertex_triangles.data();
  const size_t fan_size = topology.vertex_triangles.size();
  // Items kAhead on lie anywhere in the arrays they index: asked for now
  // (natively; WASM has no prefetch).
  constexpr size_t kAhead = 8;
  FaceNormals face(nt);
  parallel_for(nt, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f) {
      if (f + kAhead < end)
        for (uint32_t v : mesh.triangles[f + kAhead]) __builtin_prefetch(&x[v]);
      const Triangle& t = mesh.triangles[f];
      face[f].n = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
      face[f].norm = face[f].n.norm();
    }
  });
  // One sweep over the edges (sweep_edges) measures them for the side sums
  // (each once, below), finds the sharp ones (each part's in ascending
  // order; few on a smooth mesh) and sums each vertex's neighbours, and at
  // each vertex the offset (valid where it has one; on a clean crease it
  // is dropped below).
  const double cos_sharp = cos_clean_crease_turn();
  const size_t parts = detail::part_count(ne);
  std::vector<std::vector<uint32_t>> part_sharp(parts);
  UninitialisedVector<double> length(ne);
  UninitialisedVector<double> offset(nv);
  UninitialisedVector<uint8_t> valid(nv);
  {
    UninitialisedVector<NeighbourSum<Vec3>> around = filled_on_every_thread(nv, NeighbourSum<Vec3>{Vec3::Zero(), 0});
    sweep_edges(
        topology, nv, parts,
        [&](size_t part, uint32_t v, size_t first, size_t last, const auto& mine) {
          Vec3 sum = around[v].sum;
          uint32_t count = around[v].count;
          const Vec3 xv = x[v];
          for (size_t e = first; e < last; ++e) {
            if (e + kAhead < ne) {
              const uint32_t w = edges[e + kAhead][1];
              __builtin_prefetch(&x[w]);
              __builtin_prefetch(&around[w], 1);
              const auto& tt = edge_triangles[e + kAhead];
              __builtin_prefetch(&face[tt[0]]);
              if (tt[1] != kNone) __builtin_prefetch(&face[tt[1]]);
            }
            const uint32_t w = edges[e][1];
            const Vec3 xw = x[w];
            length[e] = (xw - xv).norm();
            if (sharp_edge(topology, face, uint32_t(e), cos_sharp)) part_sharp[part].push_back(uint32_t(e));
            sum += xw, ++count;
            if (mine(w)) around[w].sum += xv, ++around[w].count;
          }
          valid[v] = 0;
          if (boundary[v] || count == 0) return;
          Vec3 normal = Vec3::Zero();
          const uint32_t fan_end = topology.vertex_offsets[v + 1];
          for (uint32_t i = topology.vertex_offsets[v]; i < fan_end; ++i) {
            if (i + kAhead < fan_size) __builtin_prefetch(&face[fan[i + kAhead]]);
            normal += face[fan[i]].n;
          }
          // normalized()'s own norm, taken once (its division by the same root).
          const double norm = normal.norm();
          if (!(norm > 0)) return;
          offset[v] = (normal / norm).dot(xv - sum / count);
          valid[v] = 1;
        },
        [&](uint32_t v, uint32_t w) { around[w].sum += x[v], ++around[w].count; });
  }
  std::vector<uint32_t> sharp = std::move(part_sharp[0]);
  for (size_t p = 1; p < parts; ++p) sharp.insert(sharp.end(), part_sharp[p].begin(), part_sharp[p].end());
  part_sharp = {};
  // The parts' runs of vertices interleave: ascending again.
  if (parts > 1) std::sort(sharp.begin(), sharp.end());
  // Vertices on clean creases count as jump 0 and stay out of their
  // neighbours' means.
  const std::vector<uint8_t> on_crease = clean_crease_vertices(mesh, topology, face, sharp);
  face = FaceNormals();
  if (!sharp.empty())
    parallel_for(nv, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v)
        if (on_crease[v]) valid[v] = 0;
    });
  // Each vertex's jump, where it has one, in a second sweep: the sums of
  // its valid neighbours' offsets.
  UninitialisedVector<double> jump(nv);
  UninitialisedVector<uint8_t> has_jump(nv);
  {
    UninitialisedVector<NeighbourSum<double>> around = filled_on_every_thread(nv, NeighbourSum<double>{0.0, 0});
    sweep_edges(
        topology, nv, parts,
        [&](size_t, uint32_t v, size_t first, size_t last, const auto& mine) {
          jump[v] = 0.0, has_jump[v] = on_crease[v] && !boundary[v];
          // An invalid vertex's offset is not added to its neighbours.
          if (!valid[v]) return;
          double sum = around[v].sum;
          uint32_t count = around[v].count;
          const double own = offset[v];
          for (size_t e = first; e < last; ++e) {
            if (e + kAhead < ne) {
              const uint32_t w = edges[e + kAhead][1];
              __builtin_prefetch(&offset[w]);
              __builtin_prefetch(&around[w], 1);
            }
            const uint32_t w = edges[e][1];
            if (valid[w]) sum += offset[w], ++count;
            if (mine(w)) around[w].sum += own, ++around[w].count;
          }
          if (count > 0) jump[v] = std::abs(own - sum / count), has_jump[v] = 1;
        },
        [&](uint32_t v, uint32_t w) {
          if (valid[v]) around[w].sum += offset[v], ++around[w].count;
        });
  }
  // Each component's jumps, in units of its own mean edge length (as
  // mean_edge_length measures it: over the triangles' sides, added in
  // triangle order; each edge measured once above, on every thread).
  // The sums on every thread, then each component's jumps in vertex order
  // (the median does not depend on it) grouped and their medians found: one
  // component's in place (the jumps are not read after), several as a copy;
  // detail::value_at_rank is nth_element's value in about one pass, on
  // every thread. (Until the twenty-first session of issue 14 the sums ran
  // serially beside the medians and outlasted them: ≈ 5 ms of the calling
  // thread alone at 1.1M triangles on 2 threads.)
  SideSums sums;
  std::vector<double> median(components, 0.0);
  std::vector<uint8_t> has_median(components, 0);
  const auto find_medians = [&] {
    std::vector<uint32_t> jump_start;
    UninitialisedVector<double> jumps;
    if (components == 1) {
      uint32_t count = 0;
      for (size_t v = 0; v < nv; ++v)
        if (has_jump[v]) jump[count++] = jump[v];
      jump_start = {0, count};
      jumps = std::move(jump);
    } else {
      detail::group_by_bucket(
          nv, components,
          [&](size_t v, const auto& emit) {
            if (has_jump[v]) emit(vertex_component[v], jump[v]);
          },
          jump_start, jumps);
    }
    for (size_t c = 0; c < components; ++c) {
      const auto first = jumps.begin() + jump_start[c], last = jumps.begin() + jump_start[c + 1];
      if (first == last) continue;
      const size_t count = static_cast<size_t>(last - first);
      median[c] = detail::value_at_rank(&*first, count, count / 2), has_median[c] = 1;
    }
  };
  sums = side_sums(mesh, topology, vertex_component, components, length.data());
  find_medians();
  length = UninitialisedVector<double>();
  std::vector<double> level(components, 0.0);
  for (size_t c = 0; c < components; ++c) {
    const double h = sums.triangles[c] ? sums.sum[c] / double(3 * sums.triangles[c]) : 0;
    if (has_median[c] && h > 0) level[c] = median[c] / h;
  }
  return level;
}

double surface_noise_level(const Mesh& mesh, const Topology& topology) {
  return surface_noise_levels(mesh, topology, std::vector<uint32_t>(mesh.positions.size(), 0), 1)[0];
}

int automatic_presmooth_steps(double noise_level) {
  if (!(noise_level > kNoisySurface)) return 0;
  if (!(noise_level > kVeryNoisySurface)) return kNoisySurfaceSteps;
  const double extra = std::ceil((noise_level - kVeryNoisySurface) / kNoisyStepLevel);
  return static_cast<int>(std::min<double>(kVeryNoisySurfaceSteps, kNoisySurfaceSteps + extra));
}

// Pre-smoothing's solves (solve_step_paired). The residual is relative to
// −tL x, what a step moves (step_system); the solver's entries are in float,
// so the residual in double stops near 1e-7 whatever its own; and rows of
// tiny triangles (the dragon's t Σw / m reaches 3·10⁵) turn a small residual
// into a large move. Largest vertex difference from a 10⁻¹² double solve
// (LDLᵀ), 3 steps, 1 thread, in mean edges: one solve to 1e-6 (the double
// residual ≈ 1e-6 too): dragon 7.4e-4, 1.1M bunny 8.1e-7, bunny 7.7e-7; to
// 1e-8, float-bound: dragon 8.5e-4. To kFirstTolerance, then refined in
// double to kTolerance: dragon 6.7e-7, 1.1M 1.2e-7, bunny 1.6e-8 (to 1e-9:
// 1.0e-6; to 1e-8: dragon 2.6e-4). Main's SpdSolver (1e-10 relative to M x):
// 1.2e-7, 1.6e-6, 3.9e-8.
constexpr double kFirstTolerance = 1e-6, kTolerance = 3e-10;
// Refinement passes allowed before SpdSolver takes over (one met kTolerance
// in every step above), and iterations a solve may take.
constexpr int kRefinements = 3;
constexpr int kPairedBudget = 150;
// A step's progress: kSetUpShare after its weights, rising towards
// kSolveStart through the solver's set-up, then after i iterations of its
// solves (all of them, counted on) kSolveStart + (1 − kSolveStart) · i / (i +
// kTypicalIterations): a step took 30–40 on the meshes above.
constexpr double kSetUpShare = 0.125, kSolveStart = 0.25, kTypicalIterations = 30;

// Solves the SPD system given by `triplets` for the three coordinates at once
// (one factorization or preconditioner), starting from and replacing x.
// after_axis, if set, is called after each coordinate's solve.
static void solve_positions(const Triplets& triplets, const Eigen::MatrixXd& rhs, std::vector<Vec3>& x,
                            const std::function<void(int axis)>& after_axis = {}) {
  const size_t nv = x.size();
  SparseMatrix system(nv, nv);
  system.setFromTriplets(triplets.begin(), triplets.end());
  SpdSolver solver;
  solver.compute(std::move(system));
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::VectorXd guess(nv);
    for (size_t v = 0; v < nv; ++v) guess[v] = x[v][axis];
    const Eigen::VectorXd solved = solver.solve(rhs.col(axis), guess);
    for (size_t v = 0; v < nv; ++v) x[v][axis] = solved[v];
    if (after_axis) after_axis(axis);
  }
}

// Each vertex's neighbours along the mesh boundary in edge order (none for
// interior vertices); empty for a closed mesh. Topology only: computed once.
// CSR, so a mesh with many boundary vertices costs two allocations, not one
// per vertex.
namespace {
struct BoundaryNeighbours {
  std::vector<uint32_t> offsets, neighbours;
  bool empty() const { return offsets.empty(); }
  uint32_t count(uint32_t v) const { return offsets[v + 1] - offsets[v]; }
  const uint32_t* begin(uint32_t v) const { return neighbours.data() + offsets[v]; }
  const uint32_t* end(uint32_t v) const { return neighbours.data() + offsets[v + 1]; }
};
}  // namespace

// A boundary edge is a side of one triangle: counted from triangle_edges,
// so that the triangle lists are not read (a caller may release them).
static BoundaryNeighbours boundary_neighbours(const Topology& topology, size_t nv) {
  BoundaryNeighbours along;
  std::vector<uint8_t> sides(topology.edges.size(), 0);
  for (const auto& edges : topology.triangle_edges)
    for (const uint32_t e : edges) sides[e] = static_cast<uint8_t>(std::min(sides[e] + 1, 2));
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    if (sides[e] != 1) continue;
    if (along.empty()) along.offsets.assign(nv + 1, 0);
    ++along.offsets[topology.edges[e][0] + 1], ++along.offsets[topology.edges[e][1] + 1];
  }
  if (along.empty()) return along;
  for (size_t v = 0; v < nv; ++v) along.offsets[v + 1] += along.offsets[v];
  along.neighbours.resize(along.offsets[nv]);
  std::vector<uint32_t> fill(along.offsets.begin(), along.offsets.end() - 1);
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    if (sides[e] != 1) continue;
    const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
    along.neighbours[fill[p]++] = q, along.neighbours[fill[q]++] = p;
  }
  return along;
}

// One implicit step of the 1-D Laplacian along the boundary curves,
// (M + tL) x' = M x with M the half lengths of the adjacent boundary edges and
// L the 1-D cotan Laplacian (weights 1 / edge length), solved over the free
// boundary vertices only. Corners and non-manifold boundary vertices are
// held, so corners do not round off and pull their sides inwards. See
// presmooth_surface for why.
static void smooth_boundary_curves(std::vector<Vec3>& x, const Mesh& mesh, const BoundaryNeighbours& along,
                                   const std::vector<uint8_t>& moving, double t, double h) {
  const size_t nv = x.size();
  // A corner is where the triangles' angles at a boundary vertex sum to less
  // than 135° (the boundary turns by more than 45° within the surface); the
  // angle sum, unlike the turn of the boundary polygon, ignores noise along
  // the normal.
  constexpr double kCornerAngleSum = 0.75 * kPi;
  std::vector<double> angle_sum(nv, 0.0);
  for (const Triangle& tri : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = tri[k];
      if (along.count(v) == 0) continue;
      const Vec3 a = x[tri[(k + 1) % 3]] - x[v], b = x[tri[(k + 2) % 3]] - x[v];
      angle_sum[v] += portable_angle(a.cross(b).norm(), a.dot(b));
    }
  // Boundary edges far shorter than the mean (a weld tolerance of 0 keeps
  // near-coincident vertices) would give weights t / length that overflow:
  // their ends are held.
  const double shortest = 1e-3 * h;
  std::vector<uint32_t> free_vertices, row(nv, kNone);  // row of each free vertex
  for (uint32_t v = 0; v < nv; ++v) {
    const bool has_length = along.count(v) == 2 && (x[v] - x[along.begin(v)[0]]).norm() > shortest &&
                            (x[v] - x[along.begin(v)[1]]).norm() > shortest;
    if (has_length && moving[v] && angle_sum[v] >= kCornerAngleSum)
      row[v] = static_cast<uint32_t>(free_vertices.size()), free_vertices.push_back(v);
  }
  if (free_vertices.empty()) return;
  // Row of a free vertex v: (m_v + Σ w) x'_v − Σ_free w x'_q = m_v x_v + Σ_held w x_q.
  const size_t n = free_vertices.size();
  Eigen::MatrixXd rhs(n, 3);
  Triplets triplets;
  std::vector<Vec3> y(n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t v = free_vertices[i];
    double mass = 0, diagonal = 0;
    Eigen::RowVector3d held = Eigen::RowVector3d::Zero();
    for (const uint32_t* neighbour = along.begin(v); neighbour != along.end(v); ++neighbour) {
      const uint32_t q = *neighbour;
      const double length = (x[v] - x[q]).norm(), w = t / length;
      mass += 0.5 * length, diagonal += w;
      if (row[q] != kNone)
        triplets.emplace_back(i, row[q], -w);
      else
        held += w * x[q].transpose();
    }
    triplets.emplace_back(i, i, mass + diagonal);
    rhs.row(i) = mass * x[v].transpose() + held;
    y[i] = x[v];
  }
  solve_positions(triplets, rhs, y);
  for (uint32_t i = 0; i < n; ++i) x[free_vertices[i]] = y[i];
}

// A step's system in displacements: x' = x + d with (M + tL) d = −tL x on
// the free rows and d = 0 on the held ones. The right side is the flow's pull
// Σ_q t w_pq (x_q − x_p), formed from differences in double: it does not see
// where the mesh lies, and the solve's relative residual is relative to what
// the step moves (presmooth.h). The solver holds its entries in float
// (paired_cg.h); that perturbs the operator, so it is applied to d, never to x.
namespace {
struct StepSystem {
  SignedPairMatrix matrix;  // M + tL over the free rows; a held row is an identity row
  std::vector<Vec3> rhs;    // −tL x on the free rows, 0 on the held ones
};
}  // namespace

// Whether edge e enters a step's system, and its weight t w_e: edges of
// weight 0 and those between two held vertices do not.
static bool coupled(const Topology& topology, const CotanWeights& cotan, const std::vector<uint8_t>& fixed, double t,
                    size_t e, double& w) {
  w = t * cotan.edge_weight[e];
  return w != 0 && !(fixed[topology.edges[e][0]] && fixed[topology.edges[e][1]]);
}

// In edge order on the calling thread (each row's sums in one order: the
// same bits for any thread count).
static StepSystem step_system(const std::vector<Vec3>& x, const Topology& topology, const CotanWeights& cotan,
                              const std::vector<uint8_t>& fixed, double t) {
  const size_t nv = x.size(), ne = topology.edges.size();
  StepSystem system;
  SignedPairMatrix& a = system.matrix;
  a.diagonal = cotan.vertex_mass;
  a.offsets.assign(nv + 1, 0);
  system.rhs.assign(nv, Vec3::Zero());
  for (size_t e = 0; e < ne; ++e) {
    double w;
    if (!coupled(topology, cotan, fixed, t, e, w)) continue;
    const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
    a.diagonal[p] += w;
    a.diagonal[q] += w;
    const Vec3 pull = w * (x[q] - x[p]);
    if (!fixed[p]) system.rhs[p] += pull;
    if (!fixed[q]) system.rhs[q] -= pull;
    if (!fixed[p] && !fixed[q]) ++a.offsets[p + 1], ++a.offsets[q + 1];
  }
  for (size_t v = 0; v < nv; ++v) {
    if (fixed[v]) a.diagonal[v] = 1;
    a.offsets[v + 1] += a.offsets[v];
  }
  a.columns.resize(a.offsets[nv]);
  a.weights.resize(a.offsets[nv]);
  std::vector<uint32_t> fill(a.offsets.begin(), a.offsets.end() - 1);
  for (size_t e = 0; e < ne; ++e) {
    double w;
    const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
    if (!coupled(topology, cotan, fixed, t, e, w) || fixed[p] || fixed[q]) continue;
    a.columns[fill[p]] = q, a.weights[fill[p]++] = -w;  // no sign bits: both fields alike
    a.columns[fill[q]] = p, a.weights[fill[q]++] = -w;
  }
  return system;
}

// out = A d for a step's matrix A (step_system), in double, in edge order.
static void step_product(const Topology& topology, const CotanWeights& cotan, const std::vector<uint8_t>& fixed,
                         double t, const std::vector<Vec3>& d, std::vector<Vec3>& out) {
  for (size_t v = 0; v < d.size(); ++v) out[v] = fixed[v] ? d[v] : Vec3(cotan.vertex_mass[v] * d[v]);
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    double w;
    if (!coupled(topology, cotan, fixed, t, e, w)) continue;
    const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
    const Vec3 pull = w * (d[p] - d[q]);
    if (!fixed[p]) out[p] += pull;
    if (!fixed[q]) out[q] -= pull;
  }
}

// Solves a step's system with SignedPairSolver and adds the displacements
// to x; false, with x untouched, if a solve does not converge within
// kPairedBudget, a coordinate is not within kTolerance after kRefinements
// refinements, or the system is not one the solver takes. product(d, out)
// sets out = A d in double. report(within) gets the fractions of the step,
// rising from kSetUpShare.
//
// Each coordinate is solved to kFirstTolerance, then refined from its
// residual in double until within kTolerance (one refinement on every mesh
// measured); the solves are queued by coordinate and taken two at a time,
// (x, y), (z, x's refinement), (y's, z's): three solves of the pair, no lane
// idle, where (x, y), (z, nothing) and the two refinements took four
// (dragon, 3 steps, kTolerance 1e-9: 136 → 115 iterations).
static bool solve_step_paired(StepSystem& system, std::vector<Vec3>& x,
                              const std::function<void(const std::vector<Vec3>&, std::vector<Vec3>&)>& product,
                              const std::function<void(double)>& report) {
  const size_t nv = x.size();
  if (nv > SignedPairMatrix::kColumnMask) return false;
  for (const double d : system.matrix.diagonal)
    if (!(d > 0) || !std::isfinite(d)) return false;  // the fallback throws as SpdSolver does
  double setup = kSetUpShare;
  const auto pause = [&] {
    setup = 0.5 * (setup + kSolveStart);
    report(setup);
  };
  const SignedPairSolver solver(std::move(system.matrix), true, pause);
  Vec3 rhs_norm2 = Vec3::Zero();
  for (const Vec3& b : system.rhs) rhs_norm2 += b.cwiseAbs2();
  std::vector<double> b(2 * nv), solved(2 * nv);
  std::vector<Vec3> d(nv, Vec3::Zero()), r = system.rhs;
  // The coordinates still to solve, in order, each with the relative
  // residual it needs (kFirstTolerance from 0) and its solves so far.
  std::vector<int> queue = {0, 1, 2};
  double need[3] = {kFirstTolerance, kFirstTolerance, kFirstTolerance};
  int solves[3] = {0, 0, 0};
  int iterations = 0;  // in the step, for the progress
  while (!queue.empty()) {
    const int first = queue[0], second = queue.size() > 1 ? queue[1] : -1;
    queue.erase(queue.begin(), queue.begin() + (second < 0 ? 1 : 2));
    parallel_for(nv, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) b[2 * v] = r[v][first], b[2 * v + 1] = second < 0 ? 0.0 : r[v][second];
    });
    std::fill(solved.begin(), solved.end(), 0.0);
    const int before = iterations;
    const double tolerance = second < 0 ? need[first] : std::min(need[first], need[second]);
    if (!solver.solve(b, solved, tolerance, kPairedBudget, [&](int i) {
          iterations = before + i;
          report(kSolveStart + (1 - kSolveStart) * iterations / (iterations + kTypicalIterations));
        }))
      return false;
    parallel_for(nv, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) {
        d[v][first] += solved[2 * v];
        if (second >= 0) d[v][second] += solved[2 * v + 1];
      }
    });
    product(d, r);
    Vec3 r_norm2 = Vec3::Zero();
    for (size_t v = 0; v < nv; ++v) r[v] = system.rhs[v] - r[v], r_norm2 += r[v].cwiseAbs2();
    for (const int k : {first, second}) {
      if (k < 0 || !(r_norm2[k] > kTolerance * kTolerance * rhs_norm2[k])) continue;
      if (++solves[k] > kRefinements) return false;
      need[k] = std::min(0.5, kTolerance / std::sqrt(r_norm2[k] / rhs_norm2[k]));
      queue.push_back(k);
    }
  }
  parallel_for(nv, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) x[v] += d[v];
  });
  return true;
}

// The same system with SpdSolver (CG, then a factorization): where the pair
// does not converge.
static void solve_step_fallback(const StepSystem& system, std::vector<Vec3>& x) {
  const SignedPairMatrix& a = system.matrix;
  const size_t nv = x.size();
  Triplets triplets;
  triplets.reserve(nv + a.columns.size());
  Eigen::MatrixXd rhs(nv, 3);
  for (size_t v = 0; v < nv; ++v) {
    for (uint32_t k = a.offsets[v]; k < a.offsets[v + 1]; ++k) triplets.emplace_back(v, a.columns[k], a.weights[k]);
    triplets.emplace_back(v, v, a.diagonal[v]);
    rhs.row(v) = system.rhs[v].transpose();
  }
  std::vector<Vec3> d(nv, Vec3::Zero());
  solve_positions(triplets, rhs, d);
  for (size_t v = 0; v < nv; ++v) x[v] += d[v];
}

std::vector<Vec3> presmooth_surface(const Mesh& mesh, const Topology& topology, const PresmoothOptions& options) {
  const int steps = options.steps ? *options.steps : automatic_presmooth_steps(surface_noise_level(mesh, topology));
  return presmooth_surface(mesh, topology, options.time_step, std::vector<int>(mesh.positions.size(), steps));
}

std::vector<Vec3> presmooth_surface(const Mesh& mesh, const Topology& topology, double time_step,
                                    const std::vector<int>& vertex_steps, const std::function<void(double)>& progress) {
  std::vector<Vec3> x = mesh.positions;
  const int steps = vertex_steps.empty() ? 0 : *std::max_element(vertex_steps.begin(), vertex_steps.end());
  if (steps <= 0 || time_step <= 0) return x;
  const size_t nv = x.size();
  const double h = mean_edge_length(mesh);
  const double t = time_step * h * h;
  const BoundaryNeighbours along = boundary_neighbours(topology, nv);
  std::vector<uint8_t> fixed(nv), moving(nv);

  for (int step = 0; step < steps; ++step) {
    // Vertices whose steps are done are held like boundary ones.
    for (size_t v = 0; v < nv; ++v) {
      moving[v] = vertex_steps[v] > step;
      fixed[v] = topology.boundary_vertex[v] || !moving[v];
    }
    // Fractions of the step: kSetUpShare after the boundary curves and the
    // weights, then the solver's set-up and iterations (solve_step_paired).
    const auto report = [&](double within) {
      if (progress) progress((step + within) / steps);
    };
    if (!along.empty()) smooth_boundary_curves(x, mesh, along, moving, t, h);
    // Weights from the current surface: mean-curvature flow, linearised per step.
    const CotanWeights cotan = cotan_weights(x, mesh, topology);
    report(kSetUpShare);
    // (M + tL) x' = M x on interior vertices, in displacements; boundary
    // ones (just smoothed along their curve) are held and move to the right side.
    StepSystem system = step_system(x, topology, cotan, fixed, t);
    const auto product = [&](const std::vector<Vec3>& d, std::vector<Vec3>& out) {
      step_product(topology, cotan, fixed, t, d, out);
    };
    if (!solve_step_paired(system, x, product, [&](double within) { report(within); })) {
      system = step_system(x, topology, cotan, fixed, t);
      solve_step_fallback(system, x);
    }
  }
  return x;
}

}  // namespace crestline
