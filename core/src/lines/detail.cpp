#include "crestline/lines/detail.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "crestline/numerics/parallel.h"

namespace crestline {
namespace {

struct Interval {
  size_t first, last;
  double cap;
};

// One line's importances into out[0 … points − 1]; `stack` is scratch.
void line_importance(const std::vector<Vec3>& points, float* out, std::vector<Interval>& stack) {
  const size_t n = points.size();
  if (n == 0) return;
  std::fill(out, out + n, 0.0f);
  out[0] = out[n - 1] = std::numeric_limits<float>::infinity();
  stack.assign(1, {0, n - 1, std::numeric_limits<double>::infinity()});
  while (!stack.empty()) {
    const Interval interval = stack.back();
    stack.pop_back();
    const size_t i = interval.first, j = interval.last;
    if (j - i < 2) continue;
    const double ax = points[i].x(), ay = points[i].y(), az = points[i].z();
    const double dx = points[j].x() - ax, dy = points[j].y() - ay, dz = points[j].z() - az;
    const double length2 = dx * dx + dy * dy + dz * dz;
    size_t farthest = i + 1;
    double distance2 = -1;
    for (size_t k = i + 1; k < j; ++k) {
      const double px = points[k].x() - ax, py = points[k].y() - ay, pz = points[k].z() - az;
      // The distance to the chord as a segment (to its nearer end beyond it).
      const double t = length2 > 0 ? std::min(1.0, std::max(0.0, (px * dx + py * dy + pz * dz) / length2)) : 0;
      const double ex = px - t * dx, ey = py - t * dy, ez = pz - t * dz;
      const double d2 = ex * ex + ey * ey + ez * ez;
      if (d2 > distance2) distance2 = d2, farthest = k;
    }
    const double value = std::min(std::sqrt(distance2), interval.cap);
    out[farthest] = static_cast<float>(value);
    stack.push_back({i, farthest, value});
    stack.push_back({farthest, j, value});
  }
}

}  // namespace

std::vector<float> point_importance(const std::vector<Polyline>& lines) {
  std::vector<size_t> first(lines.size() + 1, 0);
  for (size_t l = 0; l < lines.size(); ++l) first[l + 1] = first[l] + lines[l].points.size();
  std::vector<float> importance(first.back());
  // Each line writes its own points: the same numbers for any thread count.
  parallel_for(
      lines.size(),
      [&](size_t begin, size_t end) {
        std::vector<Interval> stack;
        for (size_t l = begin; l < end; ++l) line_importance(lines[l].points, importance.data() + first[l], stack);
      },
      64);
  return importance;
}

}  // namespace crestline
