#include "crestline/mesh/repair.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>
#include <type_traits>

#include "crestline/error.h"
#include "crestline/mesh/topology.h"
#include "crestline/numerics/parallel.h"
#include "half_edges.h"
#include "parts.h"

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
}

// Throws for the index at `first_bad` (out of range) unless it is past the end.
void check_first_bad_index(const TriangleSoup& soup, size_t first_bad) {
  if (first_bad < soup.indices.size())
    throw Error(ErrorKind::InvalidInput, "triangle " + std::to_string(first_bad / 3) + " refers to vertex " +
                                             std::to_string(soup.indices[first_bad]) + " but there are only " +
                                             std::to_string(soup.vertex_count()) + " vertices.");
}

// Merges vertices closer than `tolerance`: vertex i joins the earliest
// representative (a vertex that joined no other) j < i within tolerance, or
// represents itself. Vertices are found through a grid hashed to slots
// (cells whose keys share a slot only cost distance tests). Cells measure 16
// tolerances, so the box of ±tolerance (plus a margin of half a tolerance
// for rounding) around a vertex spans 3/16 of a cell per axis: 1.7 probes on
// average (1 to 8), where cells of 2 tolerances took 15.6 (8 to 27).
// Vertices closer than a few cells are rare at a tolerance of 1e-7 of the
// diagonal (seam copies sit at distance 0), so the slots stay short. The
// result does not depend on the cells: exact distances decide.
// On one thread the grid is a flat open-addressing table from slot to a list
// (through `next`) of representatives, inserted as they are found (a sixth
// of the entries on a soup, so fewer cache misses per search). On several,
// every vertex is pushed onto its slot's list at once (an atomic exchange of
// the list's head, on every thread: no counting sort, whose passes over the
// slots doubled the weld's instructions at 2 threads); the searches run on
// every thread, read the whole of each list (in the order of the pushes,
// which varies), and
// find the earliest vertex within tolerance, which is the answer unless that
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
  const bool one_thread = max_threads() == 1;
  // Slots: on one thread, 1.5 times the vertices (the open-addressing
  // table, at most two thirds full; its 8-byte slots, 8 MB at 1.1M
  // triangles, fit the TLB's reach where the 16 MB of twice the vertices
  // did not: the weld's CPU time 45-62 -> 34-45 ms over 6 runs each, as
  // much as 2 MB pages gave the 16 MB); on several, twice (lists of 1.5
  // entries on average where a search looks).
  const size_t slots = one_thread ? points.size() + points.size() / 2 : 2 * points.size();
  int bits = 1;
  while ((size_t{1} << bits) < slots) ++bits;
  const size_t mask = (size_t{1} << bits) - 1;
  auto hashed = [&](uint64_t key) { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - bits)); };
  // Calls visit(key) for the cells within reach of a vertex at q (scaled).
  auto for_cells_near = [&](const Vec3& q, const auto& visit) {
    const int64_t x0 = cell(q.x() - kReach), x1 = cell(q.x() + kReach), y0 = cell(q.y() - kReach),
                  y1 = cell(q.y() + kReach), z0 = cell(q.z() - kReach), z1 = cell(q.z() + kReach);
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t z = z0; z <= z1; ++z) visit(cell_key(x, y, z));
  };
  auto key_at = [&](const Vec3& q) { return cell_key(cell(q.x()), cell(q.y()), cell(q.z())); };
  const double tol2 = tolerance * tolerance;
  auto near = [&](uint32_t j, uint32_t i) { return (points[j] - points[i]).squaredNorm() <= tol2; };
  if (one_thread) {
    // A slot holds its list's head and a 32-bit tag of its cell's key, side
    // by side: one cache line a probe (the table is far larger than the
    // caches, and a separate array of 64-bit keys cost a second miss). Cells
    // whose tags collide share a list, which only costs distance tests. A
    // vertex's next is read only once it is in a list: not filled first.
    struct Slot {
      uint32_t head, tag;
    };
    std::vector<Slot> table(mask + 1, Slot{kNone, 0});
    UninitialisedVector<uint32_t> next(points.size());
    auto tag_of = [](uint64_t key) { return static_cast<uint32_t>(key * 0x9E3779B97F4A7C15ull); };
    // The slot of a cell (empty if its head is kNone).
    auto slot = [&](uint64_t key) {
      size_t s = hashed(key);
      const uint32_t tag = tag_of(key);
      while (table[s].head != kNone && table[s].tag != tag) s = (s + 1) & mask;
      return s;
    };
    // Cells hash anywhere in the table: the slot of the cell of the vertex
    // kAhead on (nearly always the only one searched) is asked for now
    // (natively; WASM has no prefetch), and that cell's key kept for its
    // turn (ahead[i % kAhead] is vertex i's).
    constexpr size_t kAhead = 16;
    std::array<uint64_t, kAhead> ahead{};
    for (size_t i = 0; i < std::min(kAhead, points.size()); ++i) ahead[i] = key_at(scaled(points[i]));
    for (uint32_t i = 0; i < points.size(); ++i) {
      const uint64_t home = ahead[i % kAhead];
      if (i + kAhead < points.size()) {
        const uint64_t key = key_at(scaled(points[i + kAhead]));
        ahead[i % kAhead] = key;
        __builtin_prefetch(&table[hashed(key)]);
      }
      if (!weldable[i]) continue;
      uint32_t found = kNone;
      size_t home_slot = 0;  // the home cell is always among those searched
      for_cells_near(scaled(points[i]), [&](uint64_t key) {
        const size_t s = slot(key);
        if (key == home) home_slot = s;
        for (uint32_t j = table[s].head; j != kNone; j = next[j])
          if (j < found && near(j, i)) found = j;
      });
      if (found != kNone) {
        representative[i] = found, ++welded;
      } else {
        // Lists in descending index order (each vertex is pushed at its
        // head), in the slot the search found for its cell.
        next[i] = table[home_slot].head;
        table[home_slot] = {i, tag_of(home)};
      }
    }
    return representative;
  }
  // Several threads: every weldable vertex pushed onto its slot's list, on
  // every thread (an exchange of the slot's head: the lists' order depends
  // on the scheduling, what is found in them does not).
  std::unique_ptr<std::atomic<uint32_t>[]> slot_head(new std::atomic<uint32_t>[mask + 1]);
  parallel_for(mask + 1, [&](size_t begin, size_t end) {
    for (size_t s = begin; s < end; ++s) slot_head[s].store(kNone, std::memory_order_relaxed);
  });
  UninitialisedVector<uint32_t> next(points.size());
  parallel_for(points.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      if (weldable[i])
        next[i] = slot_head[hashed(key_at(scaled(points[i])))].exchange(uint32_t(i), std::memory_order_relaxed);
  });
  // The earliest vertex j < i within tolerance (among representatives only
  // if `representatives_only`), over the whole of each slot's list.
  auto earliest = [&](uint32_t i, bool representatives_only) {
    uint32_t found = kNone;
    for_cells_near(scaled(points[i]), [&](uint64_t key) {
      for (uint32_t j = slot_head[hashed(key)].load(std::memory_order_relaxed); j != kNone; j = next[j])
        if (j < std::min(i, found) && (!representatives_only || representative[j] == j) && near(j, i)) found = j;
    });
    return found;
  };
  UninitialisedVector<uint32_t> nearest(points.size());
  parallel_for(points.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) nearest[i] = weldable[i] ? earliest(static_cast<uint32_t>(i), false) : kNone;
  });
  for (uint32_t i = 0; i < points.size(); ++i) {
    uint32_t found = nearest[i];
    if (found == kNone) continue;
    if (representative[found] != found) found = earliest(i, true);
    if (found != kNone) representative[i] = found, ++welded;
  }
  return representative;
}

