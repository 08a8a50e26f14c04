#include "crestline/lines/singular.h"

#include <cstdint>
#include <vector>

namespace crestline {
namespace {

// The field's singular triangles (not excluded), ascending: a scan of two
// byte arrays, eight triangles at a time where all are regular (nearly all).
std::vector<uint32_t> singular_triangles(const std::vector<uint8_t>& regular, const std::vector<uint8_t>& excluded) {
  std::vector<uint32_t> out;
  const auto is_singular = [&](size_t t) { return regular[t] == 0 && excluded[t] == 0; };
  const size_t nt = regular.size();
  size_t t = 0;
  for (; t + 8 <= nt; t += 8) {
    uint64_t word = 0;
    for (size_t k = 0; k < 8; ++k) word |= uint64_t(is_singular(t + k)) << (8 * k);
    if (word == 0) continue;
    for (size_t k = t; k < t + 8; ++k)
      if (is_singular(k)) out.push_back(static_cast<uint32_t>(k));
  }
  for (; t < nt; ++t)
    if (is_singular(t)) out.push_back(static_cast<uint32_t>(t));
  return out;
}

SingularTriangleCounts connect_field(const Mesh& mesh, const Topology& topology, const std::vector<uint8_t>& regular,
                                     const std::vector<uint8_t>& excluded, FeatureGraph& graph) {
  SingularTriangleCounts counts;
  const std::vector<uint32_t> singular = singular_triangles(regular, excluded);
  for (size_t i = 0; i < singular.size(); ++i) {
    // The triangles' edges and those edges' nodes lie anywhere in their
    // arrays: asked for 2 kAhead and kAhead singular triangles on (natively;
    // WASM has no prefetch).
    constexpr size_t kAhead = 8;
    if (i + 2 * kAhead < singular.size()) __builtin_prefetch(&topology.triangle_edges[singular[i + 2 * kAhead]]);
    if (i + kAhead < singular.size())
      for (uint32_t e : topology.triangle_edges[singular[i + kAhead]]) __builtin_prefetch(&graph.edge_node[e]);
    const uint32_t t = singular[i];
    // A singular triangle draws nothing itself, so a node on one of its
    // edges was put there by a feature segment of the regular neighbour.
    uint32_t marked[3], n = 0;
    for (uint32_t e : topology.triangle_edges[t])
      if (graph.edge_node[e] != kNone) marked[n++] = graph.edge_node[e];
    if (n == 2) {
      graph.segments.push_back({marked[0], marked[1]});
      ++counts.connected;
    } else if (n == 3) {
      const Triangle& f = mesh.triangles[t];
      const uint32_t centre = static_cast<uint32_t>(graph.points.size());
      graph.points.push_back((mesh.positions[f[0]] + mesh.positions[f[1]] + mesh.positions[f[2]]) / 3.0);
      graph.curvature.push_back((graph.curvature[marked[0]] + graph.curvature[marked[1]] + graph.curvature[marked[2]]) /
                                3.0);
      graph.source.push_back(t);
      graph.edge_parameter.push_back(0);
      graph.trisector.push_back(1);
      for (uint32_t m : marked) graph.segments.push_back({m, centre});
      ++counts.trisectors;
    } else if (n == 1) {
      ++counts.endings;
    }
  }
  return counts;
}

}  // namespace

SingularResult connect_singular_triangles(const Mesh& mesh, const Topology& topology, const Regularity& regularity,
                                          TraceResult traced) {
  SingularResult out;
  out.lines = std::move(traced);
  out.ridges = connect_field(mesh, topology, regularity.regular_max, out.lines.excluded, out.lines.ridges);
  out.valleys = connect_field(mesh, topology, regularity.regular_min, out.lines.excluded, out.lines.valleys);
  return out;
}

}  // namespace crestline
