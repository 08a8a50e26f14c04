#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <tuple>

#include "../mesh/same_topology.h"
#include "analytic_meshes.h"
#include "crestline/curvature/extremality.h"
#include "crestline/curvature/extremality_smoothing.h"
#include "crestline/numerics/parallel.h"
#include "run_pipeline.h"

using namespace crestline;

namespace {

TriangleSoup bumpy(double scale = 1.0, Vec3 shift = Vec3::Zero()) {
  testing::GridOptions grid;
  grid.nu = grid.nv = 50;
  grid.jitter = 0.2;
  grid.random_diagonals = true;
  TriangleSoup s = testing::height_field(
      [](double x, double y) { return 0.1 * std::cos(5 * x) * std::cos(4 * y) + 0.05 * std::sin(9 * x + 3 * y); }, 2, 2,
      grid);
  for (size_t i = 0; i < s.positions.size(); ++i) s.positions[i] = s.positions[i] * scale + shift[i % 3];
  return s;
}

// A fold along x = 1 (44° between the sides) in a bumpy field: a boundary
// crease, along which the pipeline cuts the mesh.
Mesh fold() {
  testing::GridOptions grid;
  grid.nu = grid.nv = 40;
  return repair_mesh(
             testing::height_field(
                 [](double x, double y) { return 0.1 * std::cos(5 * x) * std::cos(4 * y) + 0.4 * std::abs(x - 1); }, 2,
                 2, grid))
      .mesh;
}

std::vector<Stage> stages_run(Pipeline& p) {
  std::vector<Stage> ran;
  p.run([&](Stage s, double fraction) {
    if (fraction == 0) ran.push_back(s);
    return true;
  });
  return ran;
}

// The stage a run after a cancel resumes at. The creases stage reports
// first while due, and it stays due until a run completes (so that a client
// learns of new creases from the run that finishes): after a cancel it
// selects again from the kept measure, then the smooth stages resume.
Stage resumed_at(Pipeline& p) {
  const std::vector<Stage> ran = stages_run(p);
  REQUIRE(ran.size() >= 2);
  CHECK(ran.front() == Stage::Creases);
  return ran[1];
}

// A jittered height field of 2 × 150² = 45,000 triangles and 67,650 edges,
// for the tests that count progress reports in blocks of edges.
Mesh jittered_grid_150() {
  testing::GridOptions grid;
  grid.nu = grid.nv = 150;
  grid.jitter = 0.2;
  return repair_mesh(testing::height_field([](double x, double y) { return 0.1 * std::sin(3 * x) * std::cos(2 * y); },
                                           2, 2, grid))
      .mesh;
}

// p's kept lines are reference's, point for point.
void same_lines(const Pipeline& p, const Pipeline& reference) {
  REQUIRE(p.lines().size() == reference.lines().size());
  for (size_t i = 0; i < p.lines().size(); ++i) CHECK(p.lines()[i].points == reference.lines()[i].points);
}

// Runs p and has its progress callback cancel at the `report`-th report of
// `stage` with a fraction above 0; checks that the run stops there (no
// later report).
void cancel_at_report(Pipeline& p, Stage stage, int report) {
  int calls = 0, after = 0;
  CHECK_THROWS_AS(p.run([&](Stage s, double fraction) {
    if (calls == report) ++after;
    if (s == stage && fraction > 0 && ++calls == report) return false;
    return true;
  }),
                  Cancelled);
  CHECK(after == 0);
}

}  // namespace

TEST_CASE("changing the threshold re-runs only the filter", "[pipeline]") {
  Pipeline p(repair_mesh(bumpy()).mesh);
  CHECK(stages_run(p).size() == static_cast<size_t>(Stage::Count));
  const size_t all = p.all_lines().size();
  const size_t automatic = p.lines().size();
  REQUIRE(all > automatic);

  PipelineOptions o = p.options();
  o.filter.threshold = 0;
  o.filter.short_line_edges = 0;
  p.set_options(o);
  CHECK(stages_run(p) == std::vector<Stage>{Stage::Filter});
  CHECK(p.lines().size() == all);

  o.smoothing.steps = 1;
  p.set_options(o);
  const auto ran = stages_run(p);
  REQUIRE(!ran.empty());
  CHECK(ran.front() == Stage::Smoothing);
  // Up to the filter: the creases do not depend on smoothing.
  CHECK(ran.size() == static_cast<size_t>(Stage::Creases) - static_cast<size_t>(Stage::Smoothing));

  p.set_options(o);
  CHECK(stages_run(p).empty());
}

