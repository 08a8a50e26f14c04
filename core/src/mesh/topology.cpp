#include "crestline/mesh/topology.h"

#include <algorithm>

#include "crestline/error.h"
#include "crestline/numerics/parallel.h"
#include "half_edges.h"
#include "parts.h"

namespace crestline {

namespace detail {

void group_vertex_triangles(const std::vector<Triangle>& tris, size_t vertex_count, Topology& topology) {
  group_by_bucket(
      tris.size(), vertex_count,
      [&](size_t t, const auto& emit) {
        for (uint32_t v : tris[t]) emit(v, uint32_t(t));
      },
      topology.vertex_offsets, topology.vertex_triangles);
}

void add_vertex_triangles(const std::vector<Triangle>& tris, size_t vertex_count, Topology& topology,
                          const std::vector<uint32_t>* boundary_edges) {
  group_vertex_triangles(tris, vertex_count, topology);
  flag_boundary_vertices(vertex_count, topology, boundary_edges);
}

void flag_boundary_vertices(size_t vertex_count, Topology& topology, const std::vector<uint32_t>* boundary_edges) {
  topology.boundary_vertex.assign(vertex_count, 0);
  auto flag_ends = [&](const std::vector<uint32_t>& edges) {
    for (uint32_t e : edges)
      topology.boundary_vertex[topology.edges[e][0]] = topology.boundary_vertex[topology.edges[e][1]] = 1;
  };
  if (boundary_edges) {
    flag_ends(*boundary_edges);
    return;
  }
  // The boundary edges (few) found on every thread, each part's listed,
  // then their ends flagged (12 M instructions at 871k triangles on the
  // calling thread before).
  const size_t ne = topology.edges.size(), parts = part_count(ne);
  std::vector<std::vector<uint32_t>> boundary(parts);
  for_each_part(parts, ne, [&](size_t p, size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e)
      if (topology.is_boundary_edge(uint32_t(e))) boundary[p].push_back(uint32_t(e));
  });
  for (const std::vector<uint32_t>& edges : boundary) flag_ends(edges);
}

}  // namespace detail

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
  detail::number_edges(first_edge, nt, topo);
  const detail::EdgeRecorder record(first_edge, topo);
  detail::for_bucket_ranges(order.start, [&](size_t begin, size_t end) {
    order.for_each_edge(begin, end, [&](uint32_t near, uint32_t far, const uint64_t* first, const uint64_t* last) {
      if (last - first > 2)
        throw Error(ErrorKind::InvalidInput, "the mesh has an edge shared by more than two triangles.");
      record(near, far, first, last);
    });
  });
  detail::add_vertex_triangles(mesh.triangles, nv, topo);
  return topo;
}

bool has_triangle_lists(const Topology& topology) {
  return topology.edge_triangles.size() == topology.edges.size() &&
         topology.vertex_offsets.size() == topology.boundary_vertex.size() + 1;
}

void release_triangle_lists(Topology& topology) {
  // Assigning new vectors frees; clear() would keep the capacity.
  topology.edge_triangles = std::vector<std::array<uint32_t, 2>>();
  topology.vertex_offsets = std::vector<uint32_t>();
  topology.vertex_triangles = std::vector<uint32_t>();
}

void restore_triangle_lists(const Mesh& mesh, Topology& topology) {
  if (has_triangle_lists(topology)) return;
  // build_topology takes an edge's triangles in corner order, so ascending:
  // as a pass over the triangles in order meets them.
  topology.edge_triangles.assign(topology.edges.size(), {kNone, kNone});
  for (uint32_t t = 0; t < topology.triangle_edges.size(); ++t)
    for (uint32_t e : topology.triangle_edges[t])
      topology.edge_triangles[e][topology.edge_triangles[e][0] != kNone] = t;
  detail::add_vertex_triangles(mesh.triangles, mesh.positions.size(), topology);
}

bool is_closed_outward(const Mesh& mesh, const Topology& topology) {
  if (mesh.triangles.empty()) return false;
  for (const auto& pair : topology.edge_triangles)
    if (pair[1] == kNone) return false;
  // Each edge has two triangles; they run along it in opposite directions
  // exactly when its two corners' signs (+1 from the smaller end, −1 from
  // the larger) cancel. Summed over all corners with a fixed pseudo-random
  // weight per edge, in one pass over the triangles (no reads of the
  // edges' other triangles): an edge run twice the same way adds ±2 of its
  // weight, which other edges cancel with chance 2⁻⁶³.
  uint64_t sum = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      uint64_t weight = topology.triangle_edges[t][k] * 0x9E3779B97F4A7C15ull;
      weight ^= weight >> 29;
      weight *= 0xBF58476D1CE4E5B9ull;
      weight ^= weight >> 32;
      sum += mesh.triangles[t][k] < mesh.triangles[t][(k + 1) % 3] ? weight : 0 - weight;
    }
  if (sum != 0) return false;
  // Six times the volume: each triangle's cone to a vertex of the mesh
  // (about the origin, far-off coordinates would cancel).
  const Vec3& apex = mesh.positions[mesh.triangles[0][0]];
  double volume = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 a = mesh.positions[t[0]] - apex, b = mesh.positions[t[1]] - apex, c = mesh.positions[t[2]] - apex;
    volume += a.dot(b.cross(c));
  }
  return volume > 0;
}

std::vector<uint32_t> boundary_ring_distance(const Mesh& mesh, const Topology& topology, uint32_t max_rings) {
  std::vector<uint32_t> distance(mesh.positions.size(), max_rings);
  if (max_rings == 0) return distance;
  bool front = false;  // whether the last ring has a vertex
  for (uint32_t v = 0; v < distance.size(); ++v)
    if (topology.boundary_vertex[v]) distance[v] = 0, front = true;
  // Each ring from the triangles with a corner on the one before: a pass
  // over the triangles instead of the vertex fans, which the smoothing and
  // the tracer, the callers, run without (release_triangle_lists). The pass
  // runs on every thread (at 1.1M triangles it was ≈ 4 ms of the calling
  // thread alone per caller on 2 threads); marking the triangles found after
  // it gives the same distances as marking them during it.
  for (uint32_t ring = 1; ring < max_rings && front; ++ring) {
    const std::vector<uint32_t> touching = detail::indices_where(mesh.triangles.size(), [&](size_t t) {
      const Triangle& f = mesh.triangles[t];
      return distance[f[0]] == ring - 1 || distance[f[1]] == ring - 1 || distance[f[2]] == ring - 1;
    });
    front = false;
    for (uint32_t t : touching)
      for (uint32_t w : mesh.triangles[t])
        if (distance[w] > ring) distance[w] = ring, front = true;
  }
  return distance;
}

}  // namespace crestline
