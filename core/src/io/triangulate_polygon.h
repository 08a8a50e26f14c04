#pragma once
// Polygon triangulation for the readers (OBJ, OFF and PLY faces with more
// than three corners): ear clipping in the polygon's best-fit plane. As in
// earcut (the triangulator three.js uses), the ear test only looks at
// corners found through a spatial index, and large polygons are clipped in
// earcut's order (two corners on after each ear), so a polygon of 10^6
// corners costs O(n log n) on typical outlines rather than O(n^2). The index
// is a k-d tree, not earcut's z-order hash: a z-order range over the thin
// ears of a star-shaped outline spans most corners (a 4·10^5-corner star
// took 10 s; 0.3 s now).
#include <cstddef>
#include <cstdint>

#include "crestline/mesh/mesh.h"

namespace crestline::io::detail {

/// Appends the triangulation of polygon `poly` (n vertex indices into
/// soup.positions, all valid) to soup.indices: n - 2 triangles with the
/// polygon's orientation. Polygons with n > 3 are ear-clipped in their
/// best-fit (Newell) plane, so concave ones stay inside their outline;
/// polygons without a plane (all vertices collinear, or non-finite ones)
/// fall back to a fan, and so does what is left when a whole turn of the
/// outline has no ear (self-intersecting or degenerate outlines).
void add_polygon(TriangleSoup& soup, const uint32_t* poly, size_t n);

/// The work add_polygon has done on this thread: ear tests, and the k-d tree
/// nodes and points those tests examined. Tests assert the clipper's
/// complexity with these counts (operation counts, not timings, so that a
/// slow or sanitized build cannot fail them and a quadratic clipper cannot
/// pass them); set it to {} before the polygons to be measured.
struct PolygonWork {
  uint64_t ear_tests = 0, nodes = 0, points = 0;
};
PolygonWork& polygon_work();

}  // namespace crestline::io::detail
