#pragma once
// Joining segments into connected polylines with a strength (OBS04).
#include <vector>

#include "crestline/lines/feature_graph.h"
#include "crestline/mesh/topology.h"

namespace crestline {

struct Polyline {
  LineType type = LineType::Ridge;
  std::vector<Vec3> points;
  std::vector<double> curvature;  // |κ| per point, pointwise (1/length)
  bool closed = false;            // last point connects back to the first (not repeated)
  /// ∫|κ| ds along the line, trapezoidal [OBS04]: unitless, so independent of scale.
  double strength = 0;
  double length = 0;
  /// Creases only: the dihedral angle is positive (convex, an outer edge).
  bool convex = false;
};

/// Walks the graph into maximal chains: they end at nodes of degree ≠ 2
/// (line ends and trisector junctions); cycles become closed polylines.
std::vector<Polyline> join_polylines(const FeatureGraph& graph);

/// The polylines stage (Table 1 after the singular triangles): ridges, then
/// valleys, each joined per connected component, with the component of each
/// line.
struct PolylinesInput {
  /// When given, every node first moves to the same place on this mesh (same
  /// connectivity as the traced one, see place_nodes_on): lines traced on a
  /// pre-smoothed surface are drawn on the input.
  const Mesh* place_on = nullptr;
  /// Component of each vertex (empty: one component). Segments never leave
  /// a component; joining per component bridges gaps only within one and
  /// measures them in that component's segment length.
  const std::vector<uint32_t>* vertex_component = nullptr;
  size_t components = 1;
};
struct PolylinesResult {
  std::vector<Polyline> lines;      // ridges first, then valleys
  std::vector<uint32_t> component;  // of each line
};
PolylinesResult build_polylines(const FeatureGraph& ridges, const FeatureGraph& valleys, const Mesh& mesh,
                                const Topology& topology, const PolylinesInput& input);

/// Recomputes length and strength from points and curvature.
void measure_polyline(Polyline& line);

}  // namespace crestline
