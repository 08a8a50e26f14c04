#include "crestline/mesh/repair.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <numeric>
#include <string>

#include "crestline/error.h"
#include "crestline/mesh/topology.h"
#include "crestline/numerics/parallel.h"
#include "half_edges.h"

namespace crestline {
namespace {

constexpr double kMinDiagonal = 1e-140, kMaxDiagonal = 1e140;

std::string short_number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

// 0 … count − 1 ordered as one global sort by (bucket(i), less) would
// order them, in linear time for the few items per bucket here (a vertex's
// triangles or half-edges): a counting sort by bucket, which keeps index
// order, then a sort of each bucket. 4 bytes per item instead of the 16 of
// sorting (key, index) pairs.
template <typename Bucket, typename Less>
std::vector<uint32_t> bucket_order(size_t count, size_t buckets, const Bucket& bucket, const Less& less) {
  std::vector<uint32_t> start, order;
  detail::group_by_bucket(
      count, buckets, [&](size_t i, const auto& emit) { emit(bucket(i), static_cast<uint32_t>(i)); }, start, order);
  parallel_for(buckets, [&](size_t first, size_t last) {
    for (size_t b = first; b < last; ++b)
      std::sort(order.begin() + ptrdiff_t(start[b]), order.begin() + ptrdiff_t(start[b + 1]), less);
  });
  return order;
}

// A triangle's vertices in ascending order.
Triangle sorted_corners(Triangle t) {
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  if (t[1] > t[2]) std::swap(t[1], t[2]);
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  return t;
}

std::string count_text(size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

void check_soup(const TriangleSoup& soup, const RepairOptions& options) {
  if (soup.positions.size() % 3 != 0)
    throw Error(ErrorKind::InvalidInput, "the vertex array length is not a multiple of 3.");
  if (soup.indices.size() % 3 != 0)
    throw Error(ErrorKind::InvalidInput, "the index array length is not a multiple of 3.");
  if (soup.triangle_count() > options.max_triangles)
    throw Error(ErrorKind::TooLarge, "the mesh has " + std::to_string(soup.triangle_count()) +
                                         " triangles, more than the limit of " + std::to_string(options.max_triangles) +
                                         ".");
  if (soup.triangle_count() == 0) throw Error(ErrorKind::InvalidInput, "the mesh contains no triangles.");
  const size_t nv = soup.vertex_count();
  for (size_t i = 0; i < soup.indices.size(); ++i)
    if (soup.indices[i] >= nv)
      throw Error(ErrorKind::InvalidInput, "triangle " + std::to_string(i / 3) + " refers to vertex " +
                                               std::to_string(soup.indices[i]) + " but there are only " +
                                               std::to_string(nv) + " vertices.");
}

// Merges vertices closer than `tolerance`: vertex i joins the earliest
// representative (a vertex that joined no other) j < i within tolerance, or
// represents itself. The grid is a flat open-addressing table from cell to a
// list (through `next`) of the vertices in it: one probe per cell instead of
// a node chase. Cells measure 16 tolerances, so the box of ±tolerance (plus
// a margin of half a tolerance for rounding) around a vertex spans 3/16 of a
// cell per axis: 1.7 probes on average (1 to 8), where cells of 2
// tolerances took 15.6 (8 to 27). Vertices closer than a few cells are rare
// at a tolerance of 1e-7 of the diagonal (seam copies sit at distance 0),
// so the lists stay short. The result does not depend on the cells: exact
// distances decide.
// On several threads the table holds every vertex; the searches run on every thread and find
// the earliest vertex within tolerance, which is the answer unless that
// vertex joined another one itself (a chain, rare: seams have exact copies);
// those few are searched again in input order, among representatives only.
// Only `weldable` vertices (finite and used by a triangle, so inside the
// bounding box) take part: unreferenced ones far away would share clamped cells.
std::vector<uint32_t> weld(const std::vector<Vec3>& points, const std::vector<uint8_t>& weldable, const Vec3& lo,
                           double tolerance, size_t& welded) {
  std::vector<uint32_t> representative(points.size());
  std::iota(representative.begin(), representative.end(), 0u);
  if (!(tolerance > 0)) return representative;
  constexpr double kCell = 16;                                 // cell size in tolerances
  constexpr double kReach = 1.5 / kCell;                       // tolerance and margin, in cells
  if (!std::isfinite(0.5 / tolerance)) return representative;  // a subnormal tolerance: nothing to weld
  const double inv = 1 / (kCell * tolerance);
  // A weldable vertex lies in the box from `lo`, so its coordinates in
  // cells, shifted by one cell, are at least 1 and every coordinate searched
  // (within kReach of one) is positive: truncation is the floor. Clamped
  // above so the conversion is defined (a tiny weld tolerance).
  auto scaled = [&](const Vec3& p) -> Vec3 { return ((p - lo) * inv).array() + 1.0; };
  auto cell = [](double q) {
    constexpr double limit = 4e18;
    return q < limit ? static_cast<int64_t>(q) : int64_t(limit);
  };
  auto cell_key = [](int64_t x, int64_t y, int64_t z) {
    return static_cast<uint64_t>(x) * 73856093u ^ static_cast<uint64_t>(y) * 19349663u ^
           static_cast<uint64_t>(z) * 83492791u;
  };
  int bits = 1;
  while ((size_t{1} << bits) < 2 * points.size()) ++bits;
  const size_t mask = (size_t{1} << bits) - 1;
  std::vector<uint64_t> keys(mask + 1);
  std::vector<uint32_t> head(mask + 1, kNone), next(points.size(), kNone);
  // The slot of a cell (empty if head == kNone); cells whose keys collide
  // share a list, which only costs distance tests.
  auto slot = [&](uint64_t key) {
    size_t s = static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - bits));
    while (head[s] != kNone && keys[s] != key) s = (s + 1) & mask;
    return s;
  };
  auto key_of = [&](uint32_t i) {
    const Vec3 q = scaled(points[i]);
    return cell_key(cell(q.x()), cell(q.y()), cell(q.z()));
  };
  // Lists in descending index order (each vertex is pushed at its head).
  auto insert = [&](uint32_t i, uint64_t key) {
    const size_t s = slot(key);
    keys[s] = key;
    next[i] = head[s];
    head[s] = i;
  };
  const double tol2 = tolerance * tolerance;
  // The earliest vertex j < i within tolerance (among representatives only
  // if `representatives_only`).
  auto earliest = [&](uint32_t i, bool representatives_only) {
    const Vec3 q = scaled(points[i]);
    const int64_t x0 = cell(q.x() - kReach), x1 = cell(q.x() + kReach), y0 = cell(q.y() - kReach),
                  y1 = cell(q.y() + kReach), z0 = cell(q.z() - kReach), z1 = cell(q.z() + kReach);
    uint32_t found = kNone;
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t z = z0; z <= z1; ++z)
          for (uint32_t j = head[slot(cell_key(x, y, z))]; j != kNone; j = next[j])
            if (j < i && j < found && (!representatives_only || representative[j] == j) &&
                (points[j] - points[i]).squaredNorm() <= tol2)
              found = j;
    return found;
  };
  if (max_threads() == 1) {
    // One thread: insert as we go, representatives only. The same answer
    // (the earliest representative within tolerance) from a table with a
    // sixth of the entries on a soup, so fewer cache misses per search.
    for (uint32_t i = 0; i < points.size(); ++i) {
      if (!weldable[i]) continue;
      const uint32_t found = earliest(i, false);
      if (found != kNone)
        representative[i] = found, ++welded;
      else
        insert(i, key_of(i));
    }
    return representative;
  }
  // Several threads: the keys on every thread, then the table in input order.
  std::vector<uint64_t> vertex_key(points.size());
  parallel_for(points.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      if (weldable[i]) vertex_key[i] = key_of(uint32_t(i));
  });
  for (uint32_t i = 0; i < points.size(); ++i)
    if (weldable[i]) insert(i, vertex_key[i]);
  vertex_key = std::vector<uint64_t>();
  std::vector<uint32_t> nearest(points.size(), kNone);
  parallel_for(points.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      if (weldable[i]) nearest[i] = earliest(static_cast<uint32_t>(i), false);
  });
  for (uint32_t i = 0; i < points.size(); ++i) {
    uint32_t found = nearest[i];
    if (found == kNone) continue;
    if (representative[found] != found) found = earliest(i, true);
    if (found != kNone) representative[i] = found, ++welded;
  }
  return representative;
}

