#include "crestline/lines/polylines.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "crestline/lines/filter.h"
#include "crestline/numerics/parallel.h"

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
  for (int i = 0; i < 6; ++i) lines[i].strength = strengths[i], lines[i].length = 100;
  FilterOptions manual;
  manual.threshold = 30;
  CHECK(filter_lines(lines, manual, 1.0).kept == std::vector<uint32_t>{0, 1, 2});
  // Reference: 40 (50 + 40 pass half of 120.8); 0.15 · 40 = 6.
  const FilterResult automatic = filter_lines(lines, {}, 1.0);
  CHECK(automatic.kept == std::vector<uint32_t>{0, 1, 2});
  CHECK(automatic.threshold == Approx(6.0));
}

TEST_CASE("automatic threshold: a floor for featureless meshes, weak lines kept only when long", "[filter]") {
  // All lines alike (a scan's bumps, or noise): the share of the reference
  // alone would keep them all; the floor of 0.35 drops them.
  std::vector<Polyline> noise(20);
  for (Polyline& l : noise) l.strength = 0.3, l.length = 10;
  const FilterResult featureless = filter_lines(noise, {}, 1.0);
  CHECK(featureless.threshold == Approx(0.35));
  CHECK(featureless.kept.empty());
  // Weak lines (strength 0.5–1) pass when they run for 6 mean edges or more.
  std::vector<Polyline> weak(4);
  const double lengths[] = {5.9, 6.0, 20, 3};
  for (int i = 0; i < 4; ++i) weak[i].strength = 0.8, weak[i].length = lengths[i] * 0.5;
  CHECK(filter_lines(weak, {}, 0.5).kept == std::vector<uint32_t>{1, 2});
  // A strong short line passes.
  weak[3].strength = 1.5;
  const FilterResult automatic = filter_lines(weak, {}, 1.0 / 2);
  CHECK(automatic.kept == std::vector<uint32_t>{1, 2, 3});
  // The same threshold set by hand keeps the same lines: the length rule
  // does not depend on the mode; short_line_edges = 0 turns it off.
  FilterOptions manual;
  manual.threshold = automatic.threshold;
  CHECK(filter_lines(weak, manual, 0.5).kept == automatic.kept);
  manual.threshold = 0.5;
  CHECK(filter_lines(weak, manual, 0.5).kept == std::vector<uint32_t>{1, 2, 3});
  manual.short_line_edges = 0;
  CHECK(filter_lines(weak, manual, 0.5).kept == std::vector<uint32_t>{0, 1, 2, 3});
}

TEST_CASE("a line runs straight through a junction; its side branch ends there", "[polylines]") {
  // A straight line along x through node 0 and a branch going up from it.
  FeatureGraph g = graph_with_points(7, 1.0);
  g.points = {Vec3(0, 0, 0), Vec3(-1, 0, 0),  Vec3(-2, 0, 0), Vec3(1, 0, 0),
              Vec3(2, 0, 0), Vec3(0.1, 1, 0), Vec3(0.2, 2, 0)};
  g.trisector[0] = 1;
  g.segments = {{0, 1}, {1, 2}, {0, 3}, {3, 4}, {0, 5}, {5, 6}};
  const auto lines = join_polylines(g);
  REQUIRE(lines.size() == 2);
  const Polyline& through = lines[0].points.size() == 5 ? lines[0] : lines[1];
  CHECK(through.points.size() == 5);
  CHECK(through.length == Approx(4.0));
}

TEST_CASE("small aligned gaps are bridged, loops with a gap close, misaligned ends stay apart", "[polylines]") {
  // Two collinear chains with a gap of one segment between nodes 2 and 3.
  FeatureGraph g = graph_with_points(6, 1.0);
  g.segments = {{0, 1}, {1, 2}, {3, 4}, {4, 5}};
  auto lines = join_polylines(g);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].points.size() == 6);
  CHECK(lines[0].length == Approx(5.0));
  CHECK_FALSE(lines[0].closed);

  // A circle traced with one segment missing comes back closed.
  FeatureGraph c;
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n;
    c.points.push_back(Vec3(std::cos(a), std::sin(a), 0));
    c.curvature.push_back(1.0);
    c.source.push_back(i);
    c.trisector.push_back(0);
  }
  for (int i = 0; i + 1 < n; ++i) c.segments.push_back({uint32_t(i), uint32_t(i + 1)});
  lines = join_polylines(c);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].closed);
  CHECK(lines[0].points.size() == size_t(n));

  // Ends side by side but pointing the same way (parallel lines) stay apart.
  FeatureGraph p = graph_with_points(6, 1.0);
  p.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 0.5, 0), Vec3(1, 0.5, 0), Vec3(2, 0.5, 0)};
  p.segments = {{0, 1}, {1, 2}, {3, 4}, {4, 5}};
  CHECK(join_polylines(p).size() == 2);
}

