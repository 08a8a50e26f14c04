#pragma once
// A small Delaunay triangulation for the quality harness's graded and
// anisotropic meshings (issue 13): Bowyer–Watson insertion with a walking
// point location, in the plane and, through a stereographic projection, on
// the unit sphere. Test support, not part of the core: it assumes points in
// general position up to collinear runs along a convex boundary (the
// generators jitter their interiors), which double-precision predicates
// decide exactly there.
#include <vector>

#include "crestline/mesh/mesh.h"

namespace crestline::quality {

/// Counter-clockwise triangles of the Delaunay triangulation of `points`
/// (indices into them), covering their convex hull.
std::vector<Triangle> delaunay_2d(const std::vector<Eigen::Vector2d>& points);

/// The Delaunay triangulation of points on the unit sphere (its convex hull),
/// oriented outwards. points[0] must be the north pole (0, 0, 1): the others
/// are projected stereographically from it, triangulated in the plane, and
/// the planar hull is closed by a fan around the pole [Brown 1979].
std::vector<Triangle> delaunay_sphere(const std::vector<Vec3>& points);

}  // namespace crestline::quality