// Half-edges (corners) paired across their undirected edges: the partner
// across a manifold edge, whether it runs the same way, and every corner of
// a non-manifold edge cut. Also finds duplicate triangles (the same three
// vertices): two of them share all three edges, and in each edge's group
// they have the same opposite corner; conversely two half-edges of one edge
// with the same opposite corner are a duplicate pair. So a clean mesh needs
// no pass of its own to prove it has none.
struct EdgePairs {
  std::vector<uint32_t> partner;  // the corner across a manifold edge, kNone elsewhere
  std::vector<uint8_t> same;      // partner runs the same way (the triangles disagree)
  std::vector<uint8_t> cut;       // 3 per triangle, edge k = corners k, k+1
  size_t nonmanifold = 0;         // edges of more than two triangles
  size_t single = 0;              // edges of one triangle
  bool duplicates = false;        // two triangles have the same three vertices
};

EdgePairs pair_half_edges(const std::vector<Triangle>& tris, size_t vertex_count) {
  const size_t nt = tris.size();
  EdgePairs out;
  out.partner.assign(3 * nt, kNone);
  out.same.assign(3 * nt, 0);
  out.cut.assign(3 * nt, 0);
  const detail::HalfEdgeOrder order = detail::order_half_edges(tris, vertex_count);
  using H = detail::HalfEdgeOrder;
  auto from = [&](uint32_t c) { return tris[c / 3][c % 3]; };
  auto opposite = [&](uint32_t c) { return tris[c / 3][(c % 3 + 2) % 3]; };
  std::atomic<size_t> nonmanifold{0}, single{0};
  std::atomic<bool> duplicates{false};
  parallel_for(vertex_count, [&](size_t begin, size_t end) {
    size_t count = 0, singles = 0;
    bool repeated = false;
    order.for_each_edge(begin, end, [&](uint32_t, uint32_t, const uint64_t* first, const uint64_t* last) {
      if (last - first == 1) {
        ++singles;
      } else if (last - first == 2) {
        const uint32_t a = H::corner(first[0]), b = H::corner(first[1]);
        out.partner[a] = b, out.partner[b] = a;
        out.same[a] = out.same[b] = from(a) == from(b);
        repeated |= opposite(a) == opposite(b);
      } else {
        ++count;
        for (const uint64_t* h = first; h < last; ++h) {
          out.cut[H::corner(*h)] = 1;
          for (const uint64_t* g = first; g < h; ++g) repeated |= opposite(H::corner(*g)) == opposite(H::corner(*h));
        }
      }
    });
    nonmanifold += count;
    single += singles;
    if (repeated) duplicates = true;
  });
  out.nonmanifold = nonmanifold;
  out.single = single;
  out.duplicates = duplicates;
  return out;
}

