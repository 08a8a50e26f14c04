#pragma once
// Paper §4.1: feature line segments in regular triangles.
#include <functional>

#include "crestline/curvature/extremality.h"
#include "crestline/curvature/regularity.h"
#include "crestline/lines/feature_graph.h"

namespace crestline {

struct TraceOptions {
  /// Triangles within this many vertex rings of the mesh boundary are not
  /// traced: curvature there sees only half a neighbourhood and would draw
  /// artefact lines along every boundary.
  int boundary_rings = 2;
};

struct TraceResult {
  FeatureGraph ridges;   // zero set of e_max with conditions (5) and (6)
  FeatureGraph valleys;  // zero set of e_min with the mirrored conditions
  /// Triangles left out near the boundary (see TraceOptions::boundary_rings).
  std::vector<uint8_t> excluded;
};

TraceResult trace_regular_triangles(const Mesh& mesh, const Topology& topology, const Curvature& curvature,
                                    const Extremality& extremality, const Regularity& regularity,
                                    const TraceOptions& options,
                                    const std::function<void(double fraction)>& progress = {});

}  // namespace crestline
