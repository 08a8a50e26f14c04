#pragma once
// Joining segments into connected polylines with a strength (OBS04).
#include <vector>

#include "crestline/lines/feature_graph.h"

namespace crestline {

struct Polyline {
  LineType type = LineType::Ridge;
  std::vector<Vec3> points;
  std::vector<double> curvature;  // |κ| per point, pointwise (1/length)
  bool closed = false;            // last point connects back to the first (not repeated)
  /// ∫|κ| ds along the line, trapezoidal [OBS04]: unitless, so independent of scale.
  double strength = 0;
  double length = 0;
};

/// Walks the graph into maximal chains: they end at nodes of degree ≠ 2
/// (line ends and trisector junctions); cycles become closed polylines.
std::vector<Polyline> join_polylines(const FeatureGraph& graph);

/// Recomputes length and strength from points and curvature.
void measure_polyline(Polyline& line);

}  // namespace crestline
