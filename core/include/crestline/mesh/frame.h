#pragma once
// The working frame: where every stage after repair computes.
//
// Each connected component is moved to its bounding-box centre and divided by
// its own mean edge length, so that a stage sees the same numbers whether the
// user's model is in millimetres or kilometres, sits at the origin or 10⁷
// diagonals away, and whatever else is in the file:
//
//   user = centre[c] + scale[c] · local,   c = the vertex's component.
//
// In local coordinates every component's mean edge length is 1 and its
// bounding box is centred on the origin (components overlap there; no stage
// relates positions of different components). Lengths measured in local
// coordinates are in mean edges, pointwise curvatures in 1 / mean edge, and
// unitless quantities (line strength ∫|κ| ds, angles) are the same in both
// frames. The Pipeline maps what the user sees (lines, the pre-smoothed
// surface, the mean edge length) back with this frame.
#include <cstdint>
#include <vector>

#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"

namespace crestline {

struct ComponentFrames {
  /// Component of each vertex (vertex-connected through triangles), numbered
  /// in order of first appearance among the triangles. A holder may release
  /// it (leave it empty) where there is one component: see component().
  std::vector<uint32_t> vertex_component;
  std::vector<Vec3> centre;            // per component, user coordinates
  std::vector<double> scale;           // per component: its mean edge length, user units
  std::vector<size_t> triangle_count;  // per component
  /// The upper median of the interior edges' lengths (edges with two
  /// triangles) over the whole mesh, each in its component's mean edges (the
  /// working frame's units), rounded to single precision as the crease
  /// measure rounds its own (creases.cpp); 0 without interior edges. The
  /// crease stage's spur rule reads it on sliver-heavy meshes.
  double median_edge_length = 0;

  size_t count() const { return centre.size(); }
  /// vertex_component[v], or 0 where it is released.
  uint32_t component(size_t v) const { return vertex_component.empty() ? 0 : vertex_component[v]; }
  /// The component with the most triangles (the first of equals): the one
  /// single-valued statistics describe.
  uint32_t largest() const;
  Vec3 to_user(const Vec3& local, uint32_t component) const { return centre[component] + scale[component] * local; }
};

/// A mesh's components as component_frames numbers them: each vertex's
/// (empty where there is one), and how many. repair_mesh finds them.
struct VertexComponents {
  std::vector<uint32_t> vertex;
  size_t count = 0;
};

/// Splits a repaired mesh into components and measures each one's frame;
/// `topology` is the mesh's (build_topology), whose edges join the
/// components and are each measured once. `components`, where given (count
/// > 0), are the mesh's, numbered as here (repair_mesh's): not found again.
/// Never overflows or underflows for finite coordinates whose bounding box is
/// finite: the mean edge is measured on coordinates first divided by the
/// component's extent.
ComponentFrames component_frames(const Mesh& mesh, const Topology& topology, VertexComponents components = {});

/// Each component's sum of its triangles' sides, length[e] for each edge e
/// of `topology` (the mesh's; finite, ≥ 0), added as integer multiples of
/// 2^-62 of the power of two above the longest (frame.cpp): the same bits
/// for any order of the triangles and any number of threads (the mean edge
/// lengths are these sums over 3 · triangles). vertex_component numbers the
/// components 0 … components−1.
struct SideSums {
  std::vector<double> sum;
  std::vector<size_t> triangles;
};
SideSums side_sums(const Mesh& mesh, const Topology& topology, const std::vector<uint32_t>& vertex_component,
                   size_t components, const double* length);

/// The mesh in local coordinates (same connectivity).
Mesh to_local(const Mesh& mesh, const ComponentFrames& frames);

}  // namespace crestline
