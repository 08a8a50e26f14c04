#include "crestline/mesh/cut.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <utility>

#include "crestline/numerics/parallel.h"

namespace crestline {

CutMesh cut_along_edges(Mesh mesh, const Topology& topology, const std::vector<uint32_t>& edges) {
  CutMesh out;
  out.mesh = std::move(mesh);
  out.input_vertices = out.mesh.positions.size();
  // The interior edges to cut and their ends, sorted: no array over the
  // whole mesh (the cut is small, and fresh memory costs a page fault per 4 kB).
  std::vector<uint32_t> cut, touched;
  for (uint32_t e : edges) {
    if (e >= topology.edges.size() || topology.is_boundary_edge(e)) continue;
    cut.push_back(e);
    touched.insert(touched.end(), topology.edges[e].begin(), topology.edges[e].end());
  }
  for (std::vector<uint32_t>* list : {&cut, &touched}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  // Per vertex: its triangles' sides by union-find over the uncut edges at
  // the vertex, over their places in the vertex's fan (ascending).
  std::vector<uint32_t> parent, side;
  auto find = [&](uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (uint32_t v : touched) {
    const auto fan = topology.vertex_triangles.begin();
    const uint32_t begin = topology.vertex_offsets[v], end = topology.vertex_offsets[v + 1];
    const uint32_t n = end - begin;
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0u);
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t t = fan[begin + i];
      for (uint32_t e : topology.triangle_edges[t]) {
        if (topology.edges[e][0] != v && topology.edges[e][1] != v) continue;
        if (std::binary_search(cut.begin(), cut.end(), e)) continue;
        const uint32_t o = topology.opposite_triangle(e, t);
        const auto place = std::lower_bound(fan + begin, fan + end, o);
        if (o == kNone || place == fan + end || *place != o) continue;
        parent[find(i)] = find(static_cast<uint32_t>(place - (fan + begin)));
      }
    }
    // Sides numbered by their first triangle: side 0 keeps v.
    side.assign(n, kNone);
    uint32_t sides = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t root = find(i);
      if (side[root] == kNone) side[root] = sides++;
      const uint32_t s = side[root];
      if (s == 0) continue;
      const uint32_t copy = static_cast<uint32_t>(out.input_vertices + out.copy_of.size()) + (s - 1);
      for (uint32_t& corner : out.mesh.triangles[fan[begin + i]])
        if (corner == v) corner = copy;
    }
    out.copy_of.insert(out.copy_of.end(), sides - 1, v);
  }
  out.mesh.positions = on_cut_vertices(out, std::move(out.mesh.positions));
  return out;
}

namespace {

// An edge at a split vertex as it stands in the cut mesh: an input edge with
// new ends, or one of the two pieces it came apart into.
struct Piece {
  uint64_t key;  // smaller end << 32 | larger end
  std::array<uint32_t, 2> triangles;
  std::array<uint32_t, 2> corners;  // 3 t + k of each triangle's half-edge along it; kNone where none
  uint32_t at;                      // the input edges before it: those with a smaller key
  uint32_t index;                   // in the cut mesh
};

uint64_t key_of(const std::array<uint32_t, 2>& edge) { return uint64_t{edge[0]} << 32 | edge[1]; }

}  // namespace

