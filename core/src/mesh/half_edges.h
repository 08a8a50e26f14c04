#pragma once
// Half-edges (corners) of a triangle list grouped by undirected edge, shared
// by repair_mesh and build_topology. Corner c = 3 t + k is the edge from
// corner k of triangle t to corner k + 1 (mod 3).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "crestline/error.h"
#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/uninitialised.h"
#include "parts.h"

namespace crestline::detail {

/// Entries grouped by bucket, in order within each bucket (a stable counting
/// sort): items 0 … count − 1 each emit entries through visit(i, emit),
/// emit(bucket < buckets, value), and entries[start[b] .. start[b + 1]) are
/// bucket b's values in the order emitted. Large inputs are counted and
/// placed in up to 8 consecutive parts on as many threads, each part after
/// the ones before it in every bucket, and the buckets' offsets summed over
/// as many ranges of buckets: the same result for any thread count. visit
/// may be called more than twice for an item (prefetches), so it must only emit.
template <typename Visit, typename Entries>
void group_by_bucket(size_t count, size_t buckets, const Visit& visit, std::vector<uint32_t>& start, Entries& entries) {
  using T = typename Entries::value_type;
  start.assign(buckets + 1, 0);
  const size_t parts = part_count(count);
  auto each_part = [&](const auto& body) { for_each_part(parts, count, body); };
  // The buckets lie anywhere: the counters (cursors) of the item kAhead on
  // are asked for now, and in the placing pass the cursors 2 kAhead on and
  // the slots kAhead on (natively; WASM has no prefetch).
  constexpr size_t kAhead = 8;
  auto count_part = [&](uint32_t* counts, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (i + kAhead < end) visit(i + kAhead, [&](uint32_t b, const T&) { __builtin_prefetch(&counts[b], 1); });
      visit(i, [&](uint32_t b, const T&) { ++counts[b]; });
    }
  };
  auto place_part = [&](uint32_t* fill, size_t begin, size_t end) {
    T* out = entries.data();
    for (size_t i = begin; i < end; ++i) {
      if (i + 2 * kAhead < end) visit(i + 2 * kAhead, [&](uint32_t b, const T&) { __builtin_prefetch(&fill[b], 1); });
      if (i + kAhead < end) visit(i + kAhead, [&](uint32_t b, const T&) { __builtin_prefetch(&out[fill[b]], 1); });
      visit(i, [&](uint32_t b, const T& value) { out[fill[b]++] = value; });
    }
  };
  if (parts == 1) {
    // One part: start[b + 1] counts bucket b, then holds where its next
    // entry goes, and ends as bucket b + 1's start (no cursor array).
    count_part(start.data() + 1, 0, count);
    uint32_t sum = 0;
    for (size_t b = 0; b < buckets; ++b) {
      const uint32_t n = start[b + 1];
      start[b + 1] = sum;
      sum += n;
    }
    entries.resize(sum);
    place_part(start.data() + 1, 0, count);
    return;
  }
  // next[p * buckets + b]: part p's count in bucket b, then where its next
  // entry goes; each part zeroes its own row.
  UninitialisedVector<uint32_t> next(parts * buckets);
  each_part([&](size_t p, size_t begin, size_t end) {
    uint32_t* counts = next.data() + p * buckets;
    std::fill(counts, counts + buckets, 0u);
    count_part(counts, begin, end);
  });
  // The offsets on every thread too: each range of buckets' total, then its
  // offsets from the totals of the ranges before it.
  std::vector<uint32_t> range_start(parts + 1, 0);
  for_each_part(parts, buckets, [&](size_t r, size_t first, size_t last) {
    uint32_t total = 0;
    for (size_t b = first; b < last; ++b)
      for (size_t p = 0; p < parts; ++p) total += next[p * buckets + b];
    range_start[r + 1] = total;
  });
  for (size_t r = 0; r < parts; ++r) range_start[r + 1] += range_start[r];
  for_each_part(parts, buckets, [&](size_t r, size_t first, size_t last) {
    uint32_t sum = range_start[r];
    for (size_t b = first; b < last; ++b) {
      start[b] = sum;
      for (size_t p = 0; p < parts; ++p) {
        const uint32_t n = next[p * buckets + b];
        next[p * buckets + b] = sum;
        sum += n;
      }
    }
  });
  const uint32_t sum = range_start[parts];
  start[buckets] = sum;
  entries.resize(sum);
  each_part([&](size_t p, size_t begin, size_t end) { place_part(next.data() + p * buckets, begin, end); });
}

