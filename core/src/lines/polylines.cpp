#include "crestline/lines/polylines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "crestline/mesh/topology.h"
#include "crestline/numerics/parallel.h"

namespace crestline {
namespace {

// Arms of a junction whose directions are at least this far from parallel
// (cos 135°) are one line running through it; the remaining arms end there.
constexpr double kStraightThrough = -0.7071;
// Two line ends are bridged when they are at most this many mean segment
// lengths apart (a segment crosses one triangle, so about an edge length)...
constexpr double kMaxGapSegments = 4.0;
// ...and both end tangents point across the gap (within 60°) and continue
// each other (within 45°: where three ridges meet at a rounded corner, about
// 60° apart, they stay separate lines). Across a gap shorter than a segment
// the gap's own direction is round-off; only the tangents are compared there.
constexpr double kGapAlignment = 0.5;
constexpr double kEndsContinue = 0.7071;
constexpr double kTinyGapSegments = 1.0;
// End tangents are taken over 2 segments (tightly curved lines, such as a
// small loop with a gap) and over 5 (the last one or two segments often hook
// sideways where the zero set breaks up); either pair may qualify a gap.
constexpr size_t kEndTangentSegments[] = {2, 5};

struct NodeIncidence {
  std::vector<uint32_t> offsets, incident;
  uint32_t degree(uint32_t node) const { return offsets[node + 1] - offsets[node]; }
};

NodeIncidence incidence(const FeatureGraph& graph) {
  const size_t nn = graph.points.size(), ns = graph.segments.size();
  NodeIncidence out;
  out.offsets.assign(nn + 1, 0);
  out.incident.resize(2 * ns);
  for (const auto& s : graph.segments) ++out.offsets[s[0] + 1], ++out.offsets[s[1] + 1];
  for (size_t i = 0; i < nn; ++i) out.offsets[i + 1] += out.offsets[i];
  std::vector<uint32_t> fill(out.offsets.begin(), out.offsets.end() - 1);
  for (uint32_t s = 0; s < ns; ++s) {
    out.incident[fill[graph.segments[s][0]]++] = s;
    out.incident[fill[graph.segments[s][1]]++] = s;
  }
  return out;
}

uint32_t other_end(const FeatureGraph& graph, uint32_t segment, uint32_t node) {
  const auto& s = graph.segments[segment];
  return s[0] == node ? s[1] : s[0];
}

// At every junction (degree ≥ 3), pairs the arms that continue each other
// most straightly, greedily from the straightest pair. partner[k] refers to
// the incidence slot k (offsets[node] + i); kNone where the arm ends.
std::vector<uint32_t> pair_junction_arms(const FeatureGraph& graph, const NodeIncidence& inc) {
  std::vector<uint32_t> partner(inc.incident.size(), kNone);
  const size_t nn = graph.points.size();
  for (uint32_t node = 0; node < nn; ++node) {
    const uint32_t begin = inc.offsets[node], d = inc.degree(node);
    if (d < 3) continue;
    std::vector<Vec3> dir(d);
    for (uint32_t i = 0; i < d; ++i) {
      const Vec3 v = graph.points[other_end(graph, inc.incident[begin + i], node)] - graph.points[node];
      const double len = v.norm();
      dir[i] = len > 0 ? Vec3(v / len) : Vec3::Zero();
    }
    struct Pair {
      double cosine;
      uint32_t a, b;
    };
    std::vector<Pair> pairs;
    for (uint32_t a = 0; a < d; ++a)
      for (uint32_t b = a + 1; b < d; ++b) {
        const double c = dir[a].dot(dir[b]);
        if (c < kStraightThrough) pairs.push_back({c, a, b});
      }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.cosine < y.cosine; });
    for (const Pair& p : pairs)
      if (partner[begin + p.a] == kNone && partner[begin + p.b] == kNone) {
        partner[begin + p.a] = begin + p.b;
        partner[begin + p.b] = begin + p.a;
      }
  }
  return partner;
}