// Drops triangles with the same vertex set as an earlier one: bucketed by
// the smallest vertex, ordered by the other two (one key).
void drop_duplicates(std::vector<Triangle>& tris, size_t vertex_count, RepairReport& report) {
  std::vector<uint64_t> larger(tris.size());
  for (size_t t = 0; t < tris.size(); ++t) {
    const Triangle k = sorted_corners(tris[t]);
    larger[t] = uint64_t{k[1]} << 32 | k[2];
  }
  const auto smallest = [&](size_t t) { return std::min({tris[t][0], tris[t][1], tris[t][2]}); };
  const std::vector<uint32_t> keyed = bucket_order(tris.size(), vertex_count, smallest, [&](uint32_t x, uint32_t y) {
    return larger[x] != larger[y] ? larger[x] < larger[y] : x < y;
  });
  std::vector<uint8_t> keep(tris.size(), 1);
  for (size_t i = 1; i < keyed.size(); ++i)
    if (larger[keyed[i]] == larger[keyed[i - 1]] && smallest(keyed[i]) == smallest(keyed[i - 1]))
      keep[keyed[i]] = 0, ++report.duplicate_triangles;
  size_t n = 0;
  for (size_t t = 0; t < tris.size(); ++t)
    if (keep[t]) tris[n++] = tris[t];
  tris.resize(n);
}

