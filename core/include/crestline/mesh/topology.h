#pragma once
// Edge and vertex adjacency of a manifold triangle mesh.
#include <cstdint>
#include <vector>

#include "crestline/mesh/mesh.h"

namespace crestline {

constexpr uint32_t kNone = 0xffffffffu;

struct Topology {
  /// Undirected edges, each as (smaller vertex index, larger vertex index).
  std::vector<std::array<uint32_t, 2>> edges;
  /// The (up to) two triangles of each edge, ascending; kNone where missing
  /// (boundary). With vertex_offsets and vertex_triangles: the triangle
  /// lists, which follow from triangle_edges (release_triangle_lists).
  std::vector<std::array<uint32_t, 2>> edge_triangles;
  /// triangle_edges[t][k] is the edge from corner k to corner k+1 (mod 3).
  std::vector<std::array<uint32_t, 3>> triangle_edges;
  /// Triangles around each vertex, CSR: vertex_triangles[vertex_offsets[v] .. vertex_offsets[v+1]).
  std::vector<uint32_t> vertex_offsets;
  std::vector<uint32_t> vertex_triangles;
  /// True for vertices on a boundary edge.
  std::vector<uint8_t> boundary_vertex;

  bool is_boundary_edge(uint32_t e) const { return edge_triangles[e][1] == kNone; }
  /// The triangle across edge e from triangle t (kNone on the boundary).
  uint32_t opposite_triangle(uint32_t e, uint32_t t) const {
    return edge_triangles[e][0] == t ? edge_triangles[e][1] : edge_triangles[e][0];
  }
};

/// Builds adjacency in O(n log n). Requires an edge-manifold mesh (at most two
/// triangles per edge), which `repair_mesh` guarantees.
Topology build_topology(const Mesh& mesh);

/// The triangle lists (edge_triangles, vertex_offsets, vertex_triangles)
/// are what the stages up to the curvature read and the later ones do not:
/// a holder of the adjacency may release them (26 bytes per triangle, the
/// rest keeps 24 and boundary_vertex) and restore them, the same as
/// build_topology's, from the triangles and triangle_edges when needed again.
bool has_triangle_lists(const Topology& topology);
void release_triangle_lists(Topology& topology);
/// No-op where they are present.
void restore_triangle_lists(const Mesh& mesh, Topology& topology);

/// Whether the surface bounds solids it faces out of: every edge has two
/// triangles that run along it in opposite directions (closed and
/// consistently oriented) and the enclosed signed volume is positive. Seen
/// from outside its bounding sphere, such a surface hides its back faces.
/// False for an empty mesh.
bool is_closed_outward(const Mesh& mesh, const Topology& topology);

/// Ring distance of each vertex to the mesh boundary (0 on it), capped at
/// `max_rings`: vertices farther away (or on closed components) get max_rings.
/// Reads boundary_vertex and the triangles, not the triangle lists (one pass
/// over the triangles per ring beyond the first).
std::vector<uint32_t> boundary_ring_distance(const Mesh& mesh, const Topology& topology, uint32_t max_rings);

}  // namespace crestline
