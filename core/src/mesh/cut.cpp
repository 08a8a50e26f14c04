#include "crestline/mesh/cut.h"

#include <algorithm>
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

Topology cut_topology(const Topology& input, const CutMesh& cut) {
  const std::vector<Triangle>& tris = cut.mesh.triangles;
  const size_t nv = cut.input_vertices, ne = input.edges.size();
  std::vector<uint8_t> split(nv, 0);
  for (uint32_t v : cut.copy_of) split[v] = 1;
  // The cut mesh's vertex at corner `source` of triangle t.
  auto renamed = [&](uint32_t t, uint32_t source) {
    for (uint32_t v : tris[t])
      if (cut.source(v) == source) return v;
    return kNone;
  };

  // Edges at a split vertex: each triangle's half-edge takes its renamed
  // ends, and the two stay one edge only if those agree. The rest keep their
  // ends and triangles; build_topology orders edges by (smaller end, larger
  // end), so both lists are merged in that order.
  struct Piece {
    uint64_t key;  // smaller end << 32 | larger end
    uint32_t triangles[2];
    uint32_t edge;  // of the input
    uint8_t slot;   // the input edge's first piece (0) or second (1)
  };
  std::vector<Piece> pieces;
  for (uint32_t e = 0; e < ne; ++e) {
    const uint32_t p = input.edges[e][0], q = input.edges[e][1];  // not a binding: the lambda below captures them
    if (!split[p] && !split[q]) continue;
    const auto [t0, t1] = input.edge_triangles[e];
    auto key = [&](uint32_t t) {
      const uint32_t a = renamed(t, p), b = renamed(t, q);
      return uint64_t{std::min(a, b)} << 32 | std::max(a, b);
    };
    const uint64_t k0 = key(t0);
    if (t1 != kNone && key(t1) == k0) {
      pieces.push_back({k0, {t0, t1}, e, 0});
      continue;
    }
    pieces.push_back({k0, {t0, kNone}, e, 0});
    if (t1 != kNone) pieces.push_back({key(t1), {t1, kNone}, e, 1});
  }
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.key < b.key; });

  Topology out;
  const size_t edge_count =
      ne - std::count_if(pieces.begin(), pieces.end(), [](const Piece& x) { return x.slot == 0; }) + pieces.size();
  out.edges.reserve(edge_count);
  out.edge_triangles.reserve(edge_count);
  // new_edge[e]: the new index of the unchanged edge, or of a split one's
  // first piece; second[e]: of its second piece where it came apart.
  std::vector<uint32_t> new_edge(ne, kNone), second(ne, kNone);
  size_t next_piece = 0;
  auto emit_pieces_before = [&](uint64_t key) {
    for (; next_piece < pieces.size() && pieces[next_piece].key < key; ++next_piece) {
      const Piece& x = pieces[next_piece];
      (x.slot ? second : new_edge)[x.edge] = static_cast<uint32_t>(out.edges.size());
      out.edges.push_back({uint32_t(x.key >> 32), uint32_t(x.key)});
      out.edge_triangles.push_back({x.triangles[0], x.triangles[1]});
    }
  };
  for (uint32_t e = 0; e < ne; ++e) {
    const auto [p, q] = input.edges[e];
    if (split[p] || split[q]) continue;
    emit_pieces_before(uint64_t{p} << 32 | q);
    new_edge[e] = static_cast<uint32_t>(out.edges.size());
    out.edges.push_back(input.edges[e]);
    out.edge_triangles.push_back(input.edge_triangles[e]);
  }
  emit_pieces_before(~uint64_t{0});

  out.triangle_edges.resize(tris.size());
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t e = input.triangle_edges[t][k];
      out.triangle_edges[t][k] = second[e] != kNone && input.edge_triangles[e][1] == t ? second[e] : new_edge[e];
    }

  // Each vertex's triangles in ascending order: a split vertex's go to the
  // side (the vertex or a copy) their corner was renamed to.
  const size_t vertices = cut.mesh.positions.size();
  out.vertex_offsets.assign(vertices + 1, 0);
  for (uint32_t v = 0; v < nv; ++v) {
    const uint32_t begin = input.vertex_offsets[v], end = input.vertex_offsets[v + 1];
    if (!split[v]) {
      out.vertex_offsets[v + 1] = end - begin;
      continue;
    }
    for (uint32_t i = begin; i < end; ++i) ++out.vertex_offsets[renamed(input.vertex_triangles[i], v) + 1];
  }
  for (size_t v = 0; v < vertices; ++v) out.vertex_offsets[v + 1] += out.vertex_offsets[v];
  out.vertex_triangles.resize(out.vertex_offsets[vertices]);
  std::vector<uint32_t> fill(out.vertex_offsets.begin(), out.vertex_offsets.end() - 1);
  for (uint32_t v = 0; v < nv; ++v)
    for (uint32_t i = input.vertex_offsets[v]; i < input.vertex_offsets[v + 1]; ++i) {
      const uint32_t t = input.vertex_triangles[i];
      out.vertex_triangles[fill[split[v] ? renamed(t, v) : v]++] = t;
    }

  out.boundary_vertex.assign(vertices, 0);
  for (size_t e = 0; e < out.edges.size(); ++e)
    if (out.is_boundary_edge(static_cast<uint32_t>(e)))
      out.boundary_vertex[out.edges[e][0]] = out.boundary_vertex[out.edges[e][1]] = 1;
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