// Orients triangles consistently across shared edges, component by
// component; edges that cannot agree (non-orientable surfaces) are cut.
// Returns per-corner "edge is cut" flags and the component of each triangle.
struct Orientation {
  std::vector<uint8_t> cut;  // 3 per triangle, edge k = corners k, k+1
  // EdgePairs::partner, its slots following the flips (its values still
  // name the other triangle, the corner there as paired): split_fans walks it.
  std::vector<uint32_t> partner;
  std::vector<uint32_t> component;
  size_t components = 0;
  size_t single_edges = 0;  // edges of one triangle: boundary edges whatever the repair does
};

Orientation orient(std::vector<Triangle>& tris, const std::vector<Vec3>& points, EdgePairs pairs,
                   RepairReport& report) {
  const size_t nt = tris.size();
  Orientation out;
  out.cut = std::move(pairs.cut);
  out.component.assign(nt, kNone);
  report.nonmanifold_edges += pairs.nonmanifold;
  out.single_edges = pairs.single;
  out.partner = std::move(pairs.partner);
  const std::vector<uint32_t>& partner = out.partner;
  std::vector<uint8_t>& same = pairs.same;

  // The traversal, component by component: a triangle is flipped relative to
  // the component's first triangle (its seed, the smallest index) when an odd
  // number of disagreeing edges lead to it. `members` lists every component's
  // triangles in traversal order, component c from member_start[c].
  // A component is closed when none of its corners lacks a partner or is
  // cut (a cut made here is between two of its own triangles).
  std::vector<uint8_t> flipped(nt, 0), closed;
  std::vector<uint32_t> stack, members, member_start;
  members.reserve(nt);
  for (uint32_t seed = 0; seed < nt; ++seed) {
    if (out.component[seed] != kNone) continue;
    const uint32_t c = static_cast<uint32_t>(out.components++);
    member_start.push_back(static_cast<uint32_t>(members.size()));
    closed.push_back(1);
    stack.assign(1, seed);
    out.component[seed] = c;
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      members.push_back(t);
      for (uint32_t corner = 3 * t; corner < 3 * t + 3; ++corner) {
        const uint32_t other = partner[corner];
        if (other == kNone || out.cut[corner]) {
          closed[c] = 0;
          continue;
        }
        const uint32_t u = other / 3;
        const uint8_t disagree = same[corner] ^ flipped[t];
        if (out.component[u] == kNone) {
          flipped[u] = disagree;
          out.component[u] = c;
          stack.push_back(u);
        } else if (disagree != flipped[u]) {
          out.cut[corner] = out.cut[other] = 1;  // non-orientable here
          closed[c] = 0;
        }
      }
    }
  }
  member_start.push_back(static_cast<uint32_t>(members.size()));
  same = std::vector<uint8_t>();

  // Closed components face outwards: the signed volume of each triangle about
  // the first corner of its component, in units of the component's first
  // edge (the same sign at any position and scale), on every thread; each
  // component's terms are then added in traversal order.
  std::vector<double> volume(nt, 0);
  parallel_for(nt, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const uint32_t c = out.component[t];
      if (!closed[c]) continue;
      const Triangle& first = tris[members[member_start[c]]];
      const Vec3& origin = points[first[0]];
      const double unit = (points[first[1]] - origin).norm();
      const double inv_unit = unit > 0 ? 1 / unit : 1;
      const Triangle& f = tris[t];
      const Vec3 a = (points[f[0]] - origin) * inv_unit, b = (points[f[1]] - origin) * inv_unit,
                 d = (points[f[2]] - origin) * inv_unit;
      volume[t] = a.dot(b.cross(d));
    }
  });
  // Keep the orientation most of the file agreed on; closed components then
  // face outwards (positive signed volume).
  std::vector<uint8_t> invert(out.components, 0);
  for (size_t c = 0; c < out.components; ++c) {
    const uint32_t* first = members.data() + member_start[c];
    const uint32_t* last = members.data() + member_start[c + 1];
    size_t nflip = 0;
    for (const uint32_t* t = first; t < last; ++t) nflip += flipped[*t];
    bool flip_all = 2 * nflip > size_t(last - first);
    if (closed[c]) {
      double sum = 0;
      for (const uint32_t* t = first; t < last; ++t) sum += (flipped[*t] != flip_all) ? -volume[*t] : volume[*t];
      flip_all = flip_all != (sum < 0);
    }
    invert[c] = flip_all;
    report.flipped_triangles += flip_all ? size_t(last - first) - nflip : nflip;
  }
  parallel_for(nt, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t)
      if (flipped[t] != invert[out.component[t]]) {
        std::swap(tris[t][1], tris[t][2]);
        // Corner k of the swapped triangle: edges (0,2),(2,1),(1,0) — remap cut flags.
        uint8_t* cut = &out.cut[3 * t];
        std::swap(cut[0], cut[2]);
        std::swap(out.partner[3 * t], out.partner[3 * t + 2]);
      }
  });
  return out;
}