std::vector<Polyline> walk_chains(const FeatureGraph& graph, const NodeIncidence& inc,
                                  const std::vector<uint32_t>& partner, std::vector<uint8_t>& open_end_node) {
  const size_t nn = graph.points.size(), ns = graph.segments.size();
  std::vector<uint8_t> used(ns, 0);
  std::vector<Polyline> lines;
  // The slot of `segment` among `node`'s incidences.
  auto slot = [&](uint32_t node, uint32_t segment) {
    for (uint32_t k = inc.offsets[node]; k < inc.offsets[node + 1]; ++k)
      if (inc.incident[k] == segment) return k;
    return kNone;
  };
  // The segment that continues the line arriving at `node` along `segment`, or kNone.
  auto next = [&](uint32_t node, uint32_t segment) -> uint32_t {
    const uint32_t d = inc.degree(node);
    if (d == 2) {
      const uint32_t a = inc.incident[inc.offsets[node]], b = inc.incident[inc.offsets[node] + 1];
      return a == segment ? b : a;
    }
    if (d < 2) return kNone;
    const uint32_t p = partner[slot(node, segment)];
    return p == kNone ? kNone : inc.incident[p];
  };
  // A line's nodes, gathered here and then copied into vectors of their
  // size: one allocation each, not one per doubling (1.1M triangles, 1
  // thread: join_polylines 165.0 -> 135.2 M instructions).
  std::vector<uint32_t> nodes;
  auto walk = [&](uint32_t start, uint32_t first_segment) {
    Polyline line;
    line.type = graph.type;
    nodes.clear();
    uint32_t node = start, segment = first_segment;
    nodes.push_back(node);
    while (true) {
      used[segment] = 1;
      node = other_end(graph, segment, node);
      segment = next(node, segment);
      if (node == start && segment == first_segment) {  // back where we began: a loop
        line.closed = true;
        break;
      }
      nodes.push_back(node);
      if (segment == kNone || used[segment]) break;
    }
    line.points.resize(nodes.size()), line.curvature.resize(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i)
      line.points[i] = graph.points[nodes[i]], line.curvature[i] = graph.curvature[nodes[i]];
    // Line ends at degree-1 nodes may be bridged to a neighbouring line later.
    open_end_node.push_back(!line.closed && inc.degree(start) == 1);
    open_end_node.push_back(!line.closed && inc.degree(node) == 1);
    measure_polyline(line);
    lines.push_back(std::move(line));
  };
  // Open chains start at ends and at junction arms that end there; whatever
  // remains are loops (possibly running through junctions).
  for (uint32_t node = 0; node < nn; ++node) {
    if (inc.degree(node) == 2) continue;
    for (uint32_t k = inc.offsets[node]; k < inc.offsets[node + 1]; ++k)
      if (!used[inc.incident[k]] && (inc.degree(node) == 1 || partner[k] == kNone)) walk(node, inc.incident[k]);
  }
  for (uint32_t s = 0; s < ns; ++s)
    if (!used[s]) walk(graph.segments[s][0], s);
  return lines;
}

// Unit tangent pointing out of the line at one end, over `segments`.
Vec3 end_tangent(const Polyline& line, bool back, size_t segments) {
  const size_t n = line.points.size();
  const size_t reach = std::min<size_t>(segments, n - 1);
  const Vec3 end = back ? line.points[n - 1] : line.points[0];
  const Vec3 inner = back ? line.points[n - 1 - reach] : line.points[reach];
  const Vec3 t = end - inner;
  const double len = t.norm();
  return len > 0 ? Vec3(t / len) : Vec3::Zero();
}

// The pairs (i, j > i) of points sorted by x with x_j − x_i ≤ `reach`, for
// each i in ascending j, as a sweep over the sorted points gives them, but
// only those whose y lies in the same or a neighbouring band of 2 · reach
// (|y_j − y_i| ≤ reach puts them there whatever the rounding of the band
// numbers): a plain sweep reads every point of the x window, at every y.
// Points with a coordinate that is not finite, or bands far more than
// points, fall back to the plain sweep (one band).
struct CloseInX {
  std::vector<uint32_t> band;                  // per point
  std::vector<uint32_t> band_offsets, member;  // each band's points in ascending order
  std::vector<uint32_t> cursor;                // per band: its first point after the last i asked for
  std::vector<uint32_t> out;

