#include "crestline/lines/polylines.h"

namespace crestline {

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
  const size_t nn = graph.points.size(), ns = graph.segments.size();
  // Node → incident segments, CSR.
  std::vector<uint32_t> offsets(nn + 1, 0), incident(2 * ns);
  for (const auto& s : graph.segments) ++offsets[s[0] + 1], ++offsets[s[1] + 1];
  for (size_t i = 0; i < nn; ++i) offsets[i + 1] += offsets[i];
  std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
  for (uint32_t s = 0; s < ns; ++s) incident[fill[graph.segments[s][0]]++] = s, incident[fill[graph.segments[s][1]]++] = s;
  auto degree = [&](uint32_t node) { return offsets[node + 1] - offsets[node]; };

  std::vector<uint8_t> used(ns, 0);
  std::vector<Polyline> lines;
  auto walk = [&](uint32_t start, uint32_t first_segment) {
    Polyline line;
    line.type = graph.type;
    uint32_t node = start, segment = first_segment;
    auto add = [&](uint32_t n) {
      line.points.push_back(graph.points[n]);
      line.curvature.push_back(graph.curvature[n]);
    };
    add(node);
    while (true) {
      used[segment] = 1;
      const auto& s = graph.segments[segment];
      node = s[0] == node ? s[1] : s[0];
      if (node == start) {  // back where we began: a loop
        line.closed = true;
        break;
      }
      add(node);
      if (degree(node) != 2) break;
      const uint32_t a = incident[offsets[node]], b = incident[offsets[node] + 1];
      segment = used[a] ? b : a;
      if (used[segment]) break;
    }
    measure_polyline(line);
    lines.push_back(std::move(line));
  };
  // Open chains start at ends and junctions; whatever remains are loops.
  for (uint32_t node = 0; node < nn; ++node)
    if (degree(node) != 2)
      for (uint32_t i = offsets[node]; i < offsets[node + 1]; ++i)
        if (!used[incident[i]]) walk(node, incident[i]);
  for (uint32_t node = 0; node < nn; ++node)
    if (degree(node) == 2 && !used[incident[offsets[node]]]) walk(node, incident[offsets[node]]);
  return lines;
}

}  // namespace crestline
