#include "crestline/lines/trace.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "crestline/curvature/shape_operator.h"
#include "crestline/numerics/parallel.h"

namespace crestline {
namespace {

// Where κ is constant along its own lines (sphere, cylinder, torus) e
// vanishes identically and its zero set is round-off. Conditions (5), (6) are
// therefore made strict: the slope of e across the line must exceed this
// fraction of |κ|³ (both in 1/length³, so the test is scale-free). Genuine
// crests have a ratio of order 1 and more; round-off is below 1e-12.
constexpr double kStrictExtremum = 1e-6;
// Condition (6) with a margin: near umbilics (|κ_max| ≈ |κ_min|, e.g. a
// whole sphere) the principal directions, and so the zero set of e, are
// decided by noise; a feature line needs its own curvature to dominate by
// this factor. 1.1 removes every line from the icosphere of
// smooth/sphere.obj (float coordinates) and leaves the quality harness's
// case counts and the feline's lines as they were.
constexpr double kDominance = 1.1;

// Zero is treated as a tiny positive value so that sign flips stay exact and
// every edge crossing is decided the same way from both of its triangles.
double nonzero(double v) { return v != 0 ? v : std::numeric_limits<double>::denorm_min(); }

struct Field {
  LineType type;
  const std::vector<double>& e;
  const std::vector<Direction>& dir;
  const std::vector<double>& kappa_own;    // κ_max for ridges
  const std::vector<double>& kappa_other;  // κ_min for ridges
  const std::vector<uint8_t>& regular;
};

// The zero of e on edge `edge`, from its lower-index end with the other end's
// sign made consistent by σ = sign⟨κ⃗(u), κ⃗(v)⟩; shared by both triangles.
// Node `node` gets its place, curvature and parameter (numbered before, in
// the order of the segments, by node_on).
void place_crossing(FeatureGraph& graph, const Mesh& mesh, const Topology& topology, const Field& field,
                    uint32_t node) {
  const uint32_t edge = graph.source[node];
  const uint32_t u = topology.edges[edge][0], v = topology.edges[edge][1];
  const double sigma = direction_sign(field.dir[u], field.dir[v]);
  const double a = nonzero(field.e[u]), b = sigma * nonzero(field.e[v]);
  const double t = a / (a - b);
  graph.points[node] = (1 - t) * mesh.positions[u] + t * mesh.positions[v];
  graph.curvature[node] = std::abs((1 - t) * field.kappa_own[u] + t * field.kappa_own[v]);
  graph.edge_parameter[node] = t;
  graph.trisector[node] = 0;
}

// The node on edge `edge`, numbered when first asked for.
uint32_t node_on(FeatureGraph& graph, uint32_t edge) {
  uint32_t& node = graph.edge_node[edge];
  if (node == kNone) node = static_cast<uint32_t>(graph.source.size()), graph.source.push_back(edge);
  return node;
}

// Triangles between two progress reports.
constexpr uint32_t kProgressStride = 1u << 15;

// Bit k set where corner k's consistently signed value s_k · nonzero(e_k)
// is positive: e_k ≥ 0 where s_k = 1 (nonzero makes ±0 positive), e_k < 0
// where s_k = −1, and neither for NaN. `code`'s bits 1 and 2 are s_1, s_2 < 0.
inline unsigned positive_corners(const double* e, const Triangle& f, uint8_t code) {
  const double e0 = e[f[0]], e1 = e[f[1]], e2 = e[f[2]];
  return unsigned(e0 >= 0) | unsigned(code & 2u ? e1 < 0 : e1 >= 0) << 1 | unsigned(code & 4u ? e2 < 0 : e2 >= 0) << 2;
}

// segment_edges for a triangle whose line crosses edges first < second.
uint8_t crossing_segment(const Mesh& mesh, const Field& field, uint32_t t, uint8_t code, int first, int second) {
  const std::vector<Vec3>& x = mesh.positions;
  const Triangle& f = mesh.triangles[t];
  const std::array<double, 3> s = code_signs(code);
  const double v[3] = {s[0] * nonzero(field.e[f[0]]), s[1] * nonzero(field.e[f[1]]), s[2] * nonzero(field.e[f[2]])};

  // Conditions (5) and (6) on the consistently signed linear function.
  const Vec3 normal = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
  const double twice_area = normal.norm();
  if (!(twice_area > 0)) return 0;
  // ∇e = Σ_k v_k N × (opposite edge) / (2 area)² with N the unnormalised
  // normal: one cross product and one division for the three corners.
  Vec3 opposite_sum = Vec3::Zero(), direction = Vec3::Zero();
  double own = 0, other = 0;
  for (int k = 0; k < 3; ++k) {
    opposite_sum += v[k] * (x[f[(k + 2) % 3]] - x[f[(k + 1) % 3]]);
    direction += s[k] * widen(field.dir[f[k]]);
    own += field.kappa_own[f[k]];
    other += field.kappa_other[f[k]];
  }
  const Vec3 gradient = normal.cross(opposite_sum) / (twice_area * twice_area);
  const double slope = gradient.dot(direction);
  const bool extremum = field.type == LineType::Ridge ? slope < 0 : slope > 0;
  if (!extremum || !(std::abs(own) > kDominance * std::abs(other))) return 0;
  const double mean_own = own / 3;
  if (!(std::abs(slope) > kStrictExtremum * direction.norm() * std::abs(mean_own * mean_own * mean_own))) return 0;
  return static_cast<uint8_t>(1 + first + 3 * second);
}

// The edges (k, k + 1) of triangle t that carry a segment of the field's
// line, as 1 + first + 3 · second (first < second); 0 where there is none.
// `code`: the triangle's regularity_code (nonzero), whose signs (code_signs)
// are Definition 1's consistent choice for the field's directions. The signs
// alone decide most triangles (no crossing); a crossing edge is one whose
// ends' signs differ, and a triangle has none or two. `positive`:
// positive_corners', neither 0 nor 7.
inline uint8_t segment_edges(const Mesh& mesh, const Field& field, uint32_t t, uint8_t code, unsigned positive) {
  // Edge k crosses where bits k and k + 1 (mod 3) differ.
  const unsigned crossing = (positive ^ (positive >> 1 | positive << 2)) & 7;
  const int first = crossing & 1 ? 0 : 1, second = crossing & 4 ? 2 : 1;
  return crossing_segment(mesh, field, t, code, first, second);
}

// The segments of the triangles [begin, begin + count) from their codes,
// with their crossing nodes numbered in triangle order. Eight codes at a
// time: most are 0 (no segment), and runs of them are skipped whole.
void make_segments(const Topology& topology, const std::vector<uint8_t>& code, uint32_t begin, uint32_t count,
                   FeatureGraph& graph) {
  auto word = [&code](uint32_t i) {
    uint64_t w;
    std::memcpy(&w, code.data() + i, sizeof w);
    return w;
  };
  for (uint32_t i = 0; i < count; i += 8) {
    // The crossed edges' nodes lie anywhere in edge_node: those of the
    // triangles kAhead on are asked for now (natively).
    constexpr uint32_t kAhead = 16;
    if (i + kAhead + 8 <= count)
      for (uint64_t w = word(i + kAhead); w;) {
        const unsigned byte = unsigned(__builtin_ctzll(w)) / 8;
        for (uint32_t edge : topology.triangle_edges[begin + i + kAhead + byte])
          __builtin_prefetch(&graph.edge_node[edge]);
        w &= ~(0xffull << (8 * byte));
      }
    if (i + 8 <= count && word(i) == 0) continue;
    for (uint32_t j = i; j < std::min(count, i + 8); ++j) {
      if (!code[j]) continue;
      const uint32_t t = begin + j;
      const int edges = code[j] - 1;
      const uint32_t a = node_on(graph, topology.triangle_edges[t][edges % 3]);
      const uint32_t b = node_on(graph, topology.triangle_edges[t][edges / 3]);
      graph.segments.push_back({a, b});
    }
  }
}

// Places the nodes from `first` on (place_crossing). Each node's edge and
// its ends' values lie anywhere in their arrays: asked for 2 kAhead and
// kAhead nodes on (natively).
void place_crossings(const Mesh& mesh, const Topology& topology, const Field& field, size_t first,
                     FeatureGraph& graph) {
  const size_t nodes = graph.source.size();
  graph.points.resize(nodes), graph.curvature.resize(nodes);
  graph.edge_parameter.resize(nodes), graph.trisector.resize(nodes);
  parallel_for(nodes - first, [&](size_t begin, size_t end) {
    constexpr size_t kAhead = 8;
    for (size_t i = begin; i < end; ++i) {
      if (i + 2 * kAhead < end) __builtin_prefetch(&topology.edges[graph.source[first + i + 2 * kAhead]]);
      if (i + kAhead < end)
        for (uint32_t v : topology.edges[graph.source[first + i + kAhead]]) {
          __builtin_prefetch(&mesh.positions[v]);
          __builtin_prefetch(&field.e[v]);
          __builtin_prefetch(&field.dir[v]);
          __builtin_prefetch(&field.kappa_own[v]);
        }
      place_crossing(graph, mesh, topology, field, uint32_t(first + i));
    }
  });
}

// Both fields (ridges, valleys) in one pass over the triangles, each into
// its graph: the triangles, their exclusion and the loop are read once for
// both (1.1M triangles, 1 thread: trace_regular_triangles 389.7 -> 369.2 M
// instructions against a pass per field). The tests run on every thread,
// block by block; the segments and their crossing nodes' numbers are then
// made in triangle order on the calling thread, each graph's apart, and the
// nodes placed on every thread: the graphs are the same for any number of
// threads, and as a pass per field makes them.
void trace_fields(const Mesh& mesh, const Topology& topology, const Field (&fields)[2],
                  const std::vector<uint8_t>& excluded, const std::function<void(double)>& progress,
                  FeatureGraph* (&graphs)[2]) {
  size_t first[2];  // the first node made here
  for (int k = 0; k < 2; ++k) {
    graphs[k]->type = fields[k].type;
    graphs[k]->edge_node.assign(topology.edges.size(), kNone);
    first[k] = graphs[k]->source.size();
  }
  const uint32_t nt = static_cast<uint32_t>(mesh.triangles.size());
  std::vector<uint8_t> code[2];
  for (auto& c : code) c.resize(std::min<uint32_t>(nt, kProgressStride));
  for (uint32_t begin = 0; begin < nt; begin += kProgressStride) {
    if (progress && begin > 0) progress(double(begin) / nt);
    const uint32_t end = std::min(nt, begin + kProgressStride);
    // The arrays by address: a byte store may alias anything, so the
    // vectors' data would be reloaded after each.
    // In two passes: the signs of every triangle, then the crossing ones'
    // tests. The corners' values lie anywhere in their arrays: those kAhead
    // triangles (crossings) on are asked for while these are tested
    // (natively; WASM has no prefetch). In the loops: GCC drops a lambda
    // made only of prefetches.
    parallel_for(end - begin, [&, tris = mesh.triangles.data(), skip = excluded.data(), x = mesh.positions.data(),
                               e_max = fields[0].e.data(), e_min = fields[1].e.data(),
                               regular_max = fields[0].regular.data(), regular_min = fields[1].regular.data(),
                               out_max = code[0].data(), out_min = code[1].data()](size_t first, size_t last) {
      constexpr size_t kAhead = 8;
      // (i << 3 | positive) of the triangles whose signs differ, per field:
      // each thread's lists, kept for its next piece (1.1M triangles, 1
      // thread: 2.9 M instructions less, 1.5 M for a list reserved per
      // piece).
      thread_local std::vector<uint32_t> crossings[2];
      crossings[0].clear(), crossings[1].clear();
      const auto note_crossing = [tris](std::vector<uint32_t>& list, const double* e, uint8_t c, size_t i, uint32_t t) {
        if (c == 0) return;
        const unsigned positive = positive_corners(e, tris[t], c);
        if (positive != 0 && positive != 7) list.push_back(static_cast<uint32_t>(i) << 3 | positive);
      };
      for (size_t i = first; i < last; ++i) {
        const uint32_t t = begin + static_cast<uint32_t>(i);
        if (i + kAhead < last)
          for (uint32_t v : tris[t + kAhead]) __builtin_prefetch(&e_max[v]), __builtin_prefetch(&e_min[v]);
        out_max[i] = out_min[i] = 0;
        if (skip[t]) continue;
        note_crossing(crossings[0], e_max, regular_max[t], i, t);
        note_crossing(crossings[1], e_min, regular_min[t], i, t);
      }
      for (int k = 0; k < 2; ++k) {
        const Field& field = fields[k];
        const std::vector<uint32_t>& list = crossings[k];
        uint8_t* out = k == 0 ? out_max : out_min;
        const uint8_t* regular = field.regular.data();
        const Direction* dir = field.dir.data();
        const double *own = field.kappa_own.data(), *other = field.kappa_other.data();
        for (size_t j = 0; j < list.size(); ++j) {
          if (j + kAhead < list.size())
            for (uint32_t v : tris[begin + (list[j + kAhead] >> 3)]) {
              __builtin_prefetch(&x[v]);
              __builtin_prefetch(&dir[v]);
              __builtin_prefetch(&own[v]);
              __builtin_prefetch(&other[v]);
            }
          const uint32_t i = list[j] >> 3, t = begin + i;
          out[i] = segment_edges(mesh, field, t, regular[t], list[j] & 7);
        }
      }
    });
    for (int k = 0; k < 2; ++k) make_segments(topology, code[k], begin, end - begin, *graphs[k]);
  }
  for (int k = 0; k < 2; ++k) place_crossings(mesh, topology, fields[k], first[k], *graphs[k]);
}

}  // namespace

const char* line_type_name(LineType type) {
  return type == LineType::Ridge ? "ridge" : type == LineType::Valley ? "valley" : "crease";
}

void place_nodes_on(FeatureGraph& graph, const Mesh& mesh, const std::vector<std::array<uint32_t, 2>>& edges) {
  const std::vector<Vec3>& x = mesh.positions;
  for (size_t i = 0; i < graph.points.size(); ++i) {
    if (graph.trisector[i]) {
      const Triangle& f = mesh.triangles[graph.source[i]];
      graph.points[i] = (x[f[0]] + x[f[1]] + x[f[2]]) / 3.0;
    } else {
      const auto& e = edges[graph.source[i]];
      const double t = graph.edge_parameter[i];
      graph.points[i] = (1 - t) * x[e[0]] + t * x[e[1]];
    }
  }
}

TraceResult trace_regular_triangles(const Mesh& mesh, const Topology& topology, const Curvature& curvature,
                                    const Extremality& extremality, const Regularity& regularity,
                                    const TraceOptions& options, const std::function<void(double)>& progress) {
  TraceResult out;
  const uint32_t rings = options.boundary_rings > 0 ? static_cast<uint32_t>(options.boundary_rings) : 0;
  const std::vector<uint32_t> distance = boundary_ring_distance(mesh, topology, rings);
  out.excluded.resize(mesh.triangles.size());
  parallel_for(mesh.triangles.size(), [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const Triangle& f = mesh.triangles[t];
      out.excluded[t] = distance[f[0]] < rings || distance[f[1]] < rings || distance[f[2]] < rings;
    }
  });

  const Field fields[2] = {{LineType::Ridge, extremality.e_max, curvature.dir_max, curvature.kappa_max,
                            curvature.kappa_min, regularity.regular_max},
                           {LineType::Valley, extremality.e_min, curvature.dir_min, curvature.kappa_min,
                            curvature.kappa_max, regularity.regular_min}};
  FeatureGraph* graphs[2] = {&out.ridges, &out.valleys};
  trace_fields(mesh, topology, fields, out.excluded, progress, graphs);
  return out;
}

}  // namespace crestline
