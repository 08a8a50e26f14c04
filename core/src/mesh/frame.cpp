#include "crestline/mesh/frame.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "../numerics/select.h"
#include "crestline/mesh/topology.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/uninitialised.h"
#include "parts.h"

namespace crestline {

uint32_t ComponentFrames::largest() const {
  return static_cast<uint32_t>(std::max_element(triangle_count.begin(), triangle_count.end()) - triangle_count.begin());
}

namespace {

VertexComponents find_components(const Mesh& mesh, const Topology& topology) {
  const size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  // Union-find over the vertices, always linking the larger root under the
  // smaller: a tree's root is then its component's smallest vertex whatever
  // order the links were made in, so the edges are joined on every thread
  // (a link is a compare-and-swap; halving a path stores an ancestor, which
  // any interleaving leaves valid). The edges join what the triangles do
  // (each triangle's sides are edges), 1.5 links a triangle instead of 2,
  // and a run of edges from one smaller end finds that end's root once.
  // number[r]: root r's component, set below. Not zero-filled: every entry
  // is set first.
  std::unique_ptr<std::atomic<uint32_t>[]> parent(new std::atomic<uint32_t>[nv]);
  UninitialisedVector<uint32_t> number(nv);
  parallel_for(nv, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) parent[v].store(uint32_t(v), std::memory_order_relaxed), number[v] = kNone;
  });
  std::atomic<uint32_t>* const parent_data = parent.get();  // a copy the links' stores cannot alias
  auto find = [parent = parent_data](uint32_t x) {
    for (;;) {
      const uint32_t p = parent[x].load(std::memory_order_relaxed);
      if (p == x) return x;
      const uint32_t g = parent[p].load(std::memory_order_relaxed);
      if (g != p) parent[x].store(g, std::memory_order_relaxed);
      x = g;
    }
  };
  parallel_for(topology.edges.size(), [&, edges = topology.edges.data()](size_t begin, size_t end) {
    uint32_t near = kNone, near_root = kNone;
    for (size_t e = begin; e < end; ++e) {
      const auto [a, b] = edges[e];
      if (a != near) near = a, near_root = a;
      for (uint32_t r = find(near_root), s = find(b);; r = find(r), s = find(b)) {
        if (r == s) {
          near_root = r;
          break;
        }
        const uint32_t low = std::min(r, s), high = std::max(r, s);
        uint32_t expected = high;  // still a root unless another thread linked it since
        if (parent_data[high].compare_exchange_weak(expected, low, std::memory_order_relaxed)) {
          near_root = low;
          break;
        }
      }
    }
  });
  // Every vertex straight under its root (later finds take one step), and
  // the roots of triangles counted.
  const size_t vertex_parts = detail::part_count(nv);
  std::vector<size_t> roots(vertex_parts, 0);
  detail::for_each_part(vertex_parts, nv, [&](size_t p, size_t begin, size_t end) {
    size_t count = 0;
    for (size_t v = begin; v < end; ++v) {
      const uint32_t r = find(uint32_t(v));
      parent[v].store(r, std::memory_order_relaxed);
      count += r == v && topology.vertex_offsets[v + 1] > topology.vertex_offsets[v];
    }
    roots[p] = count;
  });
  auto root = [&](uint32_t v) { return parent[v].load(std::memory_order_relaxed); };

  // Components are numbered in order of first appearance among the
  // triangles (a triangle's corners share a component): the triangles in
  // order until every root has its number, on the calling thread; one
  // triangle when the mesh is one component.
  VertexComponents out;
  size_t& n = out.count;
  for (size_t count : roots) n += count;
  for (size_t t = 0, numbered = 0; numbered < n && t < nt; ++t) {
    uint32_t& c = number[root(mesh.triangles[t][0])];
    if (c == kNone) c = uint32_t(numbered++);
  }
  out.vertex.resize(nv);
  // Unreferenced vertices (none after repair) join component 0.
  parallel_for(nv, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      const uint32_t c = number[root(uint32_t(v))];
      out.vertex[v] = c == kNone ? 0 : c;
    }
  });
  return out;
}

}  // namespace