TEST_CASE("build_polylines: ridges then valleys, the same on one thread and two", "[polylines][threads]") {
  FeatureGraph ridges = graph_with_points(6, 1.0), valleys = graph_with_points(4, 2.0);
  ridges.type = LineType::Ridge, valleys.type = LineType::Valley;
  for (int i = 3; i < 6; ++i) ridges.points[i] = Vec3(i, 5, 0);
  ridges.segments = {{0, 1}, {1, 2}, {3, 4}, {4, 5}};  // two chains, too far apart to bridge
  valleys.points[2] = Vec3(0, 5, 0), valleys.points[3] = Vec3(1, 5, 0);
  valleys.segments = {{0, 1}, {2, 3}};
  const int before = max_threads();
  auto run = [&](int threads) {
    set_max_threads(threads);
    return build_polylines(ridges, valleys, Mesh{}, Topology{}, PolylinesInput{});
  };
  const PolylinesResult one = run(1), two = run(2);
  set_max_threads(before);
  REQUIRE(one.lines.size() == 4);
  REQUIRE(two.lines.size() == 4);
  CHECK(one.component == std::vector<uint32_t>(4, 0));
  CHECK(two.component == one.component);
  for (size_t i = 0; i < 4; ++i) {
    CHECK(one.lines[i].type == (i < 2 ? LineType::Ridge : LineType::Valley));
    CHECK(two.lines[i].type == one.lines[i].type);
    CHECK(two.lines[i].points == one.lines[i].points);
    CHECK(two.lines[i].strength == one.lines[i].strength);
  }
  CHECK(one.lines[2].strength == Approx(2.0));
}

TEST_CASE("gaps across the end sweep's axis: bridged within the bound in y and z, not beyond", "[polylines]") {
  // Ends are swept in x, and pairs far apart in y or z are dropped before
  // their distance: lines along y and z, all at x = 0, test that shortcut.
  for (int axis = 1; axis < 3; ++axis)
    for (const double gap : {3.9, 4.1}) {  // the bound: 4 mean segment lengths, here 4
      FeatureGraph g = graph_with_points(6, 1.0);
      for (int i = 0; i < 6; ++i) {
        g.points[i] = Vec3::Zero();
        g.points[i][axis] = i < 3 ? i : 2 + gap + (i - 3);
      }
      g.segments = {{0, 1}, {1, 2}, {3, 4}, {4, 5}};
      INFO("axis " << axis << ", gap " << gap);
      CHECK(join_polylines(g).size() == (gap < 4 ? 1u : 2u));
    }
}

TEST_CASE("gaps among many ends spread along y: each bridged within the bound, whatever the y bands", "[polylines]") {
  // 40 pairs of lines along y, all at x = 0, each pair's gap in its own
  // place relative to the sweep's y bands (2 bounds wide): every pair is
  // bridged below the bound and none above it, and no two pairs are.
  for (const double gap : {3.9, 4.1}) {
    FeatureGraph g = graph_with_points(6 * 40, 1.0);
    for (int pair = 0; pair < 40; ++pair) {
      const double y0 = 13.3 * pair;
      for (int i = 0; i < 6; ++i) g.points[6 * pair + i] = Vec3(0, y0 + (i < 3 ? i : 2 + gap + (i - 3)), 0);
      const uint32_t n = 6 * pair;
      g.segments.insert(g.segments.end(), {{n, n + 1}, {n + 1, n + 2}, {n + 3, n + 4}, {n + 4, n + 5}});
    }
    INFO("gap " << gap);
    CHECK(join_polylines(g).size() == (gap < 4 ? 40u : 80u));
  }
}
