#include "crestline/mesh/topology.h"

#include <algorithm>
#include <mutex>

#include "crestline/error.h"
#include "crestline/numerics/parallel.h"
#include "half_edges.h"

namespace crestline {

Topology build_topology(const Mesh& mesh) {
  Topology topo;
  const size_t nt = mesh.triangles.size(), nv = mesh.positions.size();

  // Half-edges grouped by undirected edge, in (smaller end, larger end,
  // corner) order: edges are numbered in that order.
  // Edges are numbered vertex by vertex: each vertex's count of edges
  // (counted as the order is built), then every vertex's edges numbered from
  // the sum of the counts before it, on every thread.
  std::vector<uint32_t> first_edge;
  const detail::HalfEdgeOrder order = detail::order_half_edges(mesh.triangles, nv, &first_edge);
  topo.triangle_edges.assign(nt, {kNone, kNone, kNone});
  using H = detail::HalfEdgeOrder;
  for (size_t v = 0; v < nv; ++v) first_edge[v + 1] += first_edge[v];
  const size_t edge_count = first_edge[nv];
  topo.edges.resize(edge_count);
  topo.edge_triangles.resize(edge_count);
  // Boundary edges (few) are listed on the way, their ends marked after.
  std::vector<std::array<uint32_t, 2>> boundary_edges;
  std::mutex boundary_mutex;
  detail::for_bucket_ranges(order.start, [&](size_t begin, size_t end) {
    std::vector<std::array<uint32_t, 2>> found;
    order.for_each_edge(begin, end, [&](uint32_t near, uint32_t far, const uint64_t* first, const uint64_t* last) {
      if (last - first > 2)
        throw Error(ErrorKind::InvalidInput, "the mesh has an edge shared by more than two triangles.");
      const uint32_t e = first_edge[near]++;
      topo.edges[e] = {near, far};
      topo.edge_triangles[e] = {H::corner(first[0]) / 3, last - first == 2 ? H::corner(first[1]) / 3 : kNone};
      if (last - first == 1) found.push_back({near, far});
      for (const uint64_t* h = first; h < last; ++h) topo.triangle_edges[H::corner(*h) / 3][H::corner(*h) % 3] = e;
    });
    if (found.empty()) return;
    const std::lock_guard<std::mutex> lock(boundary_mutex);
    boundary_edges.insert(boundary_edges.end(), found.begin(), found.end());
  });

  detail::group_by_bucket(
      nt, nv,
      [&](size_t t, const auto& emit) {
        for (uint32_t v : mesh.triangles[t]) emit(v, uint32_t(t));
      },
      topo.vertex_offsets, topo.vertex_triangles);

  topo.boundary_vertex.assign(nv, 0);
  for (const std::array<uint32_t, 2>& edge : boundary_edges)
    topo.boundary_vertex[edge[0]] = topo.boundary_vertex[edge[1]] = 1;
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