TEST_CASE("with a crease cut, crease and boundary changes give the lines and creases of a fresh run",
          "[pipeline][cut]") {
  // A fold along x = 1 (44° between the sides) in a bumpy field: a boundary
  // crease, so the pipeline cuts the mesh and releases the input in the
  // working frame, its adjacency and crease angles, which measuring and
  // selecting creases then rebuild.
  const Mesh mesh = fold();
  auto same = [](const Pipeline& a, const Pipeline& b) {
    const std::vector<Polyline> la = a.all_kinds(), lb = b.all_kinds();
    REQUIRE(la.size() == lb.size());
    for (size_t i = 0; i < la.size(); ++i) CHECK(la[i].points == lb[i].points);
  };
  Pipeline fresh(mesh);
  fresh.run();
  REQUIRE(!fresh.working_cut().copy_of.empty());
  REQUIRE(fresh.stats().creases > 0);
  REQUIRE(!fresh.lines().empty());

  Pipeline p(mesh);
  p.run();
  same(p, fresh);
  // The cut took the input's adjacency over and made the cut mesh's of it.
  testing::check_same_topology(p.working_topology(), build_topology(p.working_cut().mesh));
  // Released after the run while the cut serves; the adjacency comes back
  // on demand, the same.
  CHECK(p.crease_angles().angle.empty());
  testing::check_same_topology(p.topology(), build_topology(mesh));
  // So are the input's triangles (the cut mesh has them): rebuilt the same.
  CHECK(p.input_mesh().triangles == mesh.triangles);
  PipelineOptions o = p.options();
  o.creases.angle = 80;  // no crease
  p.set_options(o);
  p.run();
  CHECK(p.stats().creases == 0);
  o.creases.boundaries = false;
  p.set_options(o);
  p.run();
  CHECK(p.working_cut().copy_of.empty());
  // Without a cut the input's triangles come back from the working frame's
  // copy, and the crease angles are kept compact after a run: a new crease
  // angle selects from them what a fresh run selects.
  CHECK(p.input_mesh().triangles == mesh.triangles);
  CHECK(p.crease_angles().angle.empty());
  o.creases.angle = 30;
  p.set_options(o);
  p.run();
  Pipeline uncut(mesh);
  uncut.set_options(o);
  uncut.run();
  REQUIRE(uncut.stats().creases > 0);
  same(p, uncut);
  o = PipelineOptions();
  p.set_options(o);
  p.run();
  REQUIRE(!p.working_cut().copy_of.empty());
  same(p, fresh);
  o.creases.normal_filter_steps = 2;  // measured again
  p.set_options(o);
  p.run();
  Pipeline filtered(mesh);
  filtered.set_options(o);
  filtered.run();
  same(p, filtered);
}

TEST_CASE("a re-run from the pre-smoothing after a run, with or without a crease cut, is a fresh run",
          "[pipeline][cut]") {
  // A run releases the working adjacency's triangle lists after the
  // curvature stage; pre-smoothing and curvature need them again. And the
  // pre-smoothed surface in the input's coordinates is made on demand.
  size_t cut = 0;
  for (const Mesh& mesh : {fold(), repair_mesh(bumpy()).mesh}) {
    Pipeline p(mesh);
    p.run();
    PipelineOptions o = p.options();
    o.presmooth.steps = 1;
    p.set_options(o);
    CHECK(stages_run(p).front() == Stage::Presmooth);
    Pipeline fresh(mesh);
    fresh.set_options(o);
    fresh.run();
    REQUIRE(!fresh.lines().empty());
    same_lines(p, fresh);
    CHECK(p.curvature().kappa_max == fresh.curvature().kappa_max);
    // The pre-smoothed surface in the input's coordinates, made when asked for.
    CHECK(p.surface().triangles == mesh.triangles);
    REQUIRE(p.surface().positions.size() == mesh.positions.size());
    CHECK(p.surface().positions == fresh.surface().positions);
    CHECK(p.surface().positions[7] == p.frames().to_user(p.working_surface().positions[7], 0));
    CHECK(p.surface().positions[7] != mesh.positions[7]);
    CHECK(p.working_cut().copy_of.size() == fresh.working_cut().copy_of.size());
    cut += !fresh.working_cut().copy_of.empty();
    testing::check_same_topology(p.working_topology(), build_topology(p.working_surface()));
  }
  CHECK(cut == 1);  // the fold's
}

