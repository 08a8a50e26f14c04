#include "crestline/lines/filter.h"

#include <algorithm>

namespace crestline {

// Automatic threshold: lines are sorted by strength and the threshold is a
// fixed fraction of the strength at the 90th percentile of *total* strength
// mass, so that a handful of strong features set the scale and the cloud of
// weak noise lines falls below it.
static double automatic_threshold(const std::vector<Polyline>& lines) {
  std::vector<double> s;
  s.reserve(lines.size());
  double total = 0;
  for (const Polyline& l : lines) s.push_back(l.strength), total += l.strength;
  if (s.empty() || !(total > 0)) return 0;
  std::sort(s.begin(), s.end(), std::greater<double>());
  double acc = 0;
  double reference = s.front();
  for (double v : s) {
    acc += v;
    reference = v;
    if (acc >= 0.5 * total) break;
  }
  return 0.25 * reference;
}

FilterResult filter_lines(const std::vector<Polyline>& lines, const FilterOptions& options) {
  FilterResult out;
  out.threshold = options.threshold >= 0 ? options.threshold : automatic_threshold(lines);
  for (uint32_t i = 0; i < lines.size(); ++i)
    if (lines[i].strength >= out.threshold) out.kept.push_back(i);
  return out;
}

}  // namespace crestline
