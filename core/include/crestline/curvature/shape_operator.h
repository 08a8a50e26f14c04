#pragma once
// Paper §3: the discrete shape operator and principal curvatures.
//
// Conventions (used everywhere in Crestline):
// - Triangles are counter-clockwise seen from outside; triangle normals point
//   outwards.
// - Curvature is positive where the surface bends away from its normal, i.e.
//   convex: a sphere of radius r has κ_max = κ_min = +1/r. Ridges are convex
//   crests (κ_max > 0 maximal), valleys concave creases (κ_min < 0 minimal).
// - The vertex shape operator S(p) is an *integrated* quantity (units of
//   length). The curvatures stored here are *pointwise* (units 1/length):
//   κ(p) = 3 / area(star(p)) · λ(p), λ an eigenvalue of S(p).
#include <functional>
#include <vector>

#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"

namespace crestline {

/// A principal direction as stored: computed in double, kept in float. The
/// two direction fields are the largest thing the Pipeline keeps through
/// the smoothing's solves (48 bytes a vertex in double, ≈ 24 bytes a
/// triangle); every reader widens them to double (widen) and computes in
/// double. Rounding them moves lines only where the lines are decided by
/// round-off anyway: on the shared meshes every line that moved by more
/// than 3.4·10⁻⁵ mean edges moves the same way when the input's
/// coordinates are rounded in their last bit (a triangle's regularity,
/// Definition 1, at a tie; a line along a mirror plane).
using Direction = Eigen::Vector3f;
inline Vec3 widen(const Direction& d) { return d.cast<double>(); }

struct Curvature {
  std::vector<Vec3> vertex_normals;  // unit, area-weighted average of triangle normals
  std::vector<double> kappa_max;     // pointwise, κ_max ≥ κ_min
  std::vector<double> kappa_min;
  std::vector<Direction> dir_max;  // unit eigenvectors rounded to float; the sign is arbitrary
  std::vector<Direction> dir_min;
  std::vector<double> star_area;  // sum of the areas of the triangles around each vertex
};

/// σ = sign⟨a, b⟩ for two principal directions, each defined only up to
/// sign (paper §5.1): +1 or −1, and negated when either direction is. Where
/// the two are exactly perpendicular (axis-aligned eigenvectors on flat or
/// symmetric meshes) the dot product is 0 whatever the signs, so the signs
/// of the two directions' first nonzero coordinates decide instead; taking
/// +1 there made the smoothed extremalities, and the lines, depend on the
/// eigen-solver's arbitrary signs.
inline double direction_sign(const Vec3& a, const Vec3& b) {
  const double dot = a.dot(b);
  if (dot != 0) return dot > 0 ? 1.0 : -1.0;
  auto leading_sign = [](const Vec3& d) {
    for (int i = 0; i < 3; ++i)
      if (d[i] != 0) return d[i] > 0 ? 1.0 : -1.0;
    return 1.0;
  };
  return leading_sign(a) * leading_sign(b);
}
inline double direction_sign(const Direction& a, const Direction& b) { return direction_sign(widen(a), widen(b)); }

/// S(e) = H_e (ē×N_e)(ē×N_e)^T with H_e = 2|e|cos(θ_e/2) (signed: + on convex
/// edges), S(p) = ½ Σ_{e∋p} ⟨N_p,N_e⟩ S(e). Principal curvatures are the
/// eigenvalues of the two eigenvectors farthest from the vertex normal (the
/// paper's two of largest magnitude on curved surfaces, and tangent on flat
/// ones), rescaled to pointwise values. Boundary edges contribute nothing
/// (they have no dihedral angle). The eigen-decompositions run on
/// max_threads() threads. progress, if set, is called on the calling thread
/// between blocks of edges and of vertices (fractions of the stage, in
/// order; at 1.1M triangles a few hundredths of a second apart) and may throw
/// to abandon the computation.
Curvature compute_curvature(const Mesh& mesh, const Topology& topology,
                            const std::function<void(double)>& progress = {});

}  // namespace crestline
