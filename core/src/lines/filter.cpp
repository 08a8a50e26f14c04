#include "crestline/lines/filter.h"

#include <algorithm>

namespace crestline {

// Automatic threshold: a share of the strength of the line at which the
// strongest lines make up half of the total strength, so that the strong
// features set the scale and the cloud of weak noise lines falls below it;
// but never below kMinimumStrength, so that a featureless surface (a sphere,
// a plane) keeps no noise lines at all. Measured on tests/quality (3 seeds ×
// 15 cases × 3 noise levels): a share of 0.25 dropped single rounded-cube
// edges once their neighbours were joined into long lines, 0.1 kept the short
// radial ridges at the ripple's umbilic centre; a floor of 1.0 dropped the
// short segments between crossings of the cosine product (strength 0.8–1.7).
constexpr double kReferenceShare = 0.15;
constexpr double kMinimumStrength = 0.35;
// Lines both weak and short are dropped too (FilterOptions::short_line_edges,
// 6 edges by default): a weak feature that runs for 6 edges and more is a
// feature (the cosine product's segments, 7–14 edges), while a scan's bumps
// leave hundreds of lines of 0.4–1.0 that are shorter (168 of the Stanford
// bunny's 221).
static double automatic_threshold(const std::vector<Polyline>& lines) {
  std::vector<double> s;
  s.reserve(lines.size());
  double total = 0;
  for (const Polyline& l : lines) s.push_back(l.strength), total += l.strength;
  if (s.empty() || !(total > 0)) return kMinimumStrength;
  std::sort(s.begin(), s.end(), std::greater<double>());
  double acc = 0;
  double reference = s.front();
  for (double v : s) {
    acc += v;
    reference = v;
    if (acc >= 0.5 * total) break;
  }
  return std::max(kReferenceShare * reference, kMinimumStrength);
}

FilterResult filter_lines(const std::vector<Polyline>& lines, const FilterOptions& options, double mean_edge_length) {
  FilterResult out;
  out.threshold = options.threshold ? *options.threshold : automatic_threshold(lines);
  const double short_length = options.short_line_edges * mean_edge_length;
  for (uint32_t i = 0; i < lines.size(); ++i) {
    const Polyline& l = lines[i];
    if (l.strength < out.threshold) continue;
    if (l.strength < kWeakStrength && l.length < short_length) continue;
    out.kept.push_back(i);
  }
  return out;
}

}  // namespace crestline