/// Calls body(first, last) on consecutive ranges of buckets covering
/// [0, start.size() − 1), each with about as many entries (start as
/// group_by_bucket returns it), on every thread. Half-edges are grouped by
/// their smaller end, so on a subdivided mesh the early (coarse) vertices
/// hold most of them: ranges of equal vertex counts left one thread with
/// three quarters of the work at 1.1M triangles.
template <typename Body>
void for_bucket_ranges(const std::vector<uint32_t>& start, const Body& body) {
  const size_t buckets = start.size() - 1, total = start[buckets];
  // The first bucket whose entries start at or after `entry`.
  auto bucket_at = [&](size_t entry) {
    return size_t(std::lower_bound(start.begin(), start.begin() + ptrdiff_t(buckets), entry) - start.begin());
  };
  parallel_for(total,
               [&](size_t begin, size_t end) { body(bucket_at(begin), end == total ? buckets : bucket_at(end)); });
}

/// Half-edges in the order of one global sort by (smaller end, larger end,
/// corner), built in linear time: a counting sort by the smaller end (corners
/// stay increasing), then a sort of each vertex's few entries. 8 bytes per
/// half-edge plus 4 per vertex.
struct HalfEdgeOrder {
  /// entries[start[v] .. start[v + 1]) are the half-edges whose smaller end is v.
  std::vector<uint32_t> start;
  /// larger end << 32 | triangle << 2 | side, ascending within each vertex
  /// (every entry written by the grouping, so not zero-filled first). The
  /// triangle and side (k of corner 3 t + k) are stored apart, in the order
  /// of the corner: a corner's `c / 3` and `c % 3` cost ≈ 20 instructions a
  /// write of triangle_edges (0.065 G at 1.1M triangles, d848c66).
  UninitialisedVector<uint64_t> entries;

  /// Triangles beyond this do not fit an entry (a triangle list of 12 GB).
  static constexpr size_t kMaxTriangles = size_t{1} << 30;

  static uint64_t entry(uint32_t far, size_t triangle, uint32_t side) {
    return uint64_t{far} << 32 | uint32_t(triangle << 2 | side);
  }
  static uint32_t far_end(uint64_t entry) { return static_cast<uint32_t>(entry >> 32); }
  static uint32_t triangle(uint64_t entry) { return static_cast<uint32_t>(entry) >> 2; }
  static uint32_t side(uint64_t entry) { return static_cast<uint32_t>(entry) & 3; }
  static uint32_t corner(uint64_t entry) { return 3 * triangle(entry) + side(entry); }

  /// Calls edge(near, far, first, last) once per undirected edge, in
  /// ascending (near, far) order, with [first, last) its half-edges in corner order.
  template <typename Edge>
  void for_each_edge(const Edge& edge) const {
    for_each_edge(0, start.size() - 1, edge);
  }
  /// The same for the edges whose smaller end is in [first_vertex, last_vertex).
  template <typename Edge>
  void for_each_edge(size_t first_vertex, size_t last_vertex, const Edge& edge) const {
    const uint64_t* data = entries.data();
    const uint32_t* offsets = start.data();
    for (uint32_t v = uint32_t(first_vertex); v < last_vertex; ++v)
      for (const uint64_t *i = data + offsets[v], *end = data + offsets[v + 1]; i < end;) {
        const uint32_t far = far_end(*i);
        const uint64_t* j = i + 1;
        while (j < end && far_end(*j) == far) ++j;
        edge(v, far, i, j);
        i = j;
      }
  }
};

/// With `edges` given, also sets (*edges)[v + 1] to the number of
/// undirected edges whose smaller end is v ((*edges)[0] = 0), counted while
/// each vertex's entries are at hand rather than in another pass over them.
/// Throws Error(TooLarge) beyond HalfEdgeOrder::kMaxTriangles.
inline HalfEdgeOrder order_half_edges(const std::vector<Triangle>& tris, size_t vertex_count,
                                      std::vector<uint32_t>* edges = nullptr) {
  using H = HalfEdgeOrder;
  if (tris.size() > H::kMaxTriangles)
    throw Error(ErrorKind::TooLarge, "the mesh has " + std::to_string(tris.size()) +
                                         " triangles, more than the half-edges can number (" +
                                         std::to_string(H::kMaxTriangles) + ").");
  HalfEdgeOrder order;
  group_by_bucket(
      tris.size(), vertex_count,
      [&](size_t t, const auto& emit) {
        const uint32_t a = tris[t][0], b = tris[t][1], c = tris[t][2];
        emit(std::min(a, b), H::entry(std::max(a, b), t, 0));
        emit(std::min(b, c), H::entry(std::max(b, c), t, 1));
        emit(std::min(c, a), H::entry(std::max(c, a), t, 2));
      },
      order.start, order.entries);
  // Each vertex's entries are sorted on their own: on every thread, with the
  // same result for any count.
  uint64_t* data = order.entries.data();
  if (edges) edges->assign(vertex_count + 1, 0);
  for_bucket_ranges(order.start, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      uint64_t *first = data + order.start[v], *last = data + order.start[v + 1];
      if (first == last) continue;
      if (last - first > 16) {
        std::sort(first, last);
      } else {
        for (uint64_t* i = first + 1; i < last; ++i) {  // insertion sort: a vertex has ~6
          const uint64_t x = *i;
          uint64_t* j = i;
          for (; j > first && j[-1] > x; --j) *j = j[-1];
          *j = x;
        }
      }
      if (edges) {
        uint32_t n = 1;
        for (const uint64_t* i = first + 1; i < last; ++i) n += H::far_end(*i) != H::far_end(i[-1]);
        (*edges)[v + 1] = n;
      }
    }
  });
  return order;
}