// Numbers the vertices in the order the triangles first use them (corner
// by corner, in triangle order), renames the corners and keeps only the
// used points, in their new order: a vertex welded into another, one no
// triangle refers to and one only on dropped triangles get no number. A
// triangle's corners then lie near each other in the numbering wherever the
// triangles themselves are in a local order, which is where a file's
// numbering often is not (subdivision appends each edge's midpoint after
// the old vertices: at 1.1M triangles a triangle's corners spanned a median
// of 320k numbers, 22 in this order), so the gathers of every later stage
// read nearby memory. Serial, so the numbers are the same for any thread
// count. Returns the number of vertices used.
size_t number_by_first_use(std::vector<Triangle>& tris, std::vector<Vec3>& points) {
  const size_t nv = points.size(), nt = tris.size();
  std::vector<uint32_t> number(nv, kNone);
  UninitialisedVector<uint32_t> source(nv);  // the old number of each new one
  uint32_t used = 0;
  bool same = true;  // every vertex keeps its number (a file already in this order)
  Triangle* out = tris.data();
  uint32_t* to = number.data();
  for (size_t t = 0; t < nt; ++t) {
    // The corners lie anywhere in the input's numbering: their numbers are
    // asked for kAhead triangles on (natively; WASM has no prefetch).
    constexpr size_t kAhead = 8;
    if (t + kAhead < nt)
      for (uint32_t v : out[t + kAhead]) __builtin_prefetch(&to[v]);
    for (uint32_t& v : out[t]) {
      if (to[v] == kNone) same = same && v == used, to[v] = used, source[used++] = v;
      v = to[v];
    }
  }
  if (same && used == nv) return used;  // the points stay where they are
  std::vector<Vec3> kept(used);
  parallel_for(used, [&, from = source.data(), p = points.data()](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      constexpr size_t kAhead = 8;
      if (i + kAhead < end) __builtin_prefetch(&p[from[i + kAhead]]);
      kept[i] = p[from[i]];
    }
  });
  points = std::move(kept);
  return used;
}

// Half-edges (corners) paired across their undirected edges: the partner
// across a manifold edge, whether it runs the same way, and every corner of
// a non-manifold edge cut. Also finds duplicate triangles (the same three
// vertices): two of them share all three edges, and in each edge's group
// they have the same opposite corner; conversely two half-edges of one edge
// with the same opposite corner are a duplicate pair. So a clean mesh needs
// no pass of its own to prove it has none.
// Every entry is written once, by its edge's group, so none is zero-filled
// first. The cut corners (few) are listed rather than flagged: a byte per
// corner written in scattered order at every edge cost more than the list.
struct EdgePairs {
  UninitialisedVector<uint32_t> partner;  // the corner across a manifold edge, kNone elsewhere
  UninitialisedVector<uint8_t> same;      // partner runs the same way (the triangles disagree)
  std::vector<uint32_t> cut;              // the corners of cut edges (corner k: edge k, k + 1), in any order
  size_t nonmanifold = 0;                 // edges of more than two triangles
  size_t single = 0;                      // edges of one triangle
  std::vector<uint32_t> single_edges;     // their numbers in the recorded topology, in any order
  bool duplicates = false;                // two triangles have the same three vertices
};