ComponentFrames component_frames(const Mesh& mesh, const Topology& topology, VertexComponents components) {
  const size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  const size_t threads = detail::part_count(nt);
  // The union-find only where repair_mesh's components are not given (at
  // 1.1M triangles ≈ 90 M instructions).
  // Given ones are used only if they fit the mesh (as the Pipeline rebuilds
  // a topology that does not): one component needs no array, several need
  // one entry a vertex.
  const bool fit = components.count == 1 ? components.vertex.empty() || components.vertex.size() == nv
                                         : components.count > 1 && components.vertex.size() == nv;
  if (!fit) components = find_components(mesh, topology);
  ComponentFrames f;
  const size_t n = components.count;
  f.vertex_component = std::move(components.vertex);

  // Centre: the bounding box's, halved before adding so it cannot overflow.
  // Each part's boxes, then merged in part order: a minimum keeps the first
  // of equal values (−0 before 0) in both, so the boxes are those of one
  // pass in vertex order. One part when the components are many and small.
  const size_t box_parts = n * 64 <= nv ? threads : 1;
  std::vector<Vec3> lo(box_parts * n, Vec3::Constant(INFINITY)), hi(box_parts * n, Vec3::Constant(-INFINITY));
  // Each part's boxes in vectors of its own, then stored: kept in place,
  // two threads' boxes of one component shared a cache line, passed back
  // and forth at every vertex.
  detail::for_each_part(box_parts, nv, [&](size_t p, size_t begin, size_t end) {
    std::vector<Vec3> part_lo(n, Vec3::Constant(INFINITY)), part_hi(n, Vec3::Constant(-INFINITY));
    for (size_t v = begin; v < end; ++v) {
      const uint32_t c = f.component(v);
      part_lo[c] = part_lo[c].cwiseMin(mesh.positions[v]), part_hi[c] = part_hi[c].cwiseMax(mesh.positions[v]);
    }
    std::copy(part_lo.begin(), part_lo.end(), lo.begin() + ptrdiff_t(p * n));
    std::copy(part_hi.begin(), part_hi.end(), hi.begin() + ptrdiff_t(p * n));
  });
  for (size_t p = 1; p < box_parts; ++p)
    for (size_t c = 0; c < n; ++c) lo[c] = lo[c].cwiseMin(lo[p * n + c]), hi[c] = hi[c].cwiseMax(hi[p * n + c]);
  f.centre.resize(n);
  std::vector<double> extent(n, 0.0);
  for (size_t c = 0; c < n; ++c) {
    f.centre[c] = 0.5 * lo[c] + 0.5 * hi[c];
    extent[c] = std::max((hi[c] - f.centre[c]).maxCoeff(), (f.centre[c] - lo[c]).maxCoeff());
    if (!(extent[c] > 0)) extent[c] = 1;  // a single point: nothing to scale
  }
  // Mean edge length on coordinates divided by the extent (|y| ≤ 1: squares
  // neither overflow nor underflow), then scaled back. Each edge is measured
  // once, on every thread (a side's length has the same bits either way
  // round), and side_sums adds the triangles' sides exactly. Measuring each side
  // instead, at 1.1M triangles: 12 M instructions more, on one thread and on
  // the calling one of two, and on several twice the memory (26 MB).
  const size_t ne = topology.edges.size();
  UninitialisedVector<double> length(ne);
  parallel_for(ne, [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e) {
      const auto [a, b] = topology.edges[e];
      length[e] = ((mesh.positions[b] - mesh.positions[a]) / extent[f.component(a)]).norm();
    }
  });
  SideSums sums = side_sums(mesh, topology, f.vertex_component, n, length.data());
  f.triangle_count = std::move(sums.triangles);
  f.scale.resize(n);
  for (size_t c = 0; c < n; ++c) {
    const double mean = f.triangle_count[c] ? sums.sum[c] / (3.0 * f.triangle_count[c]) : 0;
    f.scale[c] = mean > 0 ? extent[c] * mean : extent[c];
  }
  // The median interior edge, from the lengths just measured (the crease
  // measure measured every edge again for it: at 1.1M triangles 68 M
  // instructions there, 29 M here). The boundary edges' entries +∞, above every
  // interior edge's, so the upper median is the element at half the
  // interior count; with several components each length first to its
  // component's mean edges, with one the median alone (a positive factor
  // and the rounding keep the order). The element at a rank is the same
  // whatever order the edges are in. It differs from one measured in local
  // coordinates by round-off, which single precision hides (both round to
  // the same float unless the double lies within a few ulps of halfway
  // between two). detail::value_at_rank: nth_element's value in about one
  // pass.
  std::vector<double> factor(n);
  for (size_t c = 0; c < n; ++c) factor[c] = extent[c] / f.scale[c];
  std::atomic<size_t> boundary_edges{0};
  parallel_for(ne, [&, l = length.data()](size_t begin, size_t end) {
    size_t boundary = 0;
    if (n == 1) {
      for (size_t e = begin; e < end; ++e)
        if (topology.is_boundary_edge(uint32_t(e))) l[e] = INFINITY, ++boundary;
    } else {
      for (size_t e = begin; e < end; ++e) {
        if (topology.is_boundary_edge(uint32_t(e)))
          l[e] = INFINITY, ++boundary;
        else
          l[e] *= factor[f.vertex_component[topology.edges[e][0]]];
      }
    }
    boundary_edges.fetch_add(boundary, std::memory_order_relaxed);
  });
  if (const size_t interior = ne - boundary_edges.load()) {
    const double middle = detail::value_at_rank(length.data(), ne, interior / 2);
    f.median_edge_length = static_cast<float>(n > 1 ? middle : middle * factor[0]);
  }
  return f;
}

