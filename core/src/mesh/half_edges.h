#pragma once
// Half-edges (corners) of a triangle list grouped by undirected edge, shared
// by repair_mesh and build_topology. Corner c = 3 t + k is the edge from
// corner k of triangle t to corner k + 1 (mod 3).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "crestline/mesh/mesh.h"
#include "crestline/numerics/parallel.h"

namespace crestline::detail {

/// Half-edges in the order of one global sort by (smaller end, larger end,
/// corner), built in linear time: a counting sort by the smaller end (corners
/// stay increasing), then a sort of each vertex's few entries. 8 bytes per
/// half-edge plus 4 per vertex.
struct HalfEdgeOrder {
  /// entries[start[v] .. start[v + 1]) are the half-edges whose smaller end is v.
  std::vector<uint32_t> start;
  /// larger end << 32 | corner, ascending within each vertex.
  std::vector<uint64_t> entries;

  static uint32_t far_end(uint64_t entry) { return static_cast<uint32_t>(entry >> 32); }
  static uint32_t corner(uint64_t entry) { return static_cast<uint32_t>(entry); }

  /// The number of undirected edges.
  size_t edge_count() const {
    size_t count = 0;
    for (uint32_t v = 0; v + 1 < start.size(); ++v)
      for (uint32_t i = start[v]; i < start[v + 1]; ++i)
        count += i == start[v] || far_end(entries[i]) != far_end(entries[i - 1]);
    return count;
  }

  /// Calls edge(near, far, first, last) once per undirected edge, in
  /// ascending (near, far) order, with [first, last) its half-edges in corner order.
  template <typename Edge>
  void for_each_edge(const Edge& edge) const {
    const uint64_t* data = entries.data();
    for (uint32_t v = 0; v + 1 < start.size(); ++v)
      for (uint32_t i = start[v], end = start[v + 1]; i < end;) {
        uint32_t j = i + 1;
        while (j < end && far_end(data[j]) == far_end(data[i])) ++j;
        edge(v, far_end(data[i]), data + i, data + j);
        i = j;
      }
  }
};

inline HalfEdgeOrder order_half_edges(const std::vector<Triangle>& tris, size_t vertex_count) {
  HalfEdgeOrder order;
  order.start.assign(vertex_count + 1, 0);
  for (const Triangle& t : tris)
    for (uint32_t k = 0; k < 3; ++k) ++order.start[std::min(t[k], t[(k + 1) % 3]) + 1];
  for (size_t v = 0; v < vertex_count; ++v) order.start[v + 1] += order.start[v];
  order.entries.resize(3 * tris.size());
  {
    std::vector<uint32_t> fill(order.start.begin(), order.start.end() - 1);
    for (uint32_t t = 0; t < tris.size(); ++t)
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
        order.entries[fill[std::min(a, b)]++] = uint64_t{std::max(a, b)} << 32 | (3 * t + k);
      }
  }
  // Each vertex's entries are sorted on their own: on every thread, with the
  // same result for any count.
  uint64_t* data = order.entries.data();
  parallel_for(vertex_count, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      uint64_t *first = data + order.start[v], *last = data + order.start[v + 1];
      if (last - first > 16) {
        std::sort(first, last);
        continue;
      }
      for (uint64_t* i = first + 1; i < last; ++i) {  // insertion sort: a vertex has ~6
        const uint64_t x = *i;
        uint64_t* j = i;
        for (; j > first && j[-1] > x; --j) *j = j[-1];
        *j = x;
      }
    }
  });
  return order;
}

}  // namespace crestline::detail
