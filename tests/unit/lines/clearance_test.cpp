#include "crestline/lines/clearance.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace crestline;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A straight line along x from x0 to x1, points `step` apart, curvature f(x).
template <class F>
Polyline line_along_x(double x0, double x1, double step, F&& curvature, double y = 0) {
  Polyline line;
  for (double x = x0; x <= x1 + 1e-12; x += step) {
    line.points.push_back({x, y, 0});
    line.curvature.push_back(curvature(x));
  }
  measure_polyline(line);
  return line;
}

double to_segment(const Vec3& p, const CreaseSegment& s) {
  const Vec3 d = s.ends[1] - s.ends[0];
  const double t = std::clamp((p - s.ends[0]).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (s.ends[0] + t * d)).norm();
}

}  // namespace

TEST_CASE("a line crossing a crease is cut back to the distance on both sides", "[clearance]") {
  // Curvature linear in x, so the value at a cut point is known exactly.
  const Polyline line = line_along_x(-10, 10, 0.7, [](double x) { return x + 20; });
  const std::vector<CreaseSegment> crease{{{Vec3(0, -5, 0), Vec3(0, 5, 0)}, 0}};
  const ClearanceResult r = clear_of_creases({line}, {0}, crease, ClearanceOptions{2.0});
  REQUIRE(r.lines.size() == 2);
  CHECK(r.source == std::vector<uint32_t>{0, 0});
  const Polyline &left = r.lines[0], &right = r.lines[1];
  CHECK(left.points.front().x() == line.points.front().x());
  CHECK(left.points.back().x() == Approx(-2.0).margin(1e-12));
  CHECK(right.points.front().x() == Approx(2.0).margin(1e-12));
  CHECK(right.points.back().x() == line.points.back().x());
  CHECK(left.curvature.back() == Approx(18.0).epsilon(1e-12));
  CHECK(right.curvature.front() == Approx(22.0).epsilon(1e-12));
  // Measured again: ∫(x + 20) dx over each part (trapezoidal is exact for a linear integrand).
  const double x0 = left.points.front().x(), x1 = right.points.back().x();
  CHECK(left.length == Approx(-2.0 - x0).epsilon(1e-12));
  CHECK(left.strength == Approx(0.5 * (-2.0 + 20 + x0 + 20) * (-2.0 - x0)).epsilon(1e-12));
  CHECK(right.length == Approx(x1 - 2.0).epsilon(1e-12));
  CHECK(right.strength == Approx(0.5 * (x1 + 20 + 2.0 + 20) * (x1 - 2.0)).epsilon(1e-12));
  for (const Polyline& part : r.lines) {
    CHECK(part.type == line.type);
    CHECK_FALSE(part.closed);
    for (const Vec3& p : part.points) CHECK(to_segment(p, crease[0]) >= 2.0 - 1e-12);
  }
}

TEST_CASE("clearance reads only the line's own component's creases", "[clearance]") {
  const Polyline line = line_along_x(-10, 10, 0.7, [](double) { return 1.0; });
  const std::vector<CreaseSegment> crease{{{Vec3(0, -5, 0), Vec3(0, 5, 0)}, 1}};
  const ClearanceResult r = clear_of_creases({line}, {0}, crease, ClearanceOptions{2.0});
  REQUIRE(r.lines.size() == 1);
  CHECK(r.lines[0].points == line.points);
  CHECK(r.lines[0].strength == line.strength);
  // The same line in component 1 is cut.
  CHECK(clear_of_creases({line}, {1}, crease, ClearanceOptions{2.0}).lines.size() == 2);
}

TEST_CASE("a distance of 0 or no creases keeps every line", "[clearance]") {
  const Polyline line = line_along_x(-10, 10, 0.7, [](double) { return 1.0; });
  const std::vector<CreaseSegment> crease{{{Vec3(0, -5, 0), Vec3(0, 5, 0)}, 0}};
  for (const ClearanceResult& r : {clear_of_creases({line, line}, {0, 0}, crease, ClearanceOptions{0.0}),
                                   clear_of_creases({line, line}, {0, 0}, {}, ClearanceOptions{2.0})}) {
    REQUIRE(r.lines.size() == 2);
    CHECK(r.source == std::vector<uint32_t>{0, 1});
    CHECK(r.lines[1].points == line.points);
  }
}

TEST_CASE("a line wholly within the distance goes", "[clearance]") {
  const Polyline line = line_along_x(
      -10, 10, 0.7, [](double) { return 1.0; }, 1.5);
  const Polyline far = line_along_x(
      -10, 10, 0.7, [](double) { return 1.0; }, 2.5);
  const std::vector<CreaseSegment> crease{{{Vec3(-20, 0, 0), Vec3(20, 0, 0)}, 0}};
  const ClearanceResult r = clear_of_creases({line, far}, {0, 0}, crease, ClearanceOptions{2.0});
  REQUIRE(r.lines.size() == 1);
  CHECK(r.source == std::vector<uint32_t>{1});
  CHECK(r.lines[0].points == far.points);
}