  // For ascending i only.
  template <class Point>
  const std::vector<uint32_t>& candidates(const std::vector<Point>& p, uint32_t i, double reach) {
    out.clear();
    const uint32_t b = band[i];
    uint32_t at[3], stop[3], runs = 0;
    for (uint32_t c = b > 0 ? b - 1 : 0; c <= b + 1 && c + 1 < band_offsets.size(); ++c) {
      uint32_t k = cursor[c];
      while (k < band_offsets[c + 1] && member[k] <= i) ++k;
      cursor[c] = k;
      uint32_t end = k;
      while (end < band_offsets[c + 1] && p[member[end]].point.x() - p[i].point.x() <= reach) ++end;
      if (k < end) at[runs] = k, stop[runs] = end, ++runs;
    }
    // The runs merged in ascending point order.
    while (runs > 0) {
      uint32_t best = 0;
      for (uint32_t r = 1; r < runs; ++r)
        if (member[at[r]] < member[at[best]]) best = r;
      out.push_back(member[at[best]]);
      if (++at[best] == stop[best]) at[best] = at[runs - 1], stop[best] = stop[runs - 1], --runs;
    }
    return out;
  }
};

template <class Point>
CloseInX close_in_x(const std::vector<Point>& p, double reach) {
  CloseInX c;
  const size_t n = p.size();
  double lo = INFINITY, hi = -INFINITY;
  bool finite = reach > 0 && std::isfinite(reach);
  for (const Point& e : p) {
    finite = finite && e.point.allFinite();
    lo = std::min(lo, e.point.y()), hi = std::max(hi, e.point.y());
  }
  const double width = 2 * reach;
  const double bands = finite && n > 0 ? std::floor((hi - lo) / width) + 1 : 1;
  // One band unless every position is finite: a band number from a
  // non-finite y (or width) would be a NaN cast to an integer.
  const bool banded = finite && bands <= double(2 * n + 1);
  const uint32_t count = banded ? static_cast<uint32_t>(bands) : 1;
  c.band.resize(n);
  c.band_offsets.assign(count + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    c.band[i] = banded ? std::min(count - 1, static_cast<uint32_t>((p[i].point.y() - lo) / width)) : 0;
    ++c.band_offsets[c.band[i] + 1];
  }
  for (uint32_t k = 0; k < count; ++k) c.band_offsets[k + 1] += c.band_offsets[k];
  c.member.resize(n);
  c.cursor.assign(c.band_offsets.begin(), c.band_offsets.end() - 1);
  std::vector<uint32_t> fill = c.cursor;
  for (uint32_t i = 0; i < n; ++i) c.member[fill[c.band[i]]++] = i;
  return c;
}