// Splits every vertex whose triangles form several fans (connected through
// uncut edges around it) into one vertex per fan: the fan of the vertex's
// first corner keeps it, the others get copies, numbered in vertex order and
// at each vertex in the order of their first corners.
//
// A fan is walked over the half-edge pairing, from corner to corner across
// the uncut edges at its vertex (the triangles agree in orientation across
// those, so the edge leaving v in one enters v in the next), instead of
// grouping every vertex's corners: ~5 bytes per triangle of fresh memory
// instead of ~30. A fan holding all of its vertex's triangles is the
// vertex's only one: nearly every fan. The rest, found on every thread, are
// sorted by (vertex, first corner).
void split_fans(std::vector<Triangle>& tris, std::vector<Vec3>& points, const Orientation& orientation,
                RepairReport& report) {
  const size_t nv = points.size(), nt = tris.size();
  const std::vector<uint8_t>& cut = orientation.cut;
  const std::vector<uint32_t>& partner = orientation.partner;
  std::vector<uint32_t> triangles_at(nv, 0);
  for (const Triangle& t : tris)
    for (uint32_t v : t) ++triangles_at[v];
  // The corner at v of the triangle across the edge of corner `edge` (a
  // corner of v's triangle), or kNone where the edge is cut or has no other.
  auto across = [&](uint32_t edge, uint32_t v) {
    const uint32_t other = partner[edge];
    if (other == kNone || cut[edge]) return kNone;
    const uint32_t u = other / 3;
    return 3 * u + (tris[u][0] == v ? 0 : tris[u][1] == v ? 1 : 2);
  };
  // Calls visit(corner) for every corner of c's fan but c: first on through
  // the edges leaving v, then, on an open fan, back from c.
  auto for_fan = [&](uint32_t c, uint32_t v, const auto& visit) {
    for (uint32_t x = c;;) {
      x = across(x, v);
      if (x == c) return;
      if (x == kNone) break;
      visit(x);
    }
    for (uint32_t x = c;;) {
      x = across(3 * (x / 3) + (x + 2) % 3, v);
      if (x == kNone) break;
      visit(x);
    }
  };
  // (vertex << 32 | first corner) of every fan of a vertex of several.
  std::vector<uint64_t> fans;
  std::mutex fans_mutex;
  parallel_for(3 * nt, [&](size_t first, size_t last) {
    // Corners of this range already walked, as part of an earlier one's fan.
    std::vector<uint8_t> seen(last - first, 0);
    std::vector<uint64_t> found;
    for (size_t c = first; c < last; ++c) {
      if (seen[c - first]) continue;
      const uint32_t v = tris[c / 3][c % 3];
      uint32_t size = 1, lowest = uint32_t(c);
      for_fan(uint32_t(c), v, [&](uint32_t x) {
        ++size, lowest = std::min(lowest, x);
        if (x >= first && x < last) seen[x - first] = 1;
      });
      // Once per fan: from its first corner (the range that holds it).
      if (size < triangles_at[v] && lowest == c) found.push_back(uint64_t{v} << 32 | c);
    }
    if (found.empty()) return;
    const std::lock_guard<std::mutex> lock(fans_mutex);
    fans.insert(fans.end(), found.begin(), found.end());
  });
  if (fans.empty()) return;
  std::sort(fans.begin(), fans.end());
  // The copies of each vertex, in vertex order: its fans but the first.
  for (size_t i = 0; i < fans.size(); ++i) {
    const uint32_t v = uint32_t(fans[i] >> 32), c = uint32_t(fans[i]);
    if (i == 0 || fans[i - 1] >> 32 != v) {
      ++report.nonmanifold_vertices;
      continue;
    }
    const uint32_t copy = static_cast<uint32_t>(points.size());
    const Vec3 p = points[v];
    points.push_back(p);
    // Each corner renamed once walked past: a step finds v in the next
    // triangle, and c's last, when a closed fan comes back to it.
    for_fan(c, v, [&](uint32_t x) { tris[x / 3][x % 3] = copy; });
    tris[c / 3][c % 3] = copy;
  }
}

