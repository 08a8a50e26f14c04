#include "crestline/mesh/repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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
  std::vector<uint32_t> start(buckets + 1, 0);
  for (size_t i = 0; i < count; ++i) ++start[bucket(i) + 1];
  for (size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<uint32_t> order(count);
  for (size_t i = 0; i < count; ++i) order[start[bucket(i)]++] = static_cast<uint32_t>(i);
  // start[b] is now where bucket b ends.
  for (size_t b = 0, begin = 0; b < buckets; begin = start[b++])
    std::sort(order.begin() + ptrdiff_t(begin), order.begin() + ptrdiff_t(start[b]), less);
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

// Union-find over 0 … n − 1, reset per use without allocating.
struct Union {
  std::vector<uint32_t> parent;
  void reset(size_t n) {
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0u);
  }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Merges vertices closer than `tolerance` with a hash grid; the first vertex
// of a cluster (in input order) represents it. The grid is a flat
// open-addressing table from cell to a list (through `next`) of the
// representatives in it: one probe per cell instead of a node chase. Cells
// measure twice the tolerance, so the box of ±tolerance (plus a margin of
// half a tolerance for rounding) around a vertex touches at most two cells
// per axis: 1 to 8 probes instead of the 27 of tolerance-sized cells. The
// result does not depend on the cells: the earliest representative within
// tolerance, found by exact distances.
// Only `weldable` vertices (finite and used by a triangle, so inside the
// bounding box) take part: unreferenced ones far away would share clamped cells.
std::vector<uint32_t> weld(const std::vector<Vec3>& points, const std::vector<uint8_t>& weldable, const Vec3& lo,
                           double tolerance, size_t& welded) {
  std::vector<uint32_t> representative(points.size());
  std::iota(representative.begin(), representative.end(), 0u);
  if (!(tolerance > 0)) return representative;
  const double inv = 0.5 / tolerance;
  if (!std::isfinite(inv)) return representative;  // a subnormal tolerance: nothing to weld
  // Grid cell of a scaled coordinate, clamped so the conversion is defined.
  auto cell = [](double q) {
    constexpr double limit = 4e18;
    if (!(q < limit)) return int64_t(limit);
    if (q <= -limit) return -int64_t(limit);
    const int64_t c = static_cast<int64_t>(q);  // toward zero, then down: floor without a libm call
    return c - int64_t(static_cast<double>(c) > q);
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
  const double tol2 = tolerance * tolerance;
  for (uint32_t i = 0; i < points.size(); ++i) {
    if (!weldable[i]) continue;
    const Vec3 q = (points[i] - lo) * inv;
    // A tolerance is half a cell; the search reaches 0.75 cells either way.
    const int64_t x0 = cell(q.x() - 0.75), x1 = cell(q.x() + 0.75), y0 = cell(q.y() - 0.75), y1 = cell(q.y() + 0.75),
                  z0 = cell(q.z() - 0.75), z1 = cell(q.z() + 0.75);
    uint32_t found = kNone;  // the earliest representative within tolerance
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t z = z0; z <= z1; ++z)
          for (uint32_t j = head[slot(cell_key(x, y, z))]; j != kNone; j = next[j])
            if (j < found && (points[j] - points[i]).squaredNorm() <= tol2) found = j;
    if (found == kNone) {
      const uint64_t key = cell_key(cell(q.x()), cell(q.y()), cell(q.z()));
      const size_t s = slot(key);
      keys[s] = key;
      next[i] = head[s];
      head[s] = i;
    } else {
      representative[i] = found;
      ++welded;
    }
  }
  return representative;
}

// Orients triangles consistently across shared edges, component by
// component; edges that cannot agree (non-orientable surfaces) are cut.
// Returns per-corner "edge is cut" flags and the component of each triangle.
struct Orientation {
  std::vector<uint8_t> cut;  // 3 per triangle, edge k = corners k, k+1
  std::vector<uint32_t> component;
  size_t components = 0;
};

Orientation orient(std::vector<Triangle>& tris, const std::vector<Vec3>& points, RepairReport& report) {
  const size_t nt = tris.size();
  Orientation out;
  out.cut.assign(3 * nt, 0);
  out.component.assign(nt, kNone);

  // Half-edges (corners) grouped by undirected edge.
  std::vector<uint32_t> partner(3 * nt, kNone);  // the corner across a manifold edge
  detail::order_half_edges(tris, points.size())
      .for_each_edge([&](uint32_t, uint32_t, const uint64_t* first, const uint64_t* last) {
        using H = detail::HalfEdgeOrder;
        if (last - first == 2) {
          partner[H::corner(first[0])] = H::corner(first[1]);
          partner[H::corner(first[1])] = H::corner(first[0]);
        } else if (last - first > 2) {
          ++report.nonmanifold_edges;
          for (const uint64_t* h = first; h < last; ++h) out.cut[H::corner(*h)] = 1;
        }
      });

  std::vector<uint8_t> flipped(nt, 0);
  std::vector<uint32_t> stack, members;
  auto directed = [&](uint32_t corner, bool flip) {
    const Triangle& t = tris[corner / 3];
    uint32_t a = t[corner % 3], b = t[(corner % 3 + 1) % 3];
    return flip ? std::make_pair(b, a) : std::make_pair(a, b);
  };
  for (uint32_t seed = 0; seed < nt; ++seed) {
    if (out.component[seed] != kNone) continue;
    const uint32_t c = static_cast<uint32_t>(out.components++);
    members.clear();
    stack.assign(1, seed);
    out.component[seed] = c;
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      members.push_back(t);
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t corner = 3 * t + k, other = partner[corner];
        if (other == kNone || out.cut[corner]) continue;
        const uint32_t u = other / 3;
        const auto mine = directed(corner, flipped[t]);
        if (out.component[u] == kNone) {
          // Neighbours agree when they traverse the shared edge in opposite directions.
          flipped[u] = directed(other, false) == mine;
          out.component[u] = c;
          stack.push_back(u);
        } else if (directed(other, flipped[u]) == mine) {
          out.cut[corner] = out.cut[other] = 1;  // non-orientable here
        }
      }
    }
    // Keep the orientation most of the file agreed on; closed components then
    // face outwards (positive signed volume).
    size_t nflip = 0;
    for (uint32_t t : members) nflip += flipped[t];
    bool invert = 2 * nflip > members.size();
    bool closed = true;
    for (uint32_t t : members)
      for (uint32_t k = 0; k < 3; ++k) closed = closed && partner[3 * t + k] != kNone && !out.cut[3 * t + k];
    if (closed) {
      // Signed volume about the first corner of the component, in units of
      // its first edge: the same sign at any position and scale.
      const Vec3& origin = points[tris[members[0]][0]];
      const double unit = (points[tris[members[0]][1]] - origin).norm();
      const double inv_unit = unit > 0 ? 1 / unit : 1;
      double volume = 0;
      for (uint32_t t : members) {
        const Triangle& f = tris[t];
        const Vec3 a = (points[f[0]] - origin) * inv_unit, b = (points[f[1]] - origin) * inv_unit,
                   c = (points[f[2]] - origin) * inv_unit;
        const double v = a.dot(b.cross(c));
        volume += (flipped[t] != invert) ? -v : v;
      }
      invert = invert != (volume < 0);
    }
    for (uint32_t t : members)
      if (flipped[t] != invert) {
        std::swap(tris[t][1], tris[t][2]);
        ++report.flipped_triangles;
        // Corner k of the swapped triangle: edges (0,2),(2,1),(1,0) — remap cut flags.
        uint8_t* cut = &out.cut[size_t{3} * t];
        std::swap(cut[0], cut[2]);
      }
  }
  return out;
}