namespace {

// Sides are added as integer multiples of a quantum, 2^-62 of the power of
// two above the longest edge, into 128 bits (3 · 2^32 sides of up to 2^62
// quanta): integer sums do not depend on the order they are made in, so the
// mean edge lengths, and with them the working frame and everything
// computed in it, have the same bits however the file numbers its
// triangles, and for any number of threads. (Added in triangle order as
// doubles, before 2026-12-07, a shuffled file's scale differed in the last
// bit.) The quantum is at most 2^-61 of the longest edge: far below a
// double's rounding of the mean.
__extension__ typedef unsigned __int128 WideSum;
constexpr int kSideBits = 62;

}  // namespace

SideSums side_sums(const Mesh& mesh, const Topology& topology, const std::vector<uint32_t>& vertex_component,
                   size_t components, const double* length) {
  SideSums out{std::vector<double>(components, 0.0), std::vector<size_t>(components, 0)};
  const auto* sides = topology.triangle_edges.data();
  const size_t nt = mesh.triangles.size(), ne = topology.edges.size();
  const size_t edge_parts = detail::part_count(ne);
  std::vector<double> part_longest(edge_parts, 0.0);
  detail::for_each_part(edge_parts, ne, [&](size_t p, size_t begin, size_t end) {
    double longest = 0;
    for (size_t e = begin; e < end; ++e) longest = std::max(longest, length[e]);
    part_longest[p] = longest;
  });
  const double longest = *std::max_element(part_longest.begin(), part_longest.end());
  if (!(longest > 0) || !std::isfinite(longest)) {
    // No length to quantise by: added as doubles, in triangle order.
    for (size_t t = 0; t < nt; ++t) {
      const uint32_t c = components == 1 ? 0 : vertex_component[mesh.triangles[t][0]];
      out.sum[c] += length[sides[t][0]] + length[sides[t][1]] + length[sides[t][2]], ++out.triangles[c];
    }
    return out;
  }
  int exponent = 0;
  std::frexp(longest, &exponent);  // longest < 2^exponent
  const double to_quanta = std::ldexp(1.0, kSideBits - exponent);
  const auto quanta = [&](size_t t) {
    return WideSum(uint64_t(length[sides[t][0]] * to_quanta)) + uint64_t(length[sides[t][1]] * to_quanta) +
           uint64_t(length[sides[t][2]] * to_quanta);
  };
  // Parts by triangle, each with its own sums: one part when the components
  // are many and small.
  const size_t parts = components * 64 <= nt ? detail::part_count(nt) : 1;
  std::vector<WideSum> sum(parts * components, 0);
  std::vector<size_t> count(parts * components, 0);
  detail::for_each_part(parts, nt, [&](size_t p, size_t begin, size_t end) {
    WideSum* part_sum = sum.data() + p * components;
    size_t* part_count = count.data() + p * components;
    if (components == 1) {
      WideSum total = 0;
      for (size_t t = begin; t < end; ++t) total += quanta(t);
      part_sum[0] = total, part_count[0] = end - begin;
      return;
    }
    std::vector<WideSum> own_sum(components, 0);  // not in place: see the boxes above
    std::vector<size_t> own_count(components, 0);
    for (size_t t = begin; t < end; ++t) {
      const uint32_t c = vertex_component[mesh.triangles[t][0]];
      own_sum[c] += quanta(t), ++own_count[c];
    }
    std::copy(own_sum.begin(), own_sum.end(), part_sum);
    std::copy(own_count.begin(), own_count.end(), part_count);
  });
  for (size_t c = 0; c < components; ++c) {
    WideSum total = 0;
    for (size_t p = 0; p < parts; ++p) total += sum[p * components + c], out.triangles[c] += count[p * components + c];
    out.sum[c] = std::ldexp(static_cast<double>(total), exponent - kSideBits);
  }
  return out;
}

Mesh to_local(const Mesh& mesh, const ComponentFrames& frames) {
  Mesh local;
  local.triangles = mesh.triangles;
  local.positions.resize(mesh.positions.size());
  parallel_for(mesh.positions.size(), [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      const uint32_t c = frames.component(v);
      local.positions[v] = (mesh.positions[v] - frames.centre[c]) / frames.scale[c];
    }
  });
  return local;
}

}  // namespace crestline
