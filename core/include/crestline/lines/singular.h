#pragma once
// Paper §4.2: closing the lines through singular triangles.
#include "crestline/curvature/regularity.h"
#include "crestline/lines/trace.h"

namespace crestline {

struct SingularTriangleCounts {
  size_t connected = 0;   // regular case: 2 marked edges joined
  size_t trisectors = 0;  // 3 marked edges joined at the barycentre
  size_t endings = 0;     // start/end case: 1 marked edge, nothing drawn
};

struct SingularResult {
  TraceResult lines;  // the input graphs with the singular-triangle segments added
  SingularTriangleCounts ridges;
  SingularTriangleCounts valleys;
};

SingularResult connect_singular_triangles(const Mesh& mesh, const Topology& topology, const Regularity& regularity,
                                          TraceResult traced);

}  // namespace crestline
