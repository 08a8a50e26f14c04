#include "crestline/lines/fairing.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "analytic_meshes.h"

using namespace crestline;

namespace {

// Distance from p to the polyline.
double distance_to(const Vec3& p, const Polyline& line) {
  double best = INFINITY;
  const size_t n = line.points.size(), segs = line.closed ? n : n - 1;
  for (size_t i = 0; i < segs; ++i) {
    const Vec3 &a = line.points[i], &b = line.points[(i + 1) % n];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

double hausdorff(const Polyline& a, const Polyline& b) {
  double d = 0;
  for (const Vec3& p : a.points) d = std::max(d, distance_to(p, b));
  for (const Vec3& p : b.points) d = std::max(d, distance_to(p, a));
  return d;
}

// Sum of squared second differences: how wiggly a polyline is.
double wiggle(const Polyline& l) {
  double s = 0;
  for (size_t i = 1; i + 1 < l.points.size(); ++i)
    s += (l.points[i - 1] - 2 * l.points[i] + l.points[i + 1]).squaredNorm();
  return s;
}

}  // namespace

TEST_CASE("fairing smooths a noisy arc within the Hausdorff bound, ends fixed", "[fairing]") {
  Polyline noisy;
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0, 0.02);
  for (int i = 0; i <= 100; ++i) {
    const double a = testing::kPi * i / 100;
    noisy.points.push_back(Vec3(std::cos(a), std::sin(a), 0) + Vec3(noise(rng), noise(rng), noise(rng)));
    noisy.curvature.push_back(1.0);
  }
  measure_polyline(noisy);
  const double h = 0.05;  // "mean edge length"
  FairingOptions options;
  options.hausdorff_bound = 0.5;  // 0.025 absolute
  const Polyline faired = fair_polylines({noisy}, h, options)[0];
  CHECK(hausdorff(faired, noisy) <= 0.5 * h + 1e-12);
  CHECK(wiggle(faired) < 0.3 * wiggle(noisy));
  CHECK(faired.points.front() == noisy.points.front());
  CHECK(faired.points.back() == noisy.points.back());
  CHECK(faired.strength == noisy.strength);

  // Bi-Laplacian fairing does not shrink a clean circle the way Laplace would.
  Polyline circle;
  circle.closed = true;
  for (int i = 0; i < 60; ++i) {
    const double a = 2 * testing::kPi * i / 60;
    circle.points.push_back(Vec3(std::cos(a), std::sin(a), 0));
    circle.curvature.push_back(1.0);
  }
  options.hausdorff_bound = 10;
  const Polyline round = fair_polylines({circle}, h, options)[0];
  for (const Vec3& p : round.points) CHECK(p.norm() == Approx(1.0).epsilon(0.01));

  options.hausdorff_bound = 0;
  CHECK(fair_polylines({noisy}, h, options)[0].points == noisy.points);
}
