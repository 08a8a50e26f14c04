#pragma once
// Analytic surfaces whose ridges and valleys are known in closed form, for
// the line-quality harness (issue 9). Each comes as a triangle soup plus its
// true feature curves, densely sampled, and a predicate for the regions that
// are not scored: bands along mesh boundaries (the tracer leaves them out)
// and umbilic-like points where true lines cross, meet or end.
#include <functional>
#include <string>
#include <vector>

#include "crestline/lines/feature_graph.h"
#include "crestline/mesh/mesh.h"

namespace crestline::quality {

struct TrueCurve {
  LineType type = LineType::Ridge;
  std::vector<Vec3> points;  // spacing far below an edge length
  bool closed = false;
};

struct Surface {
  std::string name;
  TriangleSoup soup;
  std::vector<TrueCurve> curves;
  /// Not scored at p, given the mesh's mean edge length h.
  std::function<bool(const Vec3& p, double h)> excluded;
  /// Convex everywhere: every valley is spurious.
  bool convex = false;
  /// No true lines, and not part of the targets: the smooth surface has e ≡ 0,
  /// so whatever the tracer draws is decided by the O(h²) bias of the
  /// discrete curvature. Reported to show what a featureless surface gets.
  bool control = false;
};

/// How a surface is triangulated. Grids: one diagonal direction (valence 6
/// everywhere), a checkerboard (valences 4 and 8), or random diagonals with
/// tangential jitter of 0.3 cells. The sphere-based shapes are always
/// irregular; for them `Irregular` adds jitter.
///
/// Delaunay triangulations (issue 13, delaunay.h), with about as many
/// vertices as the grids:
/// - `AnisoAlong`, `AnisoAcross`: 3:1 triangles (a sheared lattice of
///   spacing 3a × a) whose long sides run along, or across, the true lines —
///   tilted by 0.12 rad so that no edge runs exactly along one. The ripple
///   uses a polar lattice (long along, or across, its circles); the
///   superquadric latitude rings (long along the circles of latitude, or
///   along the meridians), so 8 of its 12 edges get the named kind and 4 the
///   other; the cosine product's two families get one kind each.
/// - `Graded`: jittered points whose spacing grows threefold across the
///   domain (along x; on the superquadric from the south pole to the north).
/// The torus (a control) gets grids of 3:1 cells or the irregular grid.
enum class Triangulation { Uniform, Alternating, Irregular, AnisoAlong, AnisoAcross, Graded };
const char* triangulation_name(Triangulation t);
/// Every triangulation above, in order.
std::vector<Triangulation> triangulations();

struct SurfaceParams {
  /// Grid cells per unit length (the surfaces are a few units across).
  int cells_per_unit = 32;
  Triangulation triangulation = Triangulation::Irregular;
  /// Seeds jitter, diagonals and the random in-plane angle of the line
  /// pattern, so that no mesh edge runs along a true line.
  unsigned seed = 1;
};

/// z = A cos(2π u / L), u along a random direction: parallel straight
/// ridges (crests) and valleys (troughs).
Surface sine_field(const SurfaceParams& p);
/// z = A cos(kx) cos(ky) = ½A (cos k(x−y) + cos k(x+y)), pattern rotated at
/// random: two crossing families of straight ridges and valleys; their
/// crossings are umbilic-like and excluded.
Surface cosine_product(const SurfaceParams& p);
/// z = A cos(2π r / L): concentric circles, ridges at r = L and valleys at
/// r = L/2, 3L/2 — closed loops; the umbilic centre is excluded.
Surface ripple(const SurfaceParams& p);
/// z = −(a x² + b y²), a ≫ b: one ridge along the long axis; convex.
Surface paraboloid_ridge(const SurfaceParams& p);
/// |x|⁴ + |y|⁴ + |z|⁴ = 1 meshed from a randomly rotated geodesic sphere:
/// twelve rounded edges are ridges; the umbilic corners are excluded; convex.
Surface superquadric(const SurfaceParams& p);
/// A torus has constant κ along both principal directions (e ≡ 0): no lines.
Surface torus(const SurfaceParams& p);

/// Every surface above, by name.
std::vector<std::string> surface_names();
Surface make_surface(const std::string& name, const SurfaceParams& p);

}  // namespace crestline::quality