TEST_CASE("long crease segments are found along their whole length", "[clearance]") {
  // One segment 2000 mean edges long, diagonal through the grid's cells:
  // points 1.9 from it anywhere along it go, points 2.1 away stay.
  const Vec3 a(-700, -600, -500), b(700, 600, 500);
  const std::vector<CreaseSegment> crease{{{a, b}, 0}};
  const Vec3 along = (b - a).normalized(), across = along.cross(Vec3(0, 0, 1)).normalized();
  std::vector<Polyline> lines;
  for (double s : {0.013, 0.25, 0.5, 0.77, 0.999})
    for (double d : {1.9, 2.1}) {
      Polyline l;
      const Vec3 p = a + s * (b - a) + d * across;
      l.points = {p, p + 0.3 * along};
      l.curvature = {1, 1};
      measure_polyline(l);
      lines.push_back(l);
    }
  const ClearanceResult r = clear_of_creases(lines, std::vector<uint32_t>(lines.size(), 0), crease, {2.0});
  CHECK(r.source == std::vector<uint32_t>{1, 3, 5, 7, 9});
}

TEST_CASE("a closed line crossing a crease opens into one line ending at the distance", "[clearance]") {
  // A circle of radius 5 in z = 0 crossing a vertical crease at (5, 0):
  // the part within 2 of it is the arc of |θ| < 2 asin(0.2).
  Polyline circle;
  circle.closed = true;
  const int n = 720;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * kPi * (k + 0.5) / n;
    circle.points.push_back({5 * std::cos(t), 5 * std::sin(t), 0});
    circle.curvature.push_back(0.2);
  }
  measure_polyline(circle);
  const std::vector<CreaseSegment> crease{{{Vec3(5, 0, -1), Vec3(5, 0, 1)}, 0}};
  const ClearanceResult r = clear_of_creases({circle}, {0}, crease, {2.0});
  REQUIRE(r.lines.size() == 1);
  const Polyline& open = r.lines[0];
  CHECK_FALSE(open.closed);
  CHECK(to_segment(open.points.front(), crease[0]) == Approx(2.0).epsilon(1e-12));
  CHECK(to_segment(open.points.back(), crease[0]) == Approx(2.0).epsilon(1e-12));
  const double arc = 5 * (2 * kPi - 4 * std::asin(0.2));
  CHECK(open.length == Approx(arc).epsilon(1e-4));
  CHECK(open.strength == Approx(0.2 * open.length).epsilon(1e-12));
}

TEST_CASE("the clearance is counted in each crease's own edge length", "[clearance]") {
  // Two creases across the line: at x = −5 with edges of 0.5, at x = 5 with
  // edges of 1.5; the line is cut 1 and 3 from them.
  const Polyline line = line_along_x(-10, 10, 0.7, [](double) { return 1.0; });
  std::vector<CreaseSegment> creases{{{Vec3(-5, -5, 0), Vec3(-5, 5, 0)}, 0, 0.5},
                                     {{Vec3(5, -5, 0), Vec3(5, 5, 0)}, 0, 1.5}};
  const ClearanceResult r = clear_of_creases({line}, {0}, creases, ClearanceOptions{2.0});
  REQUIRE(r.lines.size() == 3);
  CHECK(r.lines[0].points.back().x() == Approx(-6.0).margin(1e-12));
  CHECK(r.lines[1].points.front().x() == Approx(-4.0).margin(1e-12));
  CHECK(r.lines[1].points.back().x() == Approx(2.0).margin(1e-12));
  CHECK(r.lines[2].points.front().x() == Approx(8.0).margin(1e-12));
  // An edge length above 8 times the median counts as 8 times it: with a
  // third crease of edge 0.5 far away the median is 0.5, so the second
  // crease's 10 counts as 4 (a cut at 5 − 8), not 10 (which would take the
  // whole line's right part down to x = −15).
  creases[1].edge_length = 10;
  creases.push_back({{Vec3(100, -5, 0), Vec3(100, 5, 0)}, 0, 0.5});
  const ClearanceResult capped = clear_of_creases({line}, {0}, creases, ClearanceOptions{2.0});
  REQUIRE(capped.lines.size() == 2);
  CHECK(capped.lines[1].points.front().x() == Approx(-4.0).margin(1e-12));
  CHECK(capped.lines[1].points.back().x() == Approx(-3.0).margin(1e-12));
}
