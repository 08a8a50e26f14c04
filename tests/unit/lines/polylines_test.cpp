#include <catch2/catch.hpp>

#include "crestline/lines/filter.h"
#include "crestline/lines/polylines.h"

using namespace crestline;

namespace {

FeatureGraph graph_with_points(int n, double curvature) {
  FeatureGraph g;
  for (int i = 0; i < n; ++i) {
    g.points.push_back(Vec3(i, 0, 0));
    g.curvature.push_back(curvature);
    g.source.push_back(i);
    g.trisector.push_back(0);
  }
  return g;
}

}  // namespace

TEST_CASE("segments join into maximal open chains with strength = integral of |kappa|", "[polylines]") {
  FeatureGraph g = graph_with_points(5, 2.0);
  g.segments = {{2, 3}, {0, 1}, {3, 4}, {1, 2}};  // unordered on purpose
  const auto lines = join_polylines(g);
  REQUIRE(lines.size() == 1);
  CHECK_FALSE(lines[0].closed);
  CHECK(lines[0].points.size() == 5);
  CHECK(lines[0].length == Approx(4.0));
  CHECK(lines[0].strength == Approx(8.0));
}

TEST_CASE("cycles become closed polylines, junctions end chains", "[polylines]") {
  FeatureGraph g = graph_with_points(4, 1.0);
  g.points[1] = Vec3(1, 0, 0);
  g.points[2] = Vec3(1, 1, 0);
  g.points[3] = Vec3(0, 1, 0);
  g.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  auto lines = join_polylines(g);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].closed);
  CHECK(lines[0].points.size() == 4);
  CHECK(lines[0].length == Approx(4.0));

  // A trisector: three arms meeting at node 0.
  FeatureGraph t = graph_with_points(7, 1.0);
  t.trisector[0] = 1;
  t.segments = {{0, 1}, {1, 2}, {0, 3}, {3, 4}, {0, 5}, {5, 6}};
  lines = join_polylines(t);
  REQUIRE(lines.size() == 3);
  for (const Polyline& l : lines) {
    CHECK(l.points.size() == 3);
    CHECK(l.points.front() == t.points[0]);
  }
}

TEST_CASE("filter keeps lines at or above the threshold, automatic one drops the weak tail", "[filter]") {
  std::vector<Polyline> lines(6);
  const double strengths[] = {50, 40, 30, 0.5, 0.2, 0.1};
  for (int i = 0; i < 6; ++i) lines[i].strength = strengths[i];
  FilterOptions manual;
  manual.threshold = 30;
  CHECK(filter_lines(lines, manual).kept == std::vector<uint32_t>{0, 1, 2});
  const FilterResult automatic = filter_lines(lines, {});
  CHECK(automatic.kept == std::vector<uint32_t>{0, 1, 2});
  CHECK(automatic.threshold > 0.5);
  CHECK(automatic.threshold < 30);
}