// Bridges small gaps between line ends (a start/end singular triangle on
// each side of a noisy spot leaves one): greedily from the smallest gap, two
// free ends are linked when close and aligned; chains of linked lines are
// concatenated, and a chain whose ends meet becomes a closed line.
std::vector<Polyline> bridge_gaps(std::vector<Polyline> lines, const std::vector<uint8_t>& open_end, double segment) {
  const double max_gap = kMaxGapSegments * segment, tiny_gap = kTinyGapSegments * segment;
  struct End {
    Vec3 point;
    std::array<Vec3, 2> tangent;  // over kEndTangentSegments
    uint32_t id;                  // 2 · line + (1 for the back end)
  };
  std::vector<End> ends;
  for (uint32_t l = 0; l < lines.size(); ++l)
    for (int back = 0; back < 2; ++back)
      if (open_end[2 * l + back] && lines[l].points.size() >= 2)
        ends.push_back(
            {back ? lines[l].points.back() : lines[l].points.front(),
             {end_tangent(lines[l], back, kEndTangentSegments[0]), end_tangent(lines[l], back, kEndTangentSegments[1])},
             2 * l + back});
  std::sort(ends.begin(), ends.end(), [](const End& a, const End& b) { return a.point.x() < b.point.x(); });
  struct Gap {
    double length;
    uint32_t a, b;
  };
  std::vector<Gap> gaps;
  CloseInX close = close_in_x(ends, max_gap);
  for (uint32_t i = 0; i < ends.size(); ++i)
    for (uint32_t j : close.candidates(ends, i, max_gap)) {
      const End &a = ends[i], &b = ends[j];
      const Vec3 g = b.point - a.point;
      // Most pairs of the sweep are far apart across it. |g| ≥ |g_y|, |g_z|
      // in floating point too (squares and sums of non-negative terms round
      // monotonically), so this drops only pairs that len > max_gap drops,
      // before the norm (join_polylines 315 → 217 M instructions at 1.1M
      // triangles).
      if (std::abs(g.y()) > max_gap || std::abs(g.z()) > max_gap) continue;
      if (a.id / 2 == b.id / 2 && lines[a.id / 2].points.size() < 4) continue;  // too short to close
      const double len = g.norm();
      if (len > max_gap) continue;
      auto aligned = [&](int k) {
        const Vec3 &ta = a.tangent[k], &tb = b.tangent[k];
        if (len > tiny_gap && (ta.dot(g) < kGapAlignment * len || -tb.dot(g) < kGapAlignment * len)) return false;
        return -ta.dot(tb) >= kEndsContinue;
      };
      if (!aligned(0) && !aligned(1)) continue;
      gaps.push_back({len, a.id, b.id});
    }
  if (gaps.empty()) return lines;
  std::sort(gaps.begin(), gaps.end(), [](const Gap& x, const Gap& y) { return x.length < y.length; });
  std::vector<uint32_t> link(2 * lines.size(), kNone);
  for (const Gap& g : gaps)
    if (link[g.a] == kNone && link[g.b] == kNone) link[g.a] = g.b, link[g.b] = g.a;

  std::vector<uint8_t> done(lines.size(), 0);
  std::vector<Polyline> out;
  // Follows the chain from the line's `entry` end; returns the joined line.
  auto follow = [&](uint32_t line, uint32_t entry_side) {
    Polyline joined;
    joined.type = lines[line].type;
    uint32_t l = line, side = entry_side;
    while (true) {
      done[l] = 1;
      Polyline& piece = lines[l];
      if (side == 1) {  // entered at the back: walk it backwards
        std::reverse(piece.points.begin(), piece.points.end());
        std::reverse(piece.curvature.begin(), piece.curvature.end());
      }
      joined.points.insert(joined.points.end(), piece.points.begin(), piece.points.end());
      joined.curvature.insert(joined.curvature.end(), piece.curvature.begin(), piece.curvature.end());
      const uint32_t exit = 2 * l + (1 - side), to = link[exit];
      if (to == kNone) break;
      if (done[to / 2]) {  // the chain came back to its first line
        joined.closed = true;
        break;
      }
      l = to / 2, side = to % 2;
    }
    measure_polyline(joined);
    return joined;
  };
  for (uint32_t l = 0; l < lines.size(); ++l) {
    if (done[l]) continue;
    const size_t front = 2 * size_t{l}, back = front + 1;
    if (link[front] == kNone && link[back] == kNone) {
      done[l] = 1;
      out.push_back(std::move(lines[l]));
    } else if (link[front] == kNone || link[back] == kNone) {
      out.push_back(follow(l, link[front] == kNone ? 0 : 1));
    }
  }
  // Whatever is left is linked at both ends all round: closed chains.
  for (uint32_t l = 0; l < lines.size(); ++l)
    if (!done[l]) out.push_back(follow(l, 0));
  return out;
}

}  // namespace

void measure_polyline(Polyline& line) {
  line.length = line.strength = 0;
  const size_t n = line.points.size();
  const size_t segments = line.closed ? n : (n ? n - 1 : 0);
  for (size_t i = 0; i < segments; ++i) {
    const size_t j = (i + 1) % n;
    const double ds = (line.points[j] - line.points[i]).norm();
    line.length += ds;
    line.strength += 0.5 * (line.curvature[i] + line.curvature[j]) * ds;
  }
}

