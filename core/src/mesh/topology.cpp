#include "crestline/mesh/topology.h"

#include <algorithm>

#include "crestline/error.h"

namespace crestline {

Topology build_topology(const Mesh& mesh) {
  Topology topo;
  const size_t nt = mesh.triangles.size(), nv = mesh.positions.size();

  // Half-edges keyed by their undirected edge; sorting groups the two sides.
  // A counting sort by the smaller vertex (corners stay in increasing order)
  // and a sort of each vertex's few half-edges give the order of one global
  // sort by (key, corner) in linear time.
  struct HalfEdge {
    uint64_t key;
    uint32_t corner;  // 3 * triangle + k
  };
  auto smaller_end = [&](uint32_t t, uint32_t k) {
    return std::min(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3]);
  };
  std::vector<uint32_t> bucket(nv + 1, 0);
  for (uint32_t t = 0; t < nt; ++t)
    for (uint32_t k = 0; k < 3; ++k) ++bucket[smaller_end(t, k) + 1];
  for (size_t v = 0; v < nv; ++v) bucket[v + 1] += bucket[v];
  std::vector<HalfEdge> half(3 * nt);
  {
    std::vector<uint32_t> fill(bucket.begin(), bucket.end() - 1);
    for (uint32_t t = 0; t < nt; ++t)
      for (uint32_t k = 0; k < 3; ++k) {
        uint64_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
        if (a > b) std::swap(a, b);
        half[fill[a]++] = {(a << 32) | b, 3 * t + k};
      }
  }
  for (size_t v = 0; v < nv; ++v)
    std::sort(half.begin() + bucket[v], half.begin() + bucket[v + 1], [](const HalfEdge& x, const HalfEdge& y) {
      return x.key < y.key || (x.key == y.key && x.corner < y.corner);
    });

  topo.triangle_edges.assign(nt, {kNone, kNone, kNone});
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    if (j - i > 2) throw Error(ErrorKind::InvalidInput, "the mesh has an edge shared by more than two triangles.");
    const uint32_t e = static_cast<uint32_t>(topo.edges.size());
    topo.edges.push_back({static_cast<uint32_t>(half[i].key >> 32), static_cast<uint32_t>(half[i].key)});
    std::array<uint32_t, 2> tris{half[i].corner / 3, kNone};
    if (j - i == 2) tris[1] = half[i + 1].corner / 3;
    topo.edge_triangles.push_back(tris);
    for (size_t h = i; h < j; ++h) topo.triangle_edges[half[h].corner / 3][half[h].corner % 3] = e;
    i = j;
  }

  topo.vertex_offsets.assign(nv + 1, 0);
  for (const Triangle& t : mesh.triangles)
    for (uint32_t v : t) ++topo.vertex_offsets[v + 1];
  for (size_t v = 0; v < nv; ++v) topo.vertex_offsets[v + 1] += topo.vertex_offsets[v];
  topo.vertex_triangles.resize(3 * nt);
  std::vector<uint32_t> fill(topo.vertex_offsets.begin(), topo.vertex_offsets.end() - 1);
  for (uint32_t t = 0; t < nt; ++t)
    for (uint32_t v : mesh.triangles[t]) topo.vertex_triangles[fill[v]++] = t;

  topo.boundary_vertex.assign(nv, 0);
  for (size_t e = 0; e < topo.edges.size(); ++e)
    if (topo.is_boundary_edge(static_cast<uint32_t>(e))) {
      topo.boundary_vertex[topo.edges[e][0]] = 1;
      topo.boundary_vertex[topo.edges[e][1]] = 1;
    }
  return topo;
}

std::vector<uint32_t> boundary_ring_distance(const Mesh& mesh, const Topology& topology, uint32_t max_rings) {
  std::vector<uint32_t> distance(mesh.positions.size(), max_rings);
  std::vector<uint32_t> front, next;
  for (uint32_t v = 0; v < distance.size(); ++v)
    if (topology.boundary_vertex[v] && max_rings > 0) distance[v] = 0, front.push_back(v);
  for (uint32_t ring = 1; ring < max_rings && !front.empty(); ++ring) {
    next.clear();
    for (uint32_t v : front)
      for (uint32_t i = topology.vertex_offsets[v]; i < topology.vertex_offsets[v + 1]; ++i)
        for (uint32_t w : mesh.triangles[topology.vertex_triangles[i]])
          if (distance[w] > ring) distance[w] = ring, next.push_back(w);
    front.swap(next);
  }
  return distance;
}

}  // namespace crestline