// Also records the edges in `topology` as build_topology numbers them (its
// edges, edge_triangles and triangle_edges; meaningless where an edge has
// more than two triangles): the repaired mesh's own when the repair renames
// no corner, so the Pipeline need not group the half-edges again.
EdgePairs pair_half_edges(const std::vector<Triangle>& tris, size_t vertex_count, Topology& topology) {
  const size_t nt = tris.size();
  EdgePairs out;
  out.partner.resize(3 * nt);
  out.same.resize(3 * nt);
  std::vector<uint32_t> first_edge;
  const detail::HalfEdgeOrder order = detail::order_half_edges(tris, vertex_count, &first_edge);
  detail::number_edges(first_edge, nt, topology);
  using H = detail::HalfEdgeOrder;
  // The arrays by address (see EdgeRecorder). A half-edge's start and the
  // corner opposite it come from its entry (no division of a corner number).
  const Triangle* triangles = tris.data();
  uint32_t* partner = out.partner.data();
  uint8_t* same = out.same.data();
  const detail::EdgeRecorder record(first_edge, topology);
  auto before = [](uint32_t side) { return side == 0 ? 2 : side - 1; };  // the side (corner) before `side`
  auto opposite = [triangles, before](uint64_t h) { return triangles[H::triangle(h)][before(H::side(h))]; };
  std::atomic<size_t> nonmanifold{0}, single{0};
  std::mutex lists_mutex;
  std::atomic<bool> duplicates{false};
  detail::for_bucket_ranges(order.start, [&](size_t begin, size_t end) {
    size_t count = 0, singles = 0;
    std::vector<uint32_t> single_edges, cut;
    bool repeated = false;
    // The half-edges' triangles lie anywhere: the triangle read and the
    // three slots written (partner, same, the topology's triangle_edges) of
    // the half-edges kAhead entries on are asked for now (natively; WASM has
    // no prefetch).
    constexpr ptrdiff_t kAhead = 16;
    const uint64_t* stop = order.entries.data() + order.start[end];
    std::array<uint32_t, 3>* triangle_edges = topology.triangle_edges.data();
    auto prefetch = [=](uint64_t h) {
      const uint32_t t = H::triangle(h), c = 3 * t + H::side(h);
      __builtin_prefetch(&triangles[t]);
      __builtin_prefetch(&partner[c], 1);
      __builtin_prefetch(&same[c], 1);
      __builtin_prefetch(&triangle_edges[t], 1);
    };
    order.for_each_edge(
        begin, end,
        [&count, &singles, &single_edges, &cut, &repeated, record, triangles, before, opposite, partner, same, stop,
         prefetch](uint32_t near, uint32_t far, const uint64_t* first, const uint64_t* last) {
          if (stop - first > kAhead + 1) prefetch(first[kAhead]), prefetch(first[kAhead + 1]);
          if (last - first == 2) {
            // Nearly every edge: each half-edge's triangle,
            // side and corner taken from its entry once.
            const uint32_t ta = H::triangle(first[0]), sa = H::side(first[0]);
            const uint32_t tb = H::triangle(first[1]), sb = H::side(first[1]);
            const uint32_t a = 3 * ta + sa, b = 3 * tb + sb;
            record(near, far, ta, sa, tb, sb);
            partner[a] = b, partner[b] = a;
            const Triangle &fa = triangles[ta], &fb = triangles[tb];
            same[a] = same[b] = fa[sa] == fb[sb];
            repeated |= fa[before(sa)] == fb[before(sb)];
            return;
          }
          const uint32_t e = record(near, far, first, std::min(last, first + 2));
          if (last - first == 1) {
            ++singles;
            single_edges.push_back(e);
            const uint32_t a = H::corner(first[0]);
            partner[a] = kNone, same[a] = 0;
          } else {
            ++count;
            for (const uint64_t* h = first; h < last; ++h) {
              const uint32_t a = H::corner(*h);
              partner[a] = kNone, same[a] = 0;
              cut.push_back(a);
              for (const uint64_t* g = first; g < h; ++g) repeated |= opposite(*g) == opposite(*h);
            }
          }
        });
    nonmanifold += count;
    single += singles;
    if (!single_edges.empty() || !cut.empty()) {
      const std::lock_guard<std::mutex> lock(lists_mutex);
      out.single_edges.insert(out.single_edges.end(), single_edges.begin(), single_edges.end());
      out.cut.insert(out.cut.end(), cut.begin(), cut.end());
    }
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

// Components and flips (see orient) from a union-find over the triangles,
// on every thread: an entry holds its parent << 1 | its flip relative to
// the parent, and links always put the larger root under the smaller, so
// whatever the order of the links a component's root is its seed and, where
// the component is orientable, a triangle's flip relative to the root is the
// only consistent one. Sets each triangle's component (numbered in order of
// seeds) and flip, and each component's seed; returns which components are
// not orientable, their triangles left with component kNone and no flip for
// the traversal. Entries are 31-bit triangle indices (3 nt corners fit in 32 bits).
std::vector<uint8_t> link_components(const UninitialisedVector<uint32_t>& partner,
                                     const UninitialisedVector<uint8_t>& same, UninitialisedVector<uint32_t>& component,
                                     std::vector<uint8_t>& flipped, std::vector<uint32_t>& seeds) {
  const size_t nt = component.size();
  std::unique_ptr<std::atomic<uint32_t>[]> link(new std::atomic<uint32_t>[nt]);
  parallel_for(nt, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) link[t].store(uint32_t(t) << 1, std::memory_order_relaxed);
  });
  // The root of t << 1 | t's flip relative to it. Halving the path stores
  // t's grandparent with the flips added: a relation read whole from one
  // entry stays true, so any interleaving leaves every entry valid.
  auto find = [&](uint32_t t) {
    for (uint32_t flip = 0;;) {
      const uint32_t to_parent = link[t].load(std::memory_order_relaxed), parent = to_parent >> 1;
      if (parent == t) return t << 1 | flip;
      const uint32_t to_grandparent = link[parent].load(std::memory_order_relaxed);
      if (to_grandparent >> 1 == parent) return parent << 1 | (flip ^ (to_parent & 1));
      const uint32_t skip = (to_grandparent & ~1u) | ((to_parent ^ to_grandparent) & 1);
      link[t].store(skip, std::memory_order_relaxed);
      flip ^= skip & 1;
      t = skip >> 1;
    }
  };
  // Joins t and u, u flipped relative to t by `flip`; false if they are
  // joined already with the other flip (a loop that cannot agree).
  auto unite = [&](uint32_t t, uint32_t u, uint32_t flip) {
    for (;;) {
      const uint32_t a = find(t), b = find(u), relative = (a ^ b ^ flip) & 1;
      uint32_t ra = a >> 1, rb = b >> 1;
      if (ra == rb) return relative == 0;
      if (ra < rb) std::swap(ra, rb);
      uint32_t expected = ra << 1;  // still a root unless another thread linked it since
      if (link[ra].compare_exchange_weak(expected, rb << 1 | relative, std::memory_order_relaxed)) return true;
    }
  };
  std::vector<uint32_t> disagreeing;  // a triangle of each loop that cannot agree
  std::mutex disagreeing_mutex;
  parallel_for(nt, [&](size_t begin, size_t end) {
    std::vector<uint32_t> found;
    for (size_t t = begin; t < end; ++t)
      for (uint32_t corner = uint32_t(3 * t); corner < 3 * t + 3; ++corner)
        if (partner[corner] != kNone && corner < partner[corner] &&  // a cut corner has no partner
            !unite(uint32_t(t), partner[corner] / 3, same[corner]))
          found.push_back(uint32_t(t));
    if (found.empty()) return;
    const std::lock_guard<std::mutex> lock(disagreeing_mutex);
    disagreeing.insert(disagreeing.end(), found.begin(), found.end());
  });
  // Every triangle straight under its root; the roots numbered in order.
  parallel_for(nt, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) link[t].store(find(uint32_t(t)), std::memory_order_relaxed);
  });
  auto seed = [&](size_t t) { return link[t].load(std::memory_order_relaxed) >> 1; };
  detail::place_kept(
      nt, [&](size_t t) { return seed(t) == t; }, [&](size_t n) { seeds.resize(n); },
      [&](size_t t, size_t c) { component[t] = uint32_t(c), seeds[c] = uint32_t(t); });
  parallel_for(nt, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      if (seed(t) != t) component[t] = component[seed(t)];  // a seed's own entry is read, not rewritten
      flipped[t] = link[t].load(std::memory_order_relaxed) & 1;
    }
  });
  link.reset();
  std::vector<uint8_t> unorientable(seeds.size(), 0);
  for (uint32_t t : disagreeing) unorientable[component[t]] = 1;
  if (!disagreeing.empty())
    parallel_for(nt, [&](size_t begin, size_t end) {
      for (size_t t = begin; t < end; ++t)
        if (unorientable[component[t]]) component[t] = kNone, flipped[t] = 0;
    });
  return unorientable;
}

