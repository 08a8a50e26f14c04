#pragma once
// Geometry helpers of the quality harness's metrics: a uniform grid for
// "is any point within r?" and polylines resampled at a fixed spacing.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "crestline/lines/polylines.h"

namespace crestline::quality {

// Points in a uniform grid of cell size `cell`, for "anything within r ≤ cell?".
class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void add(const Vec3& p, uint32_t id) { cells_[key(coord(p.x()), coord(p.y()), coord(p.z()))].push_back({p, id}); }
  /// Calls f(id) for every stored point within r of p (r ≤ cell).
  template <class F>
  void near(const Vec3& p, double r, F&& f) const {
    const int64_t cx = coord(p.x()), cy = coord(p.y()), cz = coord(p.z());
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find(key(cx + dx, cy + dy, cz + dz));
          if (it == cells_.end()) continue;
          for (const auto& [q, id] : it->second)
            if ((q - p).squaredNorm() <= r * r) f(id);
        }
  }
  bool any_near(const Vec3& p, double r) const {
    bool found = false;
    near(p, r, [&](uint32_t) { found = true; });
    return found;
  }

 private:
  int64_t coord(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
  static int64_t key(int64_t x, int64_t y, int64_t z) {
    return (x & 0x1fffff) | ((y & 0x1fffff) << 21) | ((z & 0x1fffff) << 42);
  }
  double cell_;
  std::unordered_map<int64_t, std::vector<std::pair<Vec3, uint32_t>>> cells_;
};

// A polyline resampled at spacing ≤ step; each sample carries the length it stands for.
struct Sample {
  Vec3 point;
  double length;
};
inline std::vector<Sample> resample(const Polyline& line, double step) {
  std::vector<Sample> out;
  const size_t n = line.points.size();
  const size_t segments = line.closed ? n : (n ? n - 1 : 0);
  for (size_t i = 0; i < segments; ++i) {
    const Vec3 &a = line.points[i], &b = line.points[(i + 1) % n];
    const double len = (b - a).norm();
    const int pieces = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int k = 0; k < pieces; ++k) out.push_back({a + (k + 0.5) / pieces * (b - a), len / pieces});
  }
  return out;
}

}  // namespace crestline::quality