/// Topology's edge arrays numbered from order_half_edges' per-vertex edge
/// counts: sizes them, and turns `first_edge` into each vertex's next edge
/// number (the sum of the counts before it), for EdgeRecorder.
/// The three arrays' fills write fresh pages (40 MB at 1.1M triangles, a
/// third each), whose faults cost more than the writes: the triangles'
/// edges filled on one thread, the edges and their triangles on another,
/// but allocated here (a block allocated on a kept thread would sit in that
/// thread's malloc arena, apart from the caller's: the CLI's max RSS rose
/// by 18-33 MB so).
inline void number_edges(std::vector<uint32_t>& first_edge, size_t triangle_count, Topology& topology) {
  const size_t nv = first_edge.size() - 1;
  for (size_t v = 0; v < nv; ++v) first_edge[v + 1] += first_edge[v];
  const size_t edges = first_edge[nv];
  topology.triangle_edges.reserve(triangle_count);
  topology.edges.reserve(edges);
  topology.edge_triangles.reserve(edges);
  run_side_by_side(
      [&] {
        topology.triangle_edges.assign(triangle_count, {kNone, kNone, kNone});
      },
      [&] {
        topology.edges.resize(edges);
        topology.edge_triangles.resize(edges);
      });
}

/// Records the edge (near, far) whose half-edges are [first, last) (at most
/// two, as HalfEdgeOrder::for_each_edge passes them) under the next number
/// of `near`; returns it. Holds the arrays' addresses: a loop that also
/// writes bytes (which may alias anything) would reload them from the
/// vectors at every edge otherwise.
class EdgeRecorder {
 public:
  /// first_edge as number_edges leaves it, topology sized by it.
  EdgeRecorder(std::vector<uint32_t>& first_edge, Topology& topology)
      : next_edge_(first_edge.data()),
        edges_(topology.edges.data()),
        edge_triangles_(topology.edge_triangles.data()),
        triangle_edges_(topology.triangle_edges.data()) {}

  uint32_t operator()(uint32_t near, uint32_t far, const uint64_t* first, const uint64_t* last) const {
    using H = HalfEdgeOrder;
    const uint32_t e = next_edge_[near]++;
    edges_[e] = {near, far};
    edge_triangles_[e] = {H::triangle(first[0]), last - first == 2 ? H::triangle(first[1]) : kNone};
    for (const uint64_t* h = first; h < last; ++h) triangle_edges_[H::triangle(*h)][H::side(*h)] = e;
    return e;
  }
  /// The same for an edge of two half-edges, sides sa of triangle ta and sb
  /// of tb (ta < tb), which the caller has already taken from the entries.
  uint32_t operator()(uint32_t near, uint32_t far, uint32_t ta, uint32_t sa, uint32_t tb, uint32_t sb) const {
    const uint32_t e = next_edge_[near]++;
    edges_[e] = {near, far};
    edge_triangles_[e] = {ta, tb};
    triangle_edges_[ta][sa] = e;
    triangle_edges_[tb][sb] = e;
    return e;
  }

 private:
  uint32_t* next_edge_;
  std::array<uint32_t, 2>* edges_;
  std::array<uint32_t, 2>* edge_triangles_;
  std::array<uint32_t, 3>* triangle_edges_;
};

/// The rest of build_topology once the edges are recorded: the triangles
/// around each vertex and the boundary vertices. Shared with repair_mesh,
/// which records the edges while it pairs the half-edges and passes the
/// boundary edges it met there (in any order; found here otherwise).
void add_vertex_triangles(const std::vector<Triangle>& tris, size_t vertex_count, Topology& topology,
                          const std::vector<uint32_t>* boundary_edges = nullptr);
/// Its two halves: vertex_offsets and vertex_triangles; then boundary_vertex
/// (from the edges recorded, and boundary_edges as above). repair_mesh
/// groups the triangles before it splits the vertices of several fans.
void group_vertex_triangles(const std::vector<Triangle>& tris, size_t vertex_count, Topology& topology);
void flag_boundary_vertices(size_t vertex_count, Topology& topology,
                            const std::vector<uint32_t>* boundary_edges = nullptr);

}  // namespace crestline::detail