// Orients triangles consistently across shared edges, component by
// component; edges that cannot agree (non-orientable surfaces) are cut.
// Returns the cut corners and the component of each triangle.
struct Orientation {
  // The corners of cut edges (EdgePairs::cut, then the traversal's), as the flips renumber them.
  std::vector<uint32_t> cut;
  // EdgePairs::partner, its slots following the flips (its values still
  // name the other triangle, the corner there as paired), and kNone across
  // every cut edge: split_fans walks it.
  UninitialisedVector<uint32_t> partner;
  UninitialisedVector<uint32_t> component;  // its storage then serves split_fans (see repair_mesh)
  size_t components = 0;
  size_t single_edges = 0;  // edges of one triangle: boundary edges whatever the repair does
};

// A component's triangles are those joined through uncut paired edges; a
// triangle is flipped relative to the component's first triangle (its seed,
// the smallest index) when an odd number of disagreeing edges lead to it.
// On one thread, one depth-first traversal from each seed in turn finds
// both, and cuts an edge where the flips of its triangles disagree
// (non-orientable surfaces). On several, a union-find over the triangles
// finds them on every thread (see link_components), and only the
// non-orientable components are traversed, from their seeds, so that the
// cuts are those of the traversal.
// The edges recorded in `topology` follow the flips.
Orientation orient(std::vector<Triangle>& tris, const std::vector<Vec3>& points, EdgePairs pairs, Topology& topology,
                   RepairReport& report) {
  const size_t nt = tris.size();
  Orientation out;
  out.cut = std::move(pairs.cut);
  report.nonmanifold_edges += pairs.nonmanifold;
  out.single_edges = pairs.single;
  out.partner = std::move(pairs.partner);
  // By address (byte stores would reload the vectors' data at every corner).
  // A cut edge has no partner (the pairing's cuts have none), so a corner
  // is joined to another exactly when it has a partner.
  uint32_t* partner = out.partner.data();
  // The traversal marks the corners it cuts with `same` 2, listed after it
  // (a push in its loop, even out of line, cost it 23 M instructions at
  // 1.1M triangles).
  uint8_t* same = pairs.same.data();
  bool traversal_cut = false;
  auto joined = [partner](size_t corner) { return partner[corner] != kNone; };

  std::vector<uint8_t> flipped(nt, 0);
  out.component.resize(nt);
  uint8_t* flip = flipped.data();
  uint32_t* component = out.component.data();
  std::vector<uint32_t> seeds, stack;  // seeds[c]: component c's first triangle
  // Each component's size, flipped triangles and whether it is open (a
  // corner without a partner, or cut: every non-orientable one).
  std::vector<uint32_t> size, nflip;
  std::vector<uint8_t> open;
  // Triangle t's step of a traversal of component c: each neighbour across
  // a joined corner not yet visited takes the flip that agrees with t's and
  // is pushed; disagree(corner, other) is called where a visited one's flip
  // does not agree. Returns 1 if t has a corner without a partner (open).
  auto step = [partner, same, flip, component](uint32_t t, uint32_t c, const auto& push, const auto& disagree) {
    uint8_t opening = 0;
    for (uint32_t corner = 3 * t; corner < 3 * t + 3; ++corner) {
      const uint32_t other = partner[corner];
      if (other == kNone) {
        opening = 1;
        continue;
      }
      const uint32_t u = other / 3;
      const uint8_t disagree_flip = same[corner] ^ flip[t];
      if (component[u] == kNone) {
        flip[u] = disagree_flip;
        component[u] = c;
        push(u);
      } else if (disagree_flip != flip[u]) {
        disagree(corner, other);
      }
    }
    return opening;
  };
  // Component c from its seed, over the triangles not yet visited (kNone);
  // counts it in size, nflip and open if `tally`.
  // The arrays by value and the stack as a raw array: the byte stores below
  // may alias anything reached through a reference, so each access reloaded
  // its pointer (and each push the vector's own) from memory otherwise.
  auto traverse = [&, partner, same, flip, component](uint32_t c, bool tally) {
    uint32_t* base = stack.data();
    size_t top = 0, capacity = stack.size();
    auto push = [&](uint32_t t) {
      if (top == capacity) stack.resize(capacity = 2 * capacity + 64), base = stack.data();
      base[top++] = t;
    };
    push(seeds[c]);
    component[seeds[c]] = c;
    uint32_t triangles = 0, flips = 0;
    uint8_t opening = 0;
    while (top > 0) {
      const uint32_t t = base[--top];
      ++triangles, flips += flip[t];
      if (step(t, c, push, [&](uint32_t corner, uint32_t other) {
            same[corner] = same[other] = 2;  // cut: non-orientable here
            partner[corner] = partner[other] = kNone;
            traversal_cut = true, opening = 1;
          }))
        opening = 1;
    }
    if (tally) size.push_back(triangles), nflip.push_back(flips), open.push_back(opening);
  };
  // The same in breadth-first order, which knows the triangles it will take
  // next: their partners and same are asked for kAhead places ahead in the
  // queue, their neighbours' component and flip kAhead / 2 ahead (natively;
  // WASM has no prefetch; the depth-first stack pops what it has just pushed,
  // nothing to ask for early). The order decides only where a component that
  // cannot agree is cut: sweep cuts nothing, and on the first disagreement
  // it returns false with the component's triangles unvisited again (the
  // queue holds them all), for traverse. Counts the component if it agrees.
  auto sweep = [&, partner, same, flip, component](uint32_t c) {
    uint32_t* base = stack.data();
    size_t head = 0, tail = 0, capacity = stack.size();
    auto push = [&](uint32_t t) {
      if (tail == capacity) stack.resize(capacity = 2 * capacity + 64), base = stack.data();
      base[tail++] = t;
    };
    push(seeds[c]);
    component[seeds[c]] = c;
    uint32_t flips = 0;
    uint8_t opening = 0;
    bool agree = true;
    constexpr size_t kAhead = 16;
    while (head < tail && agree) {
      if (head + kAhead < tail) {
        const uint32_t u = base[head + kAhead];
        __builtin_prefetch(&partner[3 * size_t{u}]);
        __builtin_prefetch(&partner[3 * size_t{u} + 2]);
        __builtin_prefetch(&same[3 * size_t{u}]);
      }
      if (head + kAhead / 2 < tail)
        for (uint32_t corner = 3 * base[head + kAhead / 2], last = corner + 3; corner < last; ++corner)
          if (partner[corner] != kNone) {
            __builtin_prefetch(&component[partner[corner] / 3]);
            __builtin_prefetch(&flip[partner[corner] / 3]);
          }
      const uint32_t t = base[head++];
      flips += flip[t];
      if (step(t, c, push, [&](uint32_t, uint32_t) { agree = false; })) opening = 1;
    }
    if (!agree) {
      for (size_t i = 0; i < tail; ++i) component[base[i]] = kNone, flip[base[i]] = 0;
      return false;
    }
    size.push_back(uint32_t(tail)), nflip.push_back(flips), open.push_back(opening);
    return true;
  };
  // On one thread the traversal counts the components; on several they are
  // counted by parts on every thread (on one part when they are many).
  const bool one_part = detail::part_count(nt) == 1;
  if (one_part) {
    std::fill(out.component.begin(), out.component.end(), kNone);
    for (uint32_t t = 0; t < nt; ++t)
      if (component[t] == kNone) {
        seeds.push_back(t);
        if (!sweep(uint32_t(seeds.size() - 1))) traverse(uint32_t(seeds.size() - 1), true);
      }
  } else {
    const std::vector<uint8_t> unorientable = link_components(out.partner, pairs.same, out.component, flipped, seeds);
    for (uint32_t c = 0; c < seeds.size(); ++c)
      if (unorientable[c]) traverse(c, false);
  }
  if (traversal_cut) {
    const size_t listed = out.cut.size();
    detail::place_kept(
        3 * nt, [&](size_t corner) { return same[corner] == 2; }, [&](size_t n) { out.cut.resize(listed + n); },
        [&](size_t corner, size_t rank) { out.cut[listed + rank] = uint32_t(corner); });
  }
  const size_t n = out.components = seeds.size();
  const size_t parts = one_part ? 0 : n * 64 <= nt ? detail::part_count(nt) : 1;
  if (!one_part) {
    size.assign(parts * n, 0), nflip.assign(parts * n, 0), open.assign(parts * n, 0);
    // Counted in the part's own vectors, then stored: counted in place, the
    // parts' counters of one component shared a cache line, which two
    // threads passed back and forth at every triangle (1.1M triangles, one
    // component: 15-62 ms on 2 threads).
    detail::for_each_part(parts, nt, [&](size_t p, size_t begin, size_t end) {
      std::vector<uint32_t> part_size(n, 0), part_nflip(n, 0);
      std::vector<uint8_t> part_open(n, 0);
      for (size_t t = begin; t < end; ++t) {
        const uint32_t c = component[t];
        ++part_size[c], part_nflip[c] += flip[t];
        if (!joined(3 * t) || !joined(3 * t + 1) || !joined(3 * t + 2)) part_open[c] = 1;
      }
      std::copy(part_size.begin(), part_size.end(), size.begin() + ptrdiff_t(p * n));
      std::copy(part_nflip.begin(), part_nflip.end(), nflip.begin() + ptrdiff_t(p * n));
      std::copy(part_open.begin(), part_open.end(), open.begin() + ptrdiff_t(p * n));
    });
  }
  for (size_t p = 1; p < parts; ++p)
    for (size_t c = 0; c < n; ++c) size[c] += size[p * n + c], nflip[c] += nflip[p * n + c], open[c] |= open[p * n + c];
  // Keep the orientation most of the file agreed on.
  std::vector<uint8_t> invert(n);
  for (size_t c = 0; c < n; ++c) invert[c] = 2 * size_t(nflip[c]) > size[c];
  // Closed components then face outwards (positive signed volume): the
  // signed volume of each triangle about the first corner of its component's
  // seed, in units of the seed's first edge (the same sign at any position
  // and scale), with the sign of its orientation as kept, on every thread;
  // each component's terms then added in triangle order. (They were added in
  // traversal order before 2 threads could find the components: the order
  // only decides a sum within rounding of 0, a flat closed surface, which
  // faces neither way.)
  if (std::count(open.begin(), open.begin() + ptrdiff_t(n), 0) > 0) {
    // Each component's origin and unit once, not per triangle (a square
    // root and a division: 30 % of the loop's instructions).
    std::vector<Vec3> origin(n);
    std::vector<double> inv_unit(n);
    parallel_for(n, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; ++c) {
        const Triangle& first = tris[seeds[c]];
        origin[c] = points[first[0]];
        const double unit = (points[first[1]] - origin[c]).norm();
        inv_unit[c] = unit > 0 ? 1 / unit : 1;
      }
    });
    UninitialisedVector<double> volume(nt);
    parallel_for(nt, [&](size_t begin, size_t end) {
      for (size_t t = begin; t < end; ++t) {
        const uint32_t c = out.component[t];
        if (open[c]) continue;
        const Vec3& o = origin[c];
        const double scale = inv_unit[c];
        const Triangle& f = tris[t];
        const Vec3 a = (points[f[0]] - o) * scale, b = (points[f[1]] - o) * scale, d = (points[f[2]] - o) * scale;
        const double v = a.dot(b.cross(d));
        volume[t] = flipped[t] != invert[c] ? -v : v;
      }
    });
    std::vector<double> sum(n, 0.0);
    for (size_t t = 0; t < nt; ++t)
      if (!open[out.component[t]]) sum[out.component[t]] += volume[t];
    for (size_t c = 0; c < n; ++c)
      if (!open[c]) invert[c] = invert[c] != (sum[c] < 0);
  }
  for (size_t c = 0; c < n; ++c) report.flipped_triangles += invert[c] ? size[c] - nflip[c] : nflip[c];
  parallel_for(nt, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t)
      if (flipped[t] != invert[out.component[t]]) {
        std::swap(tris[t][1], tris[t][2]);
        // Corner k of the swapped triangle: edges (0,2),(2,1),(1,0) — remap the partners.
        std::swap(partner[3 * t], partner[3 * t + 2]);
        std::swap(topology.triangle_edges[t][0], topology.triangle_edges[t][2]);
      }
  });
  for (uint32_t& corner : out.cut) {
    const uint32_t t = corner / 3;
    if (flipped[t] != invert[out.component[t]] && corner % 3 != 1) corner = 3 * t + 2 - corner % 3;
  }
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
// vertex's only one: nearly every fan. So each vertex's fan through one of
// its corners (in its first triangle of `lists`, the topology's
// vertex_offsets and vertex_triangles) is walked first, on every thread;
// only the vertices it leaves short (`several`) have all their fans found, from every corner there, on every thread
// too, and sorted by (vertex, first corner). (Walking every corner's fan once, with a flag per corner walked, cost 0.16
// G instructions at 1.1M triangles, d848c66.) Returns whether it split any vertex.
bool split_fans(std::vector<Triangle>& tris, std::vector<Vec3>& points, const Orientation& orientation,
                const Topology& lists, RepairReport& report) {
  const size_t nt = tris.size(), nv = lists.vertex_offsets.size() - 1;
  const uint32_t* offsets = lists.vertex_offsets.data();
  const UninitialisedVector<uint32_t>& partner = orientation.partner;
  // The corner at v of the triangle across the edge of corner `edge` (a
  // corner of v's triangle), or kNone where the edge is cut or has no other.
  auto across = [&](uint32_t edge, uint32_t v) {
    const uint32_t other = partner[edge];
    if (other == kNone) return kNone;  // cut, or no other
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
  std::atomic<bool> any{false};
  UninitialisedVector<uint8_t> several(nv);  // every entry written
  parallel_for(nv, [&](size_t begin, size_t end) {
    bool found = false;
    for (size_t v = begin; v < end; ++v) {
      // A fan's triangles lie anywhere in the triangle list: each step of
      // the walk waits for a corner's partner, then its triangle. The
      // triangles of the vertex kAhead on, all on its list, are asked for
      // now (natively; WASM has no prefetch).
      constexpr size_t kAhead = 4;
      if (v + kAhead < end)
        for (uint32_t i = offsets[v + kAhead], last = offsets[v + kAhead + 1]; i < last; ++i) {
          const uint32_t u = lists.vertex_triangles[i];
          __builtin_prefetch(&tris[u]);
          __builtin_prefetch(&partner[3 * size_t{u}]);
          __builtin_prefetch(&partner[3 * size_t{u} + 2]);
        }
      const uint32_t count = offsets[v + 1] - offsets[v];
      several[v] = 0;
      if (count == 0) continue;
      const uint32_t t = lists.vertex_triangles[offsets[v]];
      uint32_t size = 1;
      for_fan(3 * t + (tris[t][0] == v ? 0 : tris[t][1] == v ? 1 : 2), uint32_t(v), [&](uint32_t) { ++size; });
      if (size < count) several[v] = 1, found = true;
    }
    if (found) any = true;
  });
  if (!any) return false;
  // (vertex << 32 | first corner) of every fan of a vertex of several.
  std::vector<uint64_t> fans;
  std::mutex fans_mutex;
  parallel_for(3 * nt, [&](size_t first, size_t last) {
    // Corners of this range already walked, as part of an earlier one's fan.
    std::vector<uint8_t> seen(last - first, 0);
    std::vector<uint64_t> found;
    for (size_t c = first; c < last; ++c) {
      const uint32_t v = tris[c / 3][c % 3];
      if (seen[c - first] || !several[v]) continue;
      uint32_t lowest = uint32_t(c);
      for_fan(uint32_t(c), v, [&](uint32_t x) {
        lowest = std::min(lowest, x);
        if (x >= first && x < last) seen[x - first] = 1;
      });
      // Once per fan: from its first corner (the range that holds it).
      if (lowest == c) found.push_back(uint64_t{v} << 32 | c);
    }
    if (found.empty()) return;
    const std::lock_guard<std::mutex> lock(fans_mutex);
    fans.insert(fans.end(), found.begin(), found.end());
  });
  if (fans.empty()) return false;
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
  return true;
}

// Boundary edges of the repaired mesh, without grouping its half-edges
// again: an edge of one triangle stays one; the two triangles of an uncut
// edge share both its ends after the fans are split (they are in one fan at
// each end); only the cut edges' half-edges, few, are grouped anew by their
// renamed ends, and one left alone is a boundary edge.
size_t count_boundary_edges(const std::vector<Triangle>& tris, const Orientation& orientation) {
  if (orientation.cut.empty()) return orientation.single_edges;
  std::vector<uint64_t> cut_edges(orientation.cut.size());
  for (size_t i = 0; i < cut_edges.size(); ++i) {
    const uint32_t c = orientation.cut[i], a = tris[c / 3][c % 3], b = tris[c / 3][(c + 1) % 3];
    cut_edges[i] = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
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

// Gives a soup's arrays back (assigning {} would only clear them).
void release_arrays(TriangleSoup& soup) {
  decltype(soup.positions)().swap(soup.positions);
  decltype(soup.indices)().swap(soup.indices);
}

// repair_mesh, releasing `consumed`'s arrays once read where it is the soup.
RepairResult repair(const TriangleSoup& soup, TriangleSoup* consumed, const RepairOptions& options) {
  check_soup(soup, options);
  RepairResult result;
  RepairReport& report = result.report;
  report.input_vertices = soup.vertex_count();
  report.input_triangles = soup.triangle_count();

  const size_t nv = soup.vertex_count(), input_nt = soup.triangle_count();
  std::vector<Vec3> points(nv);
  // Vertices used by a triangle, flagged from every thread (relaxed stores
  // of the same value: no race, no ordering needed).
  std::unique_ptr<std::atomic<uint8_t>[]> referenced(new std::atomic<uint8_t>[nv]);
  parallel_for(nv, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      points[i] = Vec3(soup.positions[3 * i], soup.positions[3 * i + 1], soup.positions[3 * i + 2]);
      referenced[i].store(0, std::memory_order_relaxed);
    }
  });
  // The indices checked in the same pass: the first out of range (each
  // thread's first, the smallest kept) is the one reported.
  std::atomic<size_t> first_bad{soup.indices.size()};
  parallel_for(soup.indices.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const uint32_t v = soup.indices[i];
      if (v >= nv) {
        detail::atomic_min(first_bad, i);
        return;
      }
      referenced[v].store(1, std::memory_order_relaxed);
    }
  });
  check_first_bad_index(soup, first_bad);
  if (consumed) decltype(consumed->positions)().swap(consumed->positions);  // all in `points` now
  // The bounding box of the weldable vertices (finite and referenced), by
  // parts merged in order. (Equal minima of −0 and 0 may keep the other
  // sign than a pass in index order did; nothing below sees a zero's sign.)
  std::vector<uint8_t> finite(nv), weldable(nv);
  const size_t parts = detail::part_count(nv);
  std::vector<Vec3> part_lo(parts, Vec3::Constant(INFINITY)), part_hi(parts, Vec3::Constant(-INFINITY));
  detail::for_each_part(parts, nv, [&](size_t p, size_t begin, size_t end) {
    Vec3 lo = part_lo[p], hi = part_hi[p];
    for (size_t i = begin; i < end; ++i) {
      finite[i] = points[i].allFinite();
      weldable[i] = finite[i] && referenced[i].load(std::memory_order_relaxed);
      if (weldable[i]) lo = lo.cwiseMin(points[i]), hi = hi.cwiseMax(points[i]);
    }
    part_lo[p] = lo, part_hi[p] = hi;
  });
  referenced.reset();
  Vec3 lo = part_lo[0], hi = part_hi[0];
  for (size_t p = 1; p < parts; ++p) lo = lo.cwiseMin(part_lo[p]), hi = hi.cwiseMax(part_hi[p]);
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
  // Twice the area relative to the squared diagonal: sides are divided by the
  // diagonal first, so the test means the same at every scale (at 1e-100 the
  // squared cross product of raw coordinates would underflow to zero).
  constexpr double kMinRelativeDoubleArea = 1e-14;
  const double inv_diagonal = diagonal > 0 ? 1 / diagonal : 0;
  // The tests run on every thread, each writing its welded triangle in
  // place, with kNone as the first corner of one dropped; only a soup with
  // dropped triangles (few) is then gathered again, in input order, also on
  // every thread. (Gathering every soup, each kept triangle welded a second
  // time, cost 30 M instructions at 1.1M triangles.)
  std::vector<Triangle> tris(input_nt);
  std::atomic<size_t> nonfinite{0}, degenerate{0};
  // Where no vertex was welded (a clean mesh) the corners are the input's:
  // not looked up in `rep` (1.1M triangles, 1 thread: 143 -> 119 M
  // instructions).
  auto test_triangles = [&](auto renumbered) {
    parallel_for(input_nt, [&, indices = soup.indices.data(), to = rep.data(), is_finite = finite.data(),
                            p = points.data(), out = tris.data()](size_t begin, size_t end) {
      auto corner = [indices, to](size_t i) { return decltype(renumbered)::value ? to[indices[i]] : indices[i]; };
      size_t part_nonfinite = 0, part_degenerate = 0;
      for (size_t t = begin; t < end; ++t) {
        // The corners lie anywhere: their welded numbers are asked for
        // 2 kAhead triangles on, their flags and positions kAhead on
        // (natively; WASM has no prefetch).
        constexpr size_t kAhead = 8;
        if (decltype(renumbered)::value && t + 2 * kAhead < end)
          for (size_t i = 3 * (t + 2 * kAhead); i < 3 * (t + 2 * kAhead) + 3; ++i) __builtin_prefetch(&to[indices[i]]);
        if (t + kAhead < end)
          for (size_t i = 3 * (t + kAhead); i < 3 * (t + kAhead) + 3; ++i) {
            const uint32_t v = corner(i);
            __builtin_prefetch(&is_finite[v]);
            __builtin_prefetch(&p[v]);
          }
        Triangle f = {corner(3 * t), corner(3 * t + 1), corner(3 * t + 2)};
        if (!is_finite[f[0]] || !is_finite[f[1]] || !is_finite[f[2]])
          f[0] = kNone, ++part_nonfinite;
        else if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] ||
                 !(((p[f[1]] - p[f[0]]) * inv_diagonal).cross((p[f[2]] - p[f[0]]) * inv_diagonal).norm() >
                   kMinRelativeDoubleArea))
          f[0] = kNone, ++part_degenerate;
        out[t] = f;
      }
      nonfinite += part_nonfinite, degenerate += part_degenerate;
    });
  };
  if (report.welded_vertices > 0)
    test_triangles(std::true_type{});
  else
    test_triangles(std::false_type{});
  if (consumed) release_arrays(*consumed);  // the triangles all in `tris` now
  report.nonfinite_triangles = nonfinite, report.degenerate_triangles = degenerate;
  if (nonfinite + degenerate > 0) {
    std::vector<Triangle> kept;
    detail::place_kept(
        input_nt, [&](size_t t) { return tris[t][0] != kNone; }, [&](size_t n) { kept.resize(n); },
        [&](size_t t, size_t rank) { kept[rank] = tris[t]; });
    tris = std::move(kept);
  }
  if (tris.empty())
    throw Error(ErrorKind::InvalidInput,
                "no usable triangle remains (all are degenerate or have non-finite coordinates).");
  // From here on the vertices are numbered by first use, every one used:
  // dropping a duplicate (a later triangle on an earlier one's vertices)
  // leaves every vertex used and its number the first use's, a flip below
  // swaps two corners of a triangle (so two vertices first used by a
  // flipped triangle keep the order of its corners before the flip), and a
  // split vertex's copies come last.
  const size_t used = number_by_first_use(tris, points);
  report.unreferenced_vertices = nv - report.welded_vertices - used;

  // Triangles at each vertex, the topology's lists, grouped on every
  // thread: split_fans finds vertices of several fans by them. They stay
  // the repaired mesh's unless a vertex is split (rare). (A count and a
  // corner per vertex, found on the calling thread, cost 31 M instructions
  // at 1.1M triangles on either thread count.)
  // Grouped before the pairing (the orientation's flips do not move a
  // triangle between vertices): their 15 MB then take the heap's space the
  // weld left, not new space beside the pairing's arrays (the WASM heap at
  // 1.1M triangles 214 -> 203 MB).
  // Duplicates (the same vertex set; the first one stays) are found while
  // the half-edges are paired, and only a mesh that has some is paired again.
  // The edges are recorded in result.topology meanwhile.
  Topology& topology = result.topology;
  detail::group_vertex_triangles(tris, used, topology);
  EdgePairs pairs = pair_half_edges(tris, used, topology);
  if (pairs.duplicates) {
    drop_duplicates(tris, used, report);
    detail::group_vertex_triangles(tris, used, topology);
    pairs = pair_half_edges(tris, used, topology);
  }
  // The boundary edges of the recorded topology, where it stays the repaired mesh's (below).
  const std::vector<uint32_t> boundary_edges = std::move(pairs.single_edges);
  Orientation orientation = orient(tris, points, std::move(pairs), topology, report);
  report.components = orientation.components;
  // With several components each triangle's is kept for its vertices' (below).
  const bool several = orientation.components > 1;
  UninitialisedVector<uint32_t> triangle_component;
  if (several) triangle_component = std::move(orientation.component);
  orientation.component = {};
  const bool split = split_fans(tris, points, orientation, topology, report);
  orientation.partner = {};

  result.mesh.positions = std::move(points);
  result.mesh.triangles = std::move(tris);
  const size_t vertex_count = result.mesh.positions.size();  // the copies too

  report.boundary_edges = count_boundary_edges(result.mesh.triangles, orientation);
  // The recorded edges are the repaired mesh's unless an edge had more than
  // two triangles or a vertex was split (both rare). At 1.1M triangles
  // (2205fb1, callgrind, 1 thread) the Pipeline's build_topology took 0.44 G
  // instructions; this 0.17 G more here.
  if (report.nonmanifold_edges == 0 && !split)
    detail::flag_boundary_vertices(vertex_count, topology, &boundary_edges);
  else
    topology = build_topology(result.mesh);
  // Each vertex's component is its first triangle's: once its fans are split
  // a vertex's triangles are one fan, joined through uncut edges, so in one
  // component (numbered in order of seeds, the first triangle of each:
  // component_frames' order of first appearance).
  result.components.count = orientation.components;
  if (several) {
    result.components.vertex.resize(vertex_count);
    parallel_for(vertex_count, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v)
        result.components.vertex[v] = triangle_component[topology.vertex_triangles[topology.vertex_offsets[v]]];
    });
  }
  return result;
}

}  // namespace

RepairResult repair_mesh(const TriangleSoup& soup, const RepairOptions& options) {
  return repair(soup, nullptr, options);
}

RepairResult repair_mesh(TriangleSoup&& soup, const RepairOptions& options) {
  try {
    return repair(soup, &soup, options);
  } catch (...) {
    release_arrays(soup);
    throw;
  }
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
