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

namespace {

// Fairing as two full passes, Δx into one array and Δ²x into another, then
// the clamped update: the form fair_polylines' one-pass window must match.
std::vector<Vec3> two_pass_fairing(std::vector<Vec3> x, bool closed, double bound, int iterations) {
  const size_t n = x.size();
  auto laplacian = [&](const std::vector<Vec3>& y) {
    std::vector<Vec3> out(n, Vec3::Zero());
    for (size_t i = 1; i + 1 < n; ++i) out[i] = 0.5 * (y[i - 1] + y[i + 1]) - y[i];
    if (closed) {
      out[0] = 0.5 * (y[n - 1] + y[1]) - y[0];
      out[n - 1] = 0.5 * (y[n - 2] + y[0]) - y[n - 1];
    }
    return out;
  };
  const std::vector<Vec3> original = x;
  for (int it = 0; it < iterations; ++it) {
    const std::vector<Vec3> bilap = laplacian(laplacian(x));
    for (size_t i = closed ? 0 : 1; i < (closed ? n : n - 1); ++i) {
      Vec3 p = x[i] - 0.25 * bilap[i];
      const Vec3 moved = p - original[i];
      const double d = moved.norm();
      if (d > bound) p = original[i] + moved * (bound / d);
      x[i] = p;
    }
  }
  return x;
}

}  // namespace

TEST_CASE("fairing matches the two-pass bi-Laplacian bit for bit, open and closed, short and long", "[fairing]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  FairingOptions options;
  options.iterations = 5;
  for (const double bound : {0.02, 10.0})  // clamped often, never
    for (const bool closed : {false, true})
      for (const size_t n : {3, 4, 5, 6, 9, 40}) {
        if (closed && n < 4) continue;
        Polyline line;
        line.closed = closed;
        for (size_t i = 0; i < n; ++i) {
          line.points.push_back(Vec3(coordinate(rng), coordinate(rng), coordinate(rng)));
          line.curvature.push_back(1.0);
        }
        options.hausdorff_bound = bound;
        const Polyline faired = fair_polylines({line}, 1.0, options)[0];
        INFO("n " << n << (closed ? " closed" : " open") << ", bound " << bound);
        CHECK(faired.points == two_pass_fairing(line.points, closed, bound, options.iterations));
        CHECK(faired.points != line.points);
      }
}
