#pragma once
// Paper Table 1, step 1 (optional): smooth the surface before computing
// curvature, by implicit cotan (mean-curvature) flow [DMSB99].
#include <vector>

#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"

namespace crestline {

struct PresmoothOptions {
  /// Implicit flow steps; 0 leaves the surface untouched. Negative:
  /// automatic, see automatic_presmooth_steps.
  int steps = -1;
  /// Time step per step, in units of mean edge length squared (unitless).
  double time_step = 1.0;
};

/// How rough the surface is at the scale of its edges: the median over
/// interior vertices of |⟨N_v, x_v − mean of its neighbours⟩|, in units of
/// mean edge length. Clean meshes measure 0.002–0.04 (CAD, analytic,
/// scans like the feline), normal noise of σ = 0.1 edge about 0.075.
double surface_noise_level(const Mesh& mesh, const Topology& topology);

/// Above this noise level the automatic choice pre-smooths.
constexpr double kNoisySurface = 0.06;
/// Steps the automatic choice takes on a noisy surface: on tests/quality,
/// 2 steps left the paraboloid and cosine product short of the targets at
/// σ = 0.25 edge, 3 met them at σ = 0.1 and 0.25, 4 began to flatten the
/// cosine product's weakest segments.
constexpr int kNoisySurfaceSteps = 3;

/// 0 for a clean surface, kNoisySurfaceSteps when the noise level
/// (surface_noise_level) exceeds kNoisySurface: noise of a tenth of an edge already randomises the
/// principal directions, which extremality smoothing cannot repair, while on
/// clean meshes pre-smoothing only erases fine features.
int automatic_presmooth_steps(double noise_level);

/// Returns the smoothed vertex positions (same connectivity). Boundary
/// vertices are smoothed along their boundary curve only (1-D implicit
/// Laplacian, same time step), so open meshes do not shrink inwards, yet a
/// noisy boundary does not pin its noise into a band along it (the lines of
/// tests/quality broke 4–6 edges from the boundary when it was held fixed).
std::vector<Vec3> presmooth_surface(const Mesh& mesh, const Topology& topology, const PresmoothOptions& options);

}  // namespace crestline