TEST_CASE("cancelling leaves the pipeline usable", "[pipeline]") {
  Pipeline p(repair_mesh(bumpy()).mesh);
  CHECK_THROWS_AS(p.run([](Stage s, double) { return s != Stage::Tracing; }), Cancelled);
  CHECK(resumed_at(p) == Stage::Tracing);
  CHECK(!p.lines().empty());
}

TEST_CASE("a cancel just before the singular stage resumes with the traced graphs intact", "[pipeline]") {
  // The singular stage takes the traced graphs over (no copy); cancelled
  // before it starts, the next run must still find them.
  const Mesh mesh = repair_mesh(bumpy()).mesh;
  Pipeline reference(mesh);
  reference.run();
  Pipeline p(mesh);
  CHECK_THROWS_AS(p.run([](Stage s, double) { return s != Stage::Singular; }), Cancelled);
  CHECK(resumed_at(p) == Stage::Singular);
  REQUIRE(!reference.lines().empty());
  same_lines(p, reference);
}

TEST_CASE("progress moves inside smoothing and tracing, and a cancel there stops within one iteration", "[pipeline]") {
  Pipeline p(repair_mesh(bumpy()).mesh);
  PipelineOptions o;
  o.smoothing.steps = 3;
  p.set_options(o);
  // Every solver iteration reports: the fractions of the smoothing stage rise
  // strictly inside (0, 1).
  std::vector<double> smoothing;
  int tracing = 0;
  p.run([&](Stage s, double fraction) {
    if (s == Stage::Smoothing && fraction > 0) smoothing.push_back(fraction);
    if (s == Stage::Tracing && fraction > 0) ++tracing;
    return true;
  });
  REQUIRE(smoothing.size() > 3 * 5);  // ≥ 5 iterations per step on this noisy grid
  CHECK(smoothing.front() > 0);
  CHECK(smoothing.back() < 1);
  for (size_t i = 1; i < smoothing.size(); ++i) CHECK(smoothing[i] > smoothing[i - 1]);
  CHECK(tracing == 0);  // 5,000 triangles: fewer than one report's stride
  const std::vector<Polyline> reference = p.lines();

  // Cancel at the 4th iteration: no call after it, the stage is not kept,
  // and the next run from there gives the same lines.
  o.smoothing.time_step = 2;
  p.set_options(o);
  int calls = 0, after = 0;
  CHECK_THROWS_AS(p.run([&](Stage s, double fraction) {
    if (calls >= 4) ++after;
    if (s == Stage::Smoothing && fraction > 0) ++calls;
    return calls < 4;
  }),
                  Cancelled);
  CHECK(calls == 4);
  CHECK(after == 0);
  CHECK(stages_run(p).front() == Stage::Smoothing);
  o.smoothing.time_step = 1;
  p.set_options(o);
  p.run();
  const std::vector<Polyline> again = p.lines();
  REQUIRE(again.size() == reference.size());
  for (size_t i = 0; i < again.size(); ++i) CHECK(again[i].points == reference[i].points);
}

