#include "crestline/mesh/topology.h"

#include <algorithm>

#include "crestline/error.h"
#include "half_edges.h"

namespace crestline {

Topology build_topology(const Mesh& mesh) {
  Topology topo;
  const size_t nt = mesh.triangles.size(), nv = mesh.positions.size();

  // Half-edges grouped by undirected edge, in (smaller end, larger end,
  // corner) order: edges are numbered in that order.
  const detail::HalfEdgeOrder order = detail::order_half_edges(mesh.triangles, nv);
  topo.triangle_edges.assign(nt, {kNone, kNone, kNone});
  const size_t edge_count = order.edge_count();
  topo.edges.reserve(edge_count);
  topo.edge_triangles.reserve(edge_count);
  using H = detail::HalfEdgeOrder;
  order.for_each_edge([&](uint32_t near, uint32_t far, const uint64_t* first, const uint64_t* last) {
    if (last - first > 2)
      throw Error(ErrorKind::InvalidInput, "the mesh has an edge shared by more than two triangles.");
    const uint32_t e = static_cast<uint32_t>(topo.edges.size());
    topo.edges.push_back({near, far});
    topo.edge_triangles.push_back({H::corner(first[0]) / 3, last - first == 2 ? H::corner(first[1]) / 3 : kNone});
    for (const uint64_t* h = first; h < last; ++h) topo.triangle_edges[H::corner(*h) / 3][H::corner(*h) % 3] = e;
  });

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
