#pragma once
// Cutting a mesh open along chosen edges: how sharp creases become
// boundaries for the smooth lines (issue 16). The one-ring of a vertex on a
// cut is split into its sides, each side getting a vertex of its own at the
// same position, so that every stage that works on vertex stars — the shape
// operator (§3), pre-smoothing and extremality smoothing (§5.1), the tracer's
// boundary band (§4) — sees each side of a crease as a surface with a
// boundary, and nothing reaches across it.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"
#include "crestline/numerics/parallel.h"

namespace crestline {

struct CutMesh {
  /// The same triangles in the same order; positions: the input's, then one
  /// copy per extra side of a split vertex.
  Mesh mesh;
  /// The input vertex of each copy: vertex input_vertices + k is a copy of
  /// copy_of[k]. Ascending: a vertex's copies are consecutive.
  std::vector<uint32_t> copy_of;
  size_t input_vertices = 0;
  uint32_t source(uint32_t v) const { return v < input_vertices ? v : copy_of[v - input_vertices]; }
};

/// Splits every vertex whose triangles fall into several sides once the
/// given edges (indices into topology.edges) no longer connect them: the
/// side holding the vertex's first triangle keeps its index, each further
/// side (in the order of its first triangle) gets a copy. A cut that ends
/// inside the surface opens up to its last split vertex; a single cut edge
/// whose ends split nothing stays closed. Boundary edges in `edges` change
/// nothing. Takes the mesh to cut (moved in by a caller that no longer needs
/// it: its triangles are renamed in place). Costs the size of the cut's
/// vertex stars, and a copy of the positions to append the copies to.
CutMesh cut_along_edges(Mesh mesh, const Topology& topology, const std::vector<uint32_t>& edges);

/// The cut mesh's adjacency made from the input's: exactly
/// build_topology(cut.mesh) (the same edge numbering) without sorting the
/// half-edges again. Takes the input's adjacency (moved in by a caller that
/// no longer needs it): only the edges at split vertices are regrouped, the
/// others move in runs, the fans and per-triangle edges are rewritten in
/// place, so it costs one pass over the edges and the triangles.
Topology cut_topology(Topology topology, const CutMesh& cut);

/// A per-vertex array of the input extended to the cut mesh: each copy takes
/// the value of the vertex it split from.
template <typename T>
std::vector<T> on_cut_vertices(const CutMesh& cut, std::vector<T> values) {
  const size_t n = values.size();
  if (values.capacity() < n + cut.copy_of.size()) {
    // Copied to the larger array on every thread, where its pages are first
    // touched (growing it in place copied on the calling thread alone: the
    // positions at 1.1M triangles ≈ 5 ms of it on 2 threads). Eigen's
    // vectors construct uninitialised, so sizing it writes nothing for them.
    std::vector<T> grown(n + cut.copy_of.size());
    parallel_for(n, [&](size_t begin, size_t end) {
      std::copy(values.begin() + begin, values.begin() + end, grown.begin() + begin);
    });
    for (size_t k = 0; k < cut.copy_of.size(); ++k) grown[n + k] = values[cut.copy_of[k]];
    return grown;
  }
  for (uint32_t v : cut.copy_of) values.push_back(values[v]);  // within capacity: references stay valid
  return values;
}

/// Gives all copies of a vertex (and the vertex itself) their mean position.
void merge_copies(const CutMesh& cut, std::vector<Vec3>& positions);

}  // namespace crestline