TEST_CASE("curvature, extremality and the smoothing's set-up report progress, and a cancel there keeps nothing",
          "[pipeline]") {
  // 45,000 triangles, ≈ 67,000 edges: the curvature's edge terms come in
  // five blocks (numbers the test asserts, so it fails where a block
  // reports nothing).
  const Mesh mesh = jittered_grid_150();
  REQUIRE(mesh.triangle_count() == 2 * 150 * 150);
  Pipeline reference(mesh);
  std::vector<double> curvature, extremality;
  // The smoothing's calls in its set-up, and after iterations: the first
  // iteration reports 1/11 of the first of the default 3 steps.
  int setup = 0, iterations = 0;
  reference.run([&](Stage s, double fraction) {
    if (s == Stage::Curvature && fraction > 0) curvature.push_back(fraction);
    if (s == Stage::Extremality && fraction > 0) extremality.push_back(fraction);
    if (s == Stage::Smoothing && fraction > 0) (fraction < 1.0 / 33 ? setup : iterations) += 1;
    return true;
  });
  // Normals, five blocks of edges, one block of vertices.
  REQUIRE(curvature.size() == 7);
  for (size_t i = 1; i < curvature.size(); ++i) CHECK(curvature[i] > curvature[i - 1]);
  CHECK(curvature.back() == 1.0);
  CHECK(extremality == std::vector<double>{1.0});
  // Before and after the cotan weights, inside and after the matrix, in the
  // solver's set-up (eight points without a coarse level, as here: after the
  // colouring, the locality order, the coarse level's test, the entries'
  // scaling and each of the fill's four slices), after it.
  CHECK(setup == 13);
  CHECK(iterations > 3);

  // A cancel inside each: the stage is not kept, and the next run gives the same lines.
  for (const Stage at : {Stage::Curvature, Stage::Extremality, Stage::Smoothing}) {
    Pipeline p(mesh);
    // The smoothing's third call: inside its set-up, before any iteration.
    const int wanted = at == Stage::Smoothing ? 3 : 1;
    INFO("cancelled in " << stage_name(at));
    cancel_at_report(p, at, wanted);
    CHECK(resumed_at(p) == at);
    p.run();
    same_lines(p, reference);
  }
}

TEST_CASE("the working positions and edges, released through the smoothing's solves, come back the same",
          "[pipeline][cut]") {
  // With a crease cut (the fold) and without one (its cut off), each after
  // a whole run and after a cancel in the first solve's iterations.
  for (const bool boundaries : {true, false}) {
    INFO("boundaries " << boundaries);
    PipelineOptions o;
    o.creases.boundaries = boundaries;
    Pipeline reference(fold());
    reference.set_options(o);
    // The positions as the smoothing starts, before it releases them.
    std::vector<Vec3> positions;
    reference.run([&](Stage s, double fraction) {
      if (s == Stage::Smoothing && fraction == 0) positions = reference.working_surface().positions;
      return true;
    });
    REQUIRE(reference.working_cut().copy_of.empty() == !boundaries);
    REQUIRE(!positions.empty());
    const Mesh& surface = reference.working_surface();
    CHECK(surface.positions == positions);
    const std::vector<std::array<uint32_t, 2>> edges = build_topology(surface).edges;
    CHECK(reference.working_topology().edges == edges);

    Pipeline p(fold());
    p.set_options(o);
    // The smoothing's first report past its set-up's share (1/66): an iteration.
    int calls = 0;
    CHECK_THROWS_AS(
        p.run([&](Stage s, double fraction) { return !(s == Stage::Smoothing && fraction > 0.02 && ++calls == 1); }),
        Cancelled);
    CHECK(p.working_surface().positions == positions);
    CHECK(p.working_topology().edges == edges);
    p.run();
    same_lines(p, reference);
    CHECK(p.working_surface().positions == positions);
  }
}

TEST_CASE("the crease measure and selection report before the smooth stages, and a cancel there keeps nothing",
          "[pipeline]") {
  // 45,000 triangles, 67,650 edges: the measure reports after the noise
  // level, after each of the 2 filter steps and after the first of two
  // blocks of edges, in shares 1, 1, 1 and 3 (the edges' loop with the filter
  // runs) of 6, as 0.9 of the creases stage; then the selection (with the
  // filter on a clean surface it bridges gaps) at 0.9 between its rounds.
  const Mesh mesh = jittered_grid_150();
  const size_t edges = build_topology(mesh).edges.size();
  REQUIRE(edges > 65536);
  REQUIRE(edges <= 2 * 65536);
  PipelineOptions o;
  o.creases.normal_filter_steps = 2;
  struct Reports {
    std::vector<double> measure;
    int selection = 0;
  };
  const auto run = [](Pipeline& p) {
    Reports r;
    std::vector<Stage> started;
    p.run([&](Stage s, double fraction) {
      if (fraction == 0) started.push_back(s);
      if (s == Stage::Creases && fraction > 0) {
        CHECK(started == std::vector<Stage>{Stage::Creases});  // before any smooth stage
        if (fraction < 0.9) {
          r.measure.push_back(fraction);
        } else {
          CHECK(fraction == 0.9);
          ++r.selection;
        }
      }
      return true;
    });
    CHECK(started.size() == static_cast<size_t>(Stage::Count));
    return r;
  };
  Pipeline reference(mesh);
  reference.set_options(o);
  const Reports reported = run(reference);
  const double block = 3.0 * 65536 / static_cast<double>(edges);
  const std::vector<double> expected = {0.9 * (1.0 / 6), 0.9 * (2.0 / 6), 0.9 * (3.0 / 6), 0.9 * ((3.0 + block) / 6)};
  CHECK(reported.measure == expected);
  CHECK(reported.selection >= 1);
  REQUIRE(!reference.lines().empty());

  // Cancelled inside the filter, or in the selection: nothing after it, and
  // the next run gives the same lines and creases, measuring again, or not
  // where the measure had finished (its angles are kept).
  for (const int at : {2, 5}) {
    INFO("cancelled at the creases' report " << at);
    Pipeline p(mesh);
    p.set_options(o);
    cancel_at_report(p, Stage::Creases, at);
    const Reports again = run(p);
    CHECK(again.measure == (at == 5 ? std::vector<double>{} : expected));
    CHECK(again.selection == reported.selection);
    same_lines(p, reference);
    CHECK(p.crease_result().edges == reference.crease_result().edges);
  }
}

