#include "crestline/mesh/cut.h"

#include <numeric>

namespace crestline {

CutMesh cut_along_edges(const Mesh& mesh, const Topology& topology, const std::vector<uint32_t>& edges) {
  CutMesh out;
  out.mesh = mesh;
  out.input_vertices = mesh.positions.size();
  const size_t nv = mesh.positions.size();
  std::vector<uint8_t> cut(topology.edges.size(), 0), touched(nv, 0);
  for (uint32_t e : edges) {
    if (e >= topology.edges.size() || topology.is_boundary_edge(e)) continue;
    cut[e] = 1;
    touched[topology.edges[e][0]] = touched[topology.edges[e][1]] = 1;
  }
  // Per vertex: its triangles' sides by union-find over the uncut edges at
  // the vertex. `local` maps a triangle to its place in the vertex's fan.
  std::vector<uint32_t> local(mesh.triangles.size(), kNone), parent, side;
  auto find = [&](uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (uint32_t v = 0; v < nv; ++v) {
    if (!touched[v]) continue;
    const uint32_t begin = topology.vertex_offsets[v], end = topology.vertex_offsets[v + 1];
    const uint32_t n = end - begin;
    for (uint32_t i = 0; i < n; ++i) local[topology.vertex_triangles[begin + i]] = i;
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0u);
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t t = topology.vertex_triangles[begin + i];
      for (uint32_t e : topology.triangle_edges[t]) {
        if (cut[e] || (topology.edges[e][0] != v && topology.edges[e][1] != v)) continue;
        const uint32_t o = topology.opposite_triangle(e, t);
        if (o == kNone || local[o] == kNone) continue;
        parent[find(i)] = find(local[o]);
      }
    }
    // Sides numbered by their first triangle (the fan lists triangles in
    // ascending order): side 0 keeps v.
    side.assign(n, kNone);
    uint32_t sides = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t root = find(i);
      if (side[root] == kNone) side[root] = sides++;
      const uint32_t s = side[root];
      if (s == 0) continue;
      const uint32_t copy = static_cast<uint32_t>(out.input_vertices + out.copy_of.size()) + (s - 1);
      Triangle& t = out.mesh.triangles[topology.vertex_triangles[begin + i]];
      for (uint32_t& corner : t)
        if (corner == v) corner = copy;
    }
    for (uint32_t s = 1; s < sides; ++s) out.copy_of.push_back(v), out.mesh.positions.push_back(mesh.positions[v]);
    for (uint32_t i = 0; i < n; ++i) local[topology.vertex_triangles[begin + i]] = kNone;
  }
  return out;
}

void merge_copies(const CutMesh& cut, std::vector<Vec3>& positions) {
  if (cut.copy_of.empty()) return;
  std::vector<Vec3> sum(positions.begin(), positions.begin() + cut.input_vertices);
  std::vector<uint32_t> count(cut.input_vertices, 1);
  for (size_t k = 0; k < cut.copy_of.size(); ++k)
    sum[cut.copy_of[k]] += positions[cut.input_vertices + k], ++count[cut.copy_of[k]];
  for (size_t v = 0; v < cut.input_vertices; ++v) positions[v] = sum[v] / count[v];
  for (size_t k = 0; k < cut.copy_of.size(); ++k) positions[cut.input_vertices + k] = positions[cut.copy_of[k]];
}

}  // namespace crestline
