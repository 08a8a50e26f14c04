#include "crestline/lines/filter.h"

#include <algorithm>

namespace crestline {

// Automatic threshold: a quarter of the strength of the line at which the
// strongest lines make up half of the total strength, so that the strong
// features set the scale and the cloud of weak noise lines falls below it;
// but never below kMinimumStrength, so that a featureless surface (a sphere,
// a plane) keeps no noise lines at all.
constexpr double kMinimumStrength = 1.0;
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
  return std::max(0.25 * reference, kMinimumStrength);
}

FilterResult filter_lines(const std::vector<Polyline>& lines, const FilterOptions& options) {
  FilterResult out;
  out.threshold = options.threshold >= 0 ? options.threshold : automatic_threshold(lines);
  for (uint32_t i = 0; i < lines.size(); ++i)
    if (lines[i].strength >= out.threshold) out.kept.push_back(i);
  return out;
}

}  // namespace crestline