Topology cut_topology(Topology topology, const CutMesh& cut) {
  if (cut.copy_of.empty()) return topology;
  const std::vector<Triangle>& tris = cut.mesh.triangles;
  const size_t nv = cut.input_vertices, ne = topology.edges.size(), vertices = cut.mesh.positions.size();
  // cut_along_edges lists the split vertices in ascending order, each once per copy.
  std::vector<uint32_t> split = cut.copy_of;
  split.erase(std::unique(split.begin(), split.end()), split.end());
  // The cut mesh's vertex at corner `source` of triangle t.
  auto renamed = [&](uint32_t t, uint32_t source) {
    for (uint32_t v : tris[t])
      if (cut.source(v) == source) return v;
    return kNone;
  };

  // Only the edges at split vertices can change: each triangle's half-edge
  // takes its renamed ends, and the two stay one edge only if those agree.
  std::vector<uint32_t> at_split;
  for (uint32_t v : split)
    for (uint32_t i = topology.vertex_offsets[v]; i < topology.vertex_offsets[v + 1]; ++i)
      for (uint32_t e : topology.triangle_edges[topology.vertex_triangles[i]])
        if (topology.edges[e][0] == v || topology.edges[e][1] == v) at_split.push_back(e);
  std::sort(at_split.begin(), at_split.end());
  at_split.erase(std::unique(at_split.begin(), at_split.end()), at_split.end());
  // The split vertices' boundary flags are recomputed from these edges (all
  // of theirs); a vertex that did not split can only gain one (an edge at it
  // may come apart, never close).
  topology.boundary_vertex.resize(vertices, 0);
  for (uint32_t v : split) topology.boundary_vertex[v] = 0;
  auto mark_boundary = [&](uint64_t key) {
    topology.boundary_vertex[key >> 32] = topology.boundary_vertex[uint32_t(key)] = 1;
  };
  auto at = [&](uint64_t key) {
    return static_cast<uint32_t>(
        std::lower_bound(topology.edges.begin(), topology.edges.end(), key,
                         [](const std::array<uint32_t, 2>& x, uint64_t y) { return key_of(x) < y; }) -
        topology.edges.begin());
  };
  std::vector<Piece> pieces;
  std::vector<uint32_t> removed;  // input edges replaced by pieces, ascending
  for (uint32_t e : at_split) {
    const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];  // not a binding: the lambda below captures them
    const auto [t0, t1] = topology.edge_triangles[e];
    auto key = [&](uint32_t t) {
      const uint32_t a = renamed(t, p), b = renamed(t, q);
      return uint64_t{std::min(a, b)} << 32 | std::max(a, b);
    };
    auto corner = [&](uint32_t t) {
      uint32_t k = 0;
      while (k < 2 && topology.triangle_edges[t][k] != e) ++k;
      return 3 * t + k;
    };
    const uint64_t k0 = key(t0);
    const bool whole = t1 == kNone || key(t1) == k0;
    if (t1 == kNone || !whole) mark_boundary(k0);
    if (whole && k0 == key_of(topology.edges[e])) continue;  // unchanged: keeps its place
    removed.push_back(e);
    if (whole) {
      pieces.push_back({k0, {t0, t1}, {corner(t0), t1 == kNone ? kNone : corner(t1)}, at(k0), 0});
      continue;
    }
    const uint64_t k1 = key(t1);
    mark_boundary(k1);
    pieces.push_back({k0, {t0, kNone}, {corner(t0), kNone}, at(k0), 0});
    pieces.push_back({k1, {t1, kNone}, {corner(t1), kNone}, at(k1), 0});
  }
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.key < b.key; });

  // build_topology numbers edges by (smaller end, larger end): the unchanged
  // edges keep their order, in runs between the removed edges and the
  // pieces' places, and the pieces are merged in.
  // Appended to, not sized first: every entry is written once (no zero fill).
  const size_t count = ne - removed.size() + pieces.size();
  std::vector<std::array<uint32_t, 2>> edges, edge_triangles;
  edges.reserve(count), edge_triangles.reserve(count);
  size_t read = 0, write = 0, next_piece = 0, next_removed = 0;
  while (read < ne || next_piece < pieces.size()) {
    size_t stop = next_removed < removed.size() ? removed[next_removed] : ne;
    if (next_piece < pieces.size()) stop = std::min<size_t>(stop, pieces[next_piece].at);
    edges.insert(edges.end(), topology.edges.begin() + read, topology.edges.begin() + stop);
    edge_triangles.insert(edge_triangles.end(), topology.edge_triangles.begin() + read,
                          topology.edge_triangles.begin() + stop);
    // Once copied, an input edge's first slot holds its new number: the
    // renumbering table costs no fresh memory (4 bytes per edge otherwise).
    for (; read < stop; ++read, ++write) topology.edges[read][0] = static_cast<uint32_t>(write);
    for (; next_piece < pieces.size() && pieces[next_piece].at == read; ++next_piece, ++write) {
      Piece& x = pieces[next_piece];
      x.index = static_cast<uint32_t>(write);
      edges.push_back({uint32_t(x.key >> 32), uint32_t(x.key)});
      edge_triangles.push_back(x.triangles);
    }
    if (next_removed < removed.size() && removed[next_removed] == read) ++read, ++next_removed;
  }
  // The half-edges of removed edges get the pieces' numbers below. Each
  // triangle's entries alone, on every thread.
  parallel_for(topology.triangle_edges.size(), [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t)
      for (uint32_t& e : topology.triangle_edges[t]) e = topology.edges[e][0];
  });
  topology.edges = std::move(edges);
  topology.edge_triangles = std::move(edge_triangles);
  for (const Piece& x : pieces)
    for (uint32_t c : x.corners)
      if (c != kNone) topology.triangle_edges[c / 3][c % 3] = x.index;

  // Each vertex's triangles stay in ascending order: a split vertex keeps
  // those whose corner is still it, the others go to its copies, whose fans
  // follow every input vertex's. The fans between split vertices move as blocks.
  std::vector<uint32_t>& offsets = topology.vertex_offsets;
  std::vector<uint32_t>& fans = topology.vertex_triangles;
  std::vector<std::pair<uint32_t, uint32_t>> moved;  // (copy, triangle)
  uint32_t shift = 0, first = 0;                     // triangles moved so far; the block's first vertex
  for (size_t i = 0; i <= split.size(); ++i) {
    const uint32_t s = i < split.size() ? split[i] : static_cast<uint32_t>(nv);
    if (shift) {
      std::copy(fans.begin() + offsets[first], fans.begin() + offsets[s], fans.begin() + (offsets[first] - shift));
      for (uint32_t v = first; v < s; ++v) offsets[v] -= shift;
    }
    if (s == nv) break;
    const uint32_t begin = offsets[s], end = offsets[s + 1];
    offsets[s] = begin - shift;
    uint32_t kept = offsets[s];
    for (uint32_t j = begin; j < end; ++j) {
      const uint32_t t = fans[j], v = renamed(t, s);
      if (v == s)
        fans[kept++] = t;
      else
        moved.emplace_back(v, t);
    }
    shift = end - kept;
    first = s + 1;
  }
  offsets[nv] -= shift;
  std::sort(moved.begin(), moved.end());
  offsets.resize(vertices + 1);
  for (size_t k = 0, c = nv; c < vertices; ++c) {
    offsets[c + 1] = offsets[c];
    for (; k < moved.size() && moved[k].first == c; ++k) fans[offsets[c + 1]++] = moved[k].second;
  }
  return topology;
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
