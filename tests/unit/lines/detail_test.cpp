#include "crestline/lines/detail.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "mesh/on_threads.h"

using namespace crestline;

namespace {

// Wiggly open and closed curves of 1 to `most` points, some points repeated.
std::vector<Polyline> random_lines(uint32_t seed, int count, int most) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Polyline> lines(count);
  for (int l = 0; l < count; ++l) {
    const int n = 1 + static_cast<int>(unit(random) * most);
    const double a = 9 * unit(random), b = 7 * unit(random);
    for (int i = 0; i < n; ++i) {
      const double t = 2 * 3.14159265358979323846 * i / n;
      if (i > 0 && unit(random) < 0.05)
        lines[l].points.push_back(lines[l].points.back());
      else
        lines[l].points.push_back(
            {std::cos(t + a) + 0.02 * std::sin(b * t), 0.7 * std::sin(t), 0.03 * std::sin(a * t)});
    }
    lines[l].closed = unit(random) < 0.3;
  }
  return lines;
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double length2 = d.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0;
  return (p - a - t * d).norm();
}

// Douglas–Peucker at `tolerance`, recursively, as the textbook has it.
void split(const std::vector<Vec3>& points, size_t i, size_t j, double tolerance, std::vector<uint8_t>& keep) {
  size_t farthest = 0;
  double distance = -1;
  for (size_t k = i + 1; k < j; ++k) {
    const double d = segment_distance(points[k], points[i], points[j]);
    if (d > distance) distance = d, farthest = k;
  }
  if (distance < 0 || !(static_cast<float>(distance) > tolerance)) return;
  keep[farthest] = 1;
  split(points, i, farthest, tolerance, keep);
  split(points, farthest, j, tolerance, keep);
}

}  // namespace

TEST_CASE("point_importance: the points above a tolerance are Douglas-Peucker's at it, each left out within it") {
  const std::vector<Polyline> lines = random_lines(11, 60, 300);
  const std::vector<float> importance = point_importance(lines);
  size_t total = 0;
  for (const Polyline& line : lines) total += line.points.size();
  REQUIRE(importance.size() == total);
  for (const double tolerance : {1e-5, 1e-4, 1e-3, 4e-3, 0.02, 0.1}) {
    size_t offset = 0, kept = 0;
    double worst = 0;
    for (const Polyline& line : lines) {
      const std::vector<Vec3>& p = line.points;
      std::vector<uint8_t> keep(p.size(), 0);
      keep.front() = keep.back() = 1;
      split(p, 0, p.size() - 1, tolerance, keep);
      size_t previous = 0;
      for (size_t k = 0; k < p.size(); ++k) {
        INFO("tolerance " << tolerance << ", point " << k << " of " << p.size());
        REQUIRE((importance[offset + k] > tolerance) == (keep[k] == 1));
        if (!keep[k] || k == 0) continue;
        for (size_t m = previous + 1; m < k; ++m) worst = std::max(worst, segment_distance(p[m], p[previous], p[k]));
        previous = k;
        ++kept;
      }
      CHECK(std::isinf(importance[offset]));
      CHECK(std::isinf(importance[offset + p.size() - 1]));
      offset += p.size();
    }
    CHECK(worst <= tolerance * (1 + 1e-6));
    if (tolerance >= 1e-3) CHECK(kept < total / 2);
  }
}

TEST_CASE("point_importance: the same numbers on 1, 2 and 3 threads") {
  const std::vector<Polyline> lines = random_lines(5, 400, 200);
  const std::vector<float> one = testing::on_threads(1, [&] { return point_importance(lines); });
  for (const int threads : {2, 3}) {
    const std::vector<float> many = testing::on_threads(threads, [&] { return point_importance(lines); });
    REQUIRE(many == one);
  }
  CHECK(point_importance({}).empty());
}