TEST_CASE("the smoothing's progress keeps rising with the most steps the parameters allow", "[pipeline]") {
  // 50 steps: the first iteration reports 1/550 of the stage, and the
  // set-up's reports before it must stay below that.
  Pipeline p(repair_mesh(bumpy()).mesh);
  PipelineOptions o;
  o.smoothing.steps = 50;
  p.set_options(o);
  std::vector<double> smoothing;
  p.run([&](Stage s, double fraction) {
    if (s == Stage::Smoothing && fraction > 0) smoothing.push_back(fraction);
    return true;
  });
  REQUIRE(smoothing.size() > 50);
  CHECK(smoothing.front() < 1.0 / 550);
  for (size_t i = 1; i < smoothing.size(); ++i) CHECK(smoothing[i] > smoothing[i - 1]);
  CHECK(smoothing.back() < 1);
}

TEST_CASE(
    "pre-smoothing reports after each step's set-up and each iteration of its solves, and a cancel there "
    "keeps nothing",
    "[pipeline]") {
  const Mesh mesh = repair_mesh(bumpy()).mesh;
  PipelineOptions o;
  o.presmooth.steps = 2;
  Pipeline reference(mesh);
  reference.set_options(o);
  std::vector<double> fractions;
  reference.run([&](Stage s, double fraction) {
    if (s == Stage::Presmooth && fraction > 0) fractions.push_back(fraction);
    return true;
  });
  // Per step: an eighth after the set-up's weights, then every iteration of
  // the solves (presmooth.cpp), strictly rising; the first iteration of each
  // step at 1/4 + 3/4 · 1/31 of the step.
  REQUIRE(fractions.size() > 20);
  CHECK(fractions[0] == 0.0625);
  CHECK(std::count(fractions.begin(), fractions.end(), 0.5625) == 1);
  CHECK(std::count(fractions.begin(), fractions.end(), (0.25 + 0.75 / 31) / 2) == 1);
  CHECK(std::count(fractions.begin(), fractions.end(), (1 + (0.25 + 0.75 / 31)) / 2) == 1);
  for (size_t i = 1; i < fractions.size(); ++i) CHECK(fractions[i] > fractions[i - 1]);
  CHECK(fractions.back() < 1);
  REQUIRE(!reference.lines().empty());

  // Cancelled inside the first step's solves.
  Pipeline p(mesh);
  p.set_options(o);
  // The first report past the set-up's share: an iteration of the first step's solves.
  const auto first_iteration =
      std::find_if(fractions.begin(), fractions.end(), [](double fraction) { return fraction > 0.125; });
  REQUIRE(first_iteration != fractions.end());
  REQUIRE(*first_iteration < 0.5);
  cancel_at_report(p, Stage::Presmooth, static_cast<int>(first_iteration - fractions.begin()) + 1);
  CHECK(resumed_at(p) == Stage::Presmooth);
  same_lines(p, reference);
}