// Splits every vertex whose triangles form several fans (connected through
// uncut edges around it) into one vertex per fan.
void split_fans(std::vector<Triangle>& tris, std::vector<Vec3>& points, const std::vector<uint8_t>& cut,
                RepairReport& report) {
  const size_t nv = points.size(), nt = tris.size();
  std::vector<uint32_t> offsets(nv + 1, 0), corners(3 * nt);
  for (const Triangle& t : tris)
    for (uint32_t v : t) ++offsets[v + 1];
  for (size_t v = 0; v < nv; ++v) offsets[v + 1] += offsets[v];
  std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
  for (uint32_t t = 0; t < nt; ++t)
    for (uint32_t k = 0; k < 3; ++k) corners[fill[tris[t][k]]++] = 3 * t + k;

  // Buffers reused for every vertex.
  std::vector<uint64_t> ends;  // other end of an uncut edge at v << 32 | local triangle
  std::vector<uint32_t> fan_of;
  Union fans;
  for (uint32_t v = 0; v < nv; ++v) {
    const uint32_t begin = offsets[v], n = offsets[v + 1] - begin;
    if (n < 2) continue;
    // Two triangles at v are in one fan when they share an uncut edge at v.
    ends.clear();
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t corner = corners[begin + i], t = corner / 3, k = corner % 3;
      if (!cut[3 * t + k]) ends.push_back(uint64_t{tris[t][(k + 1) % 3]} << 32 | i);
      if (!cut[3 * t + (k + 2) % 3]) ends.push_back(uint64_t{tris[t][(k + 2) % 3]} << 32 | i);
    }
    std::sort(ends.begin(), ends.end());
    fans.reset(n);
    for (size_t j = 1; j < ends.size(); ++j)
      if (ends[j] >> 32 == ends[j - 1] >> 32) fans.join(uint32_t(ends[j]), uint32_t(ends[j - 1]));
    // The fan of the first triangle keeps v; every other fan gets a copy.
    fan_of.assign(n, kNone);
    size_t fan_count = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t root = fans.find(i);
      if (fan_of[root] == kNone) {
        fan_of[root] = fan_count++ == 0 ? v : static_cast<uint32_t>(points.size());
        if (fan_of[root] != v) {
          const Vec3 copy = points[v];
          points.push_back(copy);
        }
      }
      const uint32_t corner = corners[begin + i];
      tris[corner / 3][corner % 3] = fan_of[root];
    }
    if (fan_count > 1) ++report.nonmanifold_vertices;
  }
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
  {
    // Duplicates: triangles with the same vertex set; the first one stays.
    // Bucketed by the smallest vertex, ordered by the other two (one key).
    std::vector<uint64_t> larger(tris.size());
    for (size_t t = 0; t < tris.size(); ++t) {
      const Triangle k = sorted_corners(tris[t]);
      larger[t] = uint64_t{k[1]} << 32 | k[2];
    }
    const auto smallest = [&](size_t t) { return std::min({tris[t][0], tris[t][1], tris[t][2]}); };
    const std::vector<uint32_t> keyed = bucket_order(tris.size(), points.size(), smallest, [&](uint32_t x, uint32_t y) {
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
  if (tris.empty())
    throw Error(ErrorKind::InvalidInput,
                "no usable triangle remains (all are degenerate or have non-finite coordinates).");

  Orientation orientation = orient(tris, points, report);
  report.components = orientation.components;
  split_fans(tris, points, orientation.cut, report);

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

  // Boundary edges of the repaired mesh: undirected edges used once.
  detail::order_half_edges(result.mesh.triangles, next)
      .for_each_edge([&](uint32_t, uint32_t, const uint64_t* first, const uint64_t* last) {
        if (last - first == 1) ++report.boundary_edges;
        if (last - first > 2)
          throw Error(ErrorKind::InvalidInput, "the mesh has an edge that could not be made manifold.");
      });
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
