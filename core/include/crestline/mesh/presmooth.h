#pragma once
// Paper Table 1, step 1 (optional): smooth the surface before computing
// curvature, by implicit cotan (mean-curvature) flow [DMSB99].
#include <functional>
#include <optional>
#include <vector>

#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"

namespace crestline {

struct PresmoothOptions {
  /// Implicit flow steps; 0 leaves the surface untouched. std::nullopt:
  /// automatic, see automatic_presmooth_steps.
  std::optional<int> steps;
  /// Time step per step, in units of mean edge length squared (unitless).
  double time_step = 1.0;
};

/// How rough the surface is at the scale of its edges: the median over
/// interior vertices of |⟨N_v, x_v − mean of its neighbours⟩|, in units of
/// mean edge length. Clean meshes measure 0.002–0.04 (CAD, analytic,
/// scans like the feline), normal noise of σ = 0.1 edge about 0.075.
/// Vertices on a clean crease or corner (sharp edges and flat ones, none
/// between, or between-edges turning by the same total as along the crease,
/// as on a coarse cylinder's rim) count as 0, so coarse CAD tessellations,
/// where nearly every vertex is one, read as clean (presmooth.cpp).
/// `topology` is the mesh's with its triangle lists, its edges in ascending
/// order as build_topology and repair_mesh give them (Error otherwise).
double surface_noise_level(const Mesh& mesh, const Topology& topology);
/// The same per component (vertex_component numbers them 0 … components−1),
/// each in units of its own mean edge length.
std::vector<double> surface_noise_levels(const Mesh& mesh, const Topology& topology,
                                         const std::vector<uint32_t>& vertex_component, size_t components);

/// Above this noise level the automatic choice pre-smooths.
constexpr double kNoisySurface = 0.06;
/// Steps the automatic choice takes on a noisy surface: on tests/quality,
/// 2 steps left the paraboloid and cosine product short of the targets at
/// σ = 0.25 edge, 3 met them at σ = 0.1 and 0.25, 4 began to flatten the
/// cosine product's weakest segments.
constexpr int kNoisySurfaceSteps = 3;

/// Above this noise level the automatic choice takes more steps, one per
/// kNoisyStepLevel of noise, up to kVeryNoisySurfaceSteps (issue 13). The
/// measured level saturates under heavy noise: on tests/quality it reads
/// 0.088–0.096 at σ = 0.1 edge, 0.20–0.22 at σ = 0.25 and 0.31–0.37 at
/// σ = 0.5. There 3 steps met the targets in 16 of 30 cases, 4 in 22, 6 in
/// 22 with lines closer to the truth (mean offset 0.67 → 0.48 edges), 8 began
/// to flatten the cosine product (20).
constexpr double kVeryNoisySurface = 0.24;
constexpr double kNoisyStepLevel = 0.02;
constexpr int kVeryNoisySurfaceSteps = 6;

/// 0 for a clean surface, kNoisySurfaceSteps when the noise level
/// (surface_noise_level) exceeds kNoisySurface: noise of a tenth of an edge already randomises the
/// principal directions, which extremality smoothing cannot repair, while on
/// clean meshes pre-smoothing only erases fine features. Above
/// kVeryNoisySurface, up to kVeryNoisySurfaceSteps (see there).
int automatic_presmooth_steps(double noise_level);

/// Returns the smoothed vertex positions (same connectivity). Boundary
/// vertices are smoothed along their boundary curve only (1-D implicit
/// Laplacian, same time step), so open meshes do not shrink inwards, yet a
/// noisy boundary does not pin its noise into a band along it (the lines of
/// tests/quality broke 4–6 edges from the boundary when it was held fixed).
///
/// Expects coordinates like the Pipeline's working frame (mesh/frame.h):
/// centred, mean edge about 1. Each step solves for the displacement,
/// (M + tL) d = −tL x, by SignedPairSolver (numerics/paired_cg.h; SpdSolver
/// where it does not converge), its residual relative to −tL x, which is
/// formed from coordinate differences: neither a translation nor the scale
/// enters it. (Issue 13: the solve for x' itself stopped at a residual
/// relative to M·x, which far from the origin is dominated by the
/// translation and on a tiny mesh by the held boundary rows, so it stopped
/// before it had smoothed anything: translated by 4.3e6 units or scaled by
/// 1e-6 a noisy field got hundreds of spurious lines.) The result differs
/// from an exact solve by at most ≈ 1e-6 mean edges (presmooth.cpp says how
/// measured).
std::vector<Vec3> presmooth_surface(const Mesh& mesh, const Topology& topology, const PresmoothOptions& options);
/// The same with a step count per vertex (the Pipeline's automatic choice,
/// made per component): vertex v moves in the first vertex_steps[v] steps
/// and is held afterwards. time_step as in PresmoothOptions. progress, if
/// set, is called on the calling thread after each step's set-up, between
/// the solver's set-up parts and after every iteration of its solves, with
/// fractions of all steps that rise strictly, and may throw to abandon the
/// smoothing (nothing is kept; the mesh is not touched). Reads the
/// adjacency's edges, triangle_edges and boundary_vertex, not its triangle
/// lists (which a caller may release: topology.h).
std::vector<Vec3> presmooth_surface(const Mesh& mesh, const Topology& topology, double time_step,
                                    const std::vector<int>& vertex_steps,
                                    const std::function<void(double)>& progress = {});

}  // namespace crestline
