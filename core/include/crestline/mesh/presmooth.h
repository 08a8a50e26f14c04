#pragma once
// Paper Table 1, step 1 (optional): smooth the surface before computing
// curvature, by implicit cotan (mean-curvature) flow [DMSB99].
#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"

namespace crestline {

struct PresmoothOptions {
  /// Implicit flow steps; 0 leaves the surface untouched.
  int steps = 0;
  /// Time step per step, in units of mean edge length squared (unitless).
  double time_step = 1.0;
};

/// Returns the smoothed vertex positions (same connectivity). Boundary
/// vertices stay fixed so open meshes do not shrink inwards.
std::vector<Vec3> presmooth_surface(const Mesh& mesh, const Topology& topology,
                                    const PresmoothOptions& options);

}  // namespace crestline
