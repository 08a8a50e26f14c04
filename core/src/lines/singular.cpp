#include "crestline/lines/singular.h"

namespace crestline {
namespace {

SingularTriangleCounts connect_field(const Mesh& mesh, const Topology& topology, const std::vector<uint8_t>& regular,
                                     const std::vector<uint8_t>& excluded, FeatureGraph& graph) {
  SingularTriangleCounts counts;
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    if (regular[t] || excluded[t]) continue;
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