std::vector<Polyline> join_polylines(const FeatureGraph& graph) {
  const NodeIncidence inc = incidence(graph);
  const std::vector<uint32_t> partner = pair_junction_arms(graph, inc);
  std::vector<uint8_t> open_end;
  std::vector<Polyline> lines = walk_chains(graph, inc, partner, open_end);
  if (graph.segments.empty()) return lines;
  // The graph's own scale: a segment crosses one triangle.
  double total = 0;
  for (const auto& s : graph.segments) total += (graph.points[s[1]] - graph.points[s[0]]).norm();
  return bridge_gaps(std::move(lines), open_end, total / graph.segments.size());
}

namespace {

// The graph's nodes and segments split by the component they lie on, one
// part per component that has nodes, with that component in part_component.
std::vector<FeatureGraph> split_by_component(const FeatureGraph& graph, const Mesh& mesh, const Topology& topology,
                                             const std::vector<uint32_t>& vertex_component, size_t components,
                                             std::vector<uint32_t>& part_component) {
  std::vector<FeatureGraph> parts;
  part_component.clear();
  std::vector<uint32_t> part_of(components, kNone);
  std::vector<uint32_t> index(graph.points.size()), node_part(graph.points.size());
  for (size_t n = 0; n < graph.points.size(); ++n) {
    const uint32_t vertex =
        graph.trisector[n] ? mesh.triangles[graph.source[n]][0] : topology.edges[graph.source[n]][0];
    const uint32_t c = vertex_component[vertex];
    if (part_of[c] == kNone) {
      part_of[c] = static_cast<uint32_t>(parts.size());
      part_component.push_back(c);
      parts.emplace_back().type = graph.type;
    }
    FeatureGraph& part = parts[node_part[n] = part_of[c]];
    index[n] = static_cast<uint32_t>(part.points.size());
    part.points.push_back(graph.points[n]);
    part.curvature.push_back(graph.curvature[n]);
    part.source.push_back(graph.source[n]);
    part.edge_parameter.push_back(graph.edge_parameter[n]);
    part.trisector.push_back(graph.trisector[n]);
  }
  for (const auto& s : graph.segments) parts[node_part[s[0]]].segments.push_back({index[s[0]], index[s[1]]});
  return parts;
}

}  // namespace

PolylinesResult build_polylines(const FeatureGraph& ridges, const FeatureGraph& valleys, const Mesh& mesh,
                                const Topology& topology, const PolylinesInput& input) {
  // Joining a graph is serial (0.32 G instructions for both at 1.1M
  // triangles), so ridges and valleys are joined on two threads when there
  // are two, each into its own result, concatenated in that order after.
  const FeatureGraph* traced[2] = {&ridges, &valleys};
  PolylinesResult of_type[2];
  parallel_for(
      2,
      [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) {
          const FeatureGraph* graph = traced[k];
          FeatureGraph placed;
          if (input.place_on) {
            placed = *graph;
            place_nodes_on(placed, *input.place_on, topology.edges);
            graph = &placed;
          }
          std::vector<FeatureGraph> parts;
          std::vector<uint32_t> part_component{0};
          if (input.vertex_component && input.components > 1)
            parts =
                split_by_component(*graph, mesh, topology, *input.vertex_component, input.components, part_component);
          PolylinesResult& out = of_type[k];
          for (size_t i = 0; i < part_component.size(); ++i) {
            std::vector<Polyline> lines = join_polylines(parts.empty() ? *graph : parts[i]);
            out.component.insert(out.component.end(), lines.size(), part_component[i]);
            out.lines.insert(out.lines.end(), std::make_move_iterator(lines.begin()),
                             std::make_move_iterator(lines.end()));
          }
        }
      },
      1);
  PolylinesResult out = std::move(of_type[0]);
  out.component.insert(out.component.end(), of_type[1].component.begin(), of_type[1].component.end());
  out.lines.insert(out.lines.end(), std::make_move_iterator(of_type[1].lines.begin()),
                   std::make_move_iterator(of_type[1].lines.end()));
  return out;
}

}  // namespace crestline