// Boundary edges of the repaired mesh, without grouping its half-edges
// again: an edge of one triangle stays one; the two triangles of an uncut
// edge share both its ends after the fans are split (they are in one fan at
// each end); only the cut edges' half-edges, few, are grouped anew by their
// renamed ends, and one left alone is a boundary edge.
size_t count_boundary_edges(const std::vector<Triangle>& tris, const Orientation& orientation) {
  std::vector<uint64_t> cut_edges;
  for (size_t c = 0; c < orientation.cut.size(); ++c)
    if (orientation.cut[c]) {
      const uint32_t a = tris[c / 3][c % 3], b = tris[c / 3][(c + 1) % 3];
      cut_edges.push_back(uint64_t{std::min(a, b)} << 32 | std::max(a, b));
    }
  std::sort(cut_edges.begin(), cut_edges.end());
  size_t boundary = orientation.single_edges;
  for (size_t i = 0, j = 0; i < cut_edges.size(); i = j) {
    while (j < cut_edges.size() && cut_edges[j] == cut_edges[i]) ++j;
    if (j - i > 2) throw Error(ErrorKind::InvalidInput, "the mesh has an edge that could not be made manifold.");
    boundary += j - i == 1;
  }
  return boundary;
}

}  // namespace

RepairResult repair_mesh(const TriangleSoup& soup, const RepairOptions& options) {
  check_soup(soup, options);
  RepairResult result;
  RepairReport& report = result.report;
  report.input_vertices = soup.vertex_count();
  report.input_triangles = soup.triangle_count();

  const size_t nv = soup.vertex_count();
  std::vector<Vec3> points(nv);
  std::vector<uint8_t> finite(nv);
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (size_t i = 0; i < nv; ++i) {
    points[i] = Vec3(soup.positions[3 * i], soup.positions[3 * i + 1], soup.positions[3 * i + 2]);
    finite[i] = points[i].allFinite();
  }
  std::vector<uint8_t> weldable(nv, 0);
  for (uint32_t v : soup.indices)
    if (finite[v]) lo = lo.cwiseMin(points[v]), hi = hi.cwiseMax(points[v]), weldable[v] = 1;
  // The diagonal measured without squaring raw coordinates (no underflow).
  const double extent = (hi - lo).cwiseAbs().maxCoeff();
  const double diagonal = extent > 0 && std::isfinite(extent) ? extent * ((hi - lo) / extent).norm() : extent;
  if (!std::isfinite(diagonal)) {
    if (!lo.allFinite()) throw Error(ErrorKind::InvalidInput, "no vertex of any triangle has finite coordinates.");
    throw Error(ErrorKind::InvalidInput, "the coordinates are too large to compute with (the bounding box overflows).");
  }
  // Beyond this range products of two coordinate differences (areas, squared
  // lengths) leave double precision; inside it every stage works (the
  // pipeline computes in a frame scaled to the mesh, see mesh/frame.h).
  if (diagonal > 0 && (diagonal < kMinDiagonal || diagonal > kMaxDiagonal))
    throw Error(ErrorKind::InvalidInput, "the coordinates are out of range: the model measures " +
                                             short_number(diagonal) + " units across, outside 1e-140 to 1e140.");

  const std::vector<uint32_t> rep =
      weld(points, weldable, lo, options.weld_tolerance * diagonal, report.welded_vertices);

  // Triangles on welded vertices; drop non-finite, degenerate and duplicates.
  std::vector<Triangle> tris;
  tris.reserve(soup.triangle_count());
  // Twice the area relative to the squared diagonal: sides are divided by the
  // diagonal first, so the test means the same at every scale (at 1e-100 the
  // squared cross product of raw coordinates would underflow to zero).
  constexpr double kMinRelativeDoubleArea = 1e-14;
  const double inv_diagonal = diagonal > 0 ? 1 / diagonal : 0;
  // The tests run on every thread (one status byte per triangle); the kept
  // triangles are then gathered in input order.
  enum : uint8_t { kKeep, kNonFinite, kDegenerate };
  std::vector<uint8_t> status(soup.triangle_count());
  parallel_for(status.size(), [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const Triangle f{rep[soup.indices[3 * t]], rep[soup.indices[3 * t + 1]], rep[soup.indices[3 * t + 2]]};
      if (!finite[f[0]] || !finite[f[1]] || !finite[f[2]])
        status[t] = kNonFinite;
      else if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] ||
               !(((points[f[1]] - points[f[0]]) * inv_diagonal)
                     .cross((points[f[2]] - points[f[0]]) * inv_diagonal)
                     .norm() > kMinRelativeDoubleArea))
        status[t] = kDegenerate;
      else
        status[t] = kKeep;
    }
  });
  for (size_t t = 0; t < status.size(); ++t) {
    if (status[t] == kKeep)
      tris.push_back({rep[soup.indices[3 * t]], rep[soup.indices[3 * t + 1]], rep[soup.indices[3 * t + 2]]});
    else
      ++(status[t] == kNonFinite ? report.nonfinite_triangles : report.degenerate_triangles);
  }
  status = std::vector<uint8_t>();
  if (tris.empty())
    throw Error(ErrorKind::InvalidInput,
                "no usable triangle remains (all are degenerate or have non-finite coordinates).");

  // Duplicates (the same vertex set; the first one stays) are found while
  // the half-edges are paired, and only a mesh that has some is paired again.
  EdgePairs pairs = pair_half_edges(tris, points.size());
  if (pairs.duplicates) {
    drop_duplicates(tris, points.size(), report);
    pairs = pair_half_edges(tris, points.size());
  }
  Orientation orientation = orient(tris, points, std::move(pairs), report);
  report.components = orientation.components;
  split_fans(tris, points, orientation, report);
  orientation.partner = std::vector<uint32_t>();

  // Compact: keep referenced vertices in first-use order of the input.
  std::vector<uint32_t> index(points.size(), kNone);
  uint32_t next = 0;
  std::vector<uint8_t> used(points.size(), 0);
  for (const Triangle& t : tris)
    for (uint32_t v : t) used[v] = 1;
  for (size_t v = 0; v < points.size(); ++v)
    if (used[v]) index[v] = next++;
  size_t input_used = 0;
  for (size_t v = 0; v < nv; ++v) input_used += used[v];
  report.unreferenced_vertices = nv - report.welded_vertices - input_used;
  result.mesh.positions.resize(next);
  for (size_t v = 0; v < points.size(); ++v)
    if (used[v]) result.mesh.positions[index[v]] = points[v];
  result.mesh.triangles = std::move(tris);
  for (Triangle& t : result.mesh.triangles)
    for (uint32_t& v : t) v = index[v];

  report.boundary_edges = count_boundary_edges(result.mesh.triangles, orientation);
  return result;
}