TEST_CASE("the lines are identical for 1 and 2 threads", "[pipeline][threads]") {
  // 10,201 vertices: enough rows for the solver's reductions to split.
  testing::GridOptions grid;
  grid.nu = grid.nv = 100;
  grid.jitter = 0.2;
  grid.random_diagonals = true;
  const Mesh mesh = repair_mesh(testing::height_field(
                                    [](double x, double y) {
                                      return 0.1 * std::cos(5 * x) * std::cos(4 * y) + 0.05 * std::sin(9 * x + 3 * y);
                                    },
                                    2, 2, grid))
                        .mesh;
  const int before = max_threads();
  auto run = [&](int threads) {
    set_max_threads(threads);
    Pipeline p(mesh);
    p.run();
    return std::make_tuple(p.extremality(), p.lines(), p.stats().smoothing_iterations);
  };
  const auto one = run(1);
  const auto two = run(2);
  set_max_threads(before);
  // 3 steps of a well-conditioned system: a few to a few tens of iterations each.
  CHECK(std::get<2>(one) >= 3 * 3);
  CHECK(std::get<2>(one) <= 3 * 30);
  CHECK(std::get<2>(one) == std::get<2>(two));
  CHECK(std::get<0>(one).e_max == std::get<0>(two).e_max);
  CHECK(std::get<0>(one).e_min == std::get<0>(two).e_min);
  const std::vector<Polyline>&lines_one = std::get<1>(one), &lines_two = std::get<1>(two);
  REQUIRE(!lines_one.empty());
  REQUIRE(lines_one.size() == lines_two.size());
  for (size_t i = 0; i < lines_one.size(); ++i) CHECK(lines_one[i].points == lines_two[i].points);
}

TEST_CASE("parameters are unitless: a scaled, moved model gives the same lines scaled", "[pipeline][scale]") {
  const Pipeline reference = testing::run_pipeline(bumpy());
  const auto ref_lines = reference.lines();
  REQUIRE(ref_lines.size() > 2);
  for (double scale : {1e-3, 1e3}) {
    const Vec3 shift(1e3 * scale, -2e3 * scale, 0);
    const Pipeline p = testing::run_pipeline(bumpy(scale, shift));
    const auto lines = p.lines();
    INFO("scale " << scale);
    REQUIRE(lines.size() == ref_lines.size());
    for (size_t i = 0; i < lines.size(); ++i) {
      CHECK(lines[i].type == ref_lines[i].type);
      REQUIRE(lines[i].points.size() == ref_lines[i].points.size());
      CHECK(lines[i].strength == Approx(ref_lines[i].strength).epsilon(1e-6));
      for (size_t k = 0; k < lines[i].points.size(); ++k)
        CHECK(((lines[i].points[k] - shift) / scale - ref_lines[i].points[k]).norm() < 1e-6);
    }
  }
}

TEST_CASE("stats count what the pipeline produced", "[pipeline]") {
  const Pipeline p = testing::run_pipeline(bumpy());
  const PipelineStats s = p.stats();
  size_t ridges = 0, valleys = 0;
  double ridge_length = 0;
  for (const Polyline& l : p.lines()) {
    if (l.type == LineType::Ridge)
      ++ridges, ridge_length += l.length;
    else
      ++valleys;
  }
  CHECK(s.ridges == ridges);
  CHECK(s.valleys == valleys);
  CHECK(s.ridge_length == Approx(ridge_length));
  CHECK(s.triangles == p.input_mesh().triangle_count());
  CHECK(s.singular_max == p.regularity().singular_max);
  CHECK(s.mean_edge_length > 0);
}

TEST_CASE("the smoothing stage freezes the boundary band it is given", "[pipeline]") {
  const Mesh mesh = repair_mesh(bumpy()).mesh;
  const Topology topology = build_topology(mesh);
  const Curvature curvature = compute_curvature(mesh, topology);
  const Extremality raw = compute_extremality(mesh, curvature);
  ExtremalitySmoothingOptions options;
  options.frozen_boundary_rings = 2;
  const Extremality smoothed = smooth_extremality(mesh, topology, curvature, raw, options);
  const std::vector<uint32_t> distance = boundary_ring_distance(mesh, topology, 2);
  size_t frozen = 0, moved = 0;
  for (size_t v = 0; v < distance.size(); ++v) {
    if (distance[v] < 2) {
      ++frozen;
      CHECK(smoothed.e_max[v] == raw.e_max[v]);
      CHECK(smoothed.e_min[v] == raw.e_min[v]);
    } else {
      moved += smoothed.e_max[v] != raw.e_max[v];
    }
  }
  CHECK(frozen > 300);  // two rings along the 50 × 50 grid's border
  CHECK(moved > distance.size() / 2);
}