std::vector<std::string> RepairReport::notes() const {
  std::vector<std::string> out;
  auto add = [&](size_t n, const std::string& text) {
    if (n) out.push_back(text);
  };
  add(welded_vertices, "Welded " + count_text(welded_vertices, "duplicate vertex", "duplicate vertices") + ".");
  add(nonfinite_triangles,
      "Dropped " + count_text(nonfinite_triangles, "triangle", "triangles") + " with non-finite coordinates.");
  add(degenerate_triangles,
      "Dropped " + count_text(degenerate_triangles, "degenerate triangle", "degenerate triangles") + ".");
  add(duplicate_triangles,
      "Dropped " + count_text(duplicate_triangles, "duplicate triangle", "duplicate triangles") + ".");
  add(unreferenced_vertices,
      "Dropped " + count_text(unreferenced_vertices, "unreferenced vertex", "unreferenced vertices") + ".");
  add(nonmanifold_edges, "Cut " + count_text(nonmanifold_edges, "non-manifold edge", "non-manifold edges") + ".");
  add(nonmanifold_vertices,
      "Split " + count_text(nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices") + ".");
  add(flipped_triangles,
      "Reoriented " + count_text(flipped_triangles, "triangle", "triangles") + " to agree with their neighbours.");
  return out;
}

}  // namespace crestline
