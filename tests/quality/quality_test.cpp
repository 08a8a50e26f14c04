// Issue 9's targets on a representative subset of the quality harness, fast
// enough for CI. crestline_quality_report prints the whole table.
#include <catch2/catch.hpp>
#include <cstdlib>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"
#include "quality_metrics.h"

using namespace crestline;
using namespace crestline::quality;

namespace {

struct Case {
  std::string surface;
  Triangulation triangulation;
  double noise;
};

// Where the defaults miss issue 9's targets (seed 1, measured; README "Line
// quality"): each is held to floors a little below its measured values, so
// it cannot get worse unnoticed; every other case must meet the targets.
struct KnownMiss {
  const char* surface;
  Triangulation triangulation;
  double noise;
  double coverage, precision, fragments;  // floors, floors, ceiling
};
const KnownMiss kKnownMisses[] = {
    {"sine", Triangulation::Graded, 0.00, 0.86, 0.97, 1.5},
    {"sine", Triangulation::Graded, 0.10, 0.86, 0.90, 1.5},
    {"sine", Triangulation::Graded, 0.25, 0.86, 0.95, 1.5},
    {"sine", Triangulation::Graded, 0.50, 0.81, 0.90, 1.5},
    {"cos-product", Triangulation::AnisoAlong, 0.50, 0.85, 0.95, 1.5},
    {"cos-product", Triangulation::AnisoAcross, 0.50, 0.73, 0.95, 1.5},
    {"cos-product", Triangulation::Graded, 0.50, 0.83, 0.94, 1.5},
    {"ripple", Triangulation::AnisoAlong, 0.50, 0.88, 0.96, 1.5},
    {"ripple", Triangulation::AnisoAcross, 0.50, 0.86, 0.97, 1.5},
    {"ripple", Triangulation::Graded, 0.50, 0.87, 0.84, 1.5},
    {"paraboloid", Triangulation::Graded, 0.25, 0.76, 0.54, 1.5},
    {"paraboloid", Triangulation::Graded, 0.50, 0.89, 0.88, 1.5},
};

const KnownMiss* known_miss(const Case& c) {
  for (const KnownMiss& m : kKnownMisses)
    if (c.surface == m.surface && c.triangulation == m.triangulation && c.noise == m.noise) return &m;
  return nullptr;
}

// Mean distance of the lines from the true ones at σ = 0 (issue 13's goal:
// 0.05 mean edges), where it is missed: bounds a little above the measured values.
struct KnownOffset {
  const char* surface;
  Triangulation triangulation;
  double offset;
};
const KnownOffset kKnownOffsets[] = {
    {"sine", Triangulation::Irregular, 0.09},          {"cos-product", Triangulation::Alternating, 0.18},
    {"cos-product", Triangulation::Irregular, 0.18},   {"cos-product", Triangulation::Graded, 0.07},
    {"ripple", Triangulation::Uniform, 0.09},          {"ripple", Triangulation::Alternating, 0.16},
    {"ripple", Triangulation::Irregular, 0.12},        {"ripple", Triangulation::AnisoAlong, 0.11},
    {"ripple", Triangulation::AnisoAcross, 0.07},      {"ripple", Triangulation::Graded, 0.11},
    {"paraboloid", Triangulation::Irregular, 0.17},    {"paraboloid", Triangulation::Graded, 0.11},
    {"superquadric", Triangulation::AnisoAlong, 0.07}, {"superquadric", Triangulation::Graded, 0.07},
};

double offset_bound(const Case& c) {
  for (const KnownOffset& k : kKnownOffsets)
    if (c.surface == k.surface && c.triangulation == k.triangulation) return k.offset;
  return 0.05;
}

void check_targets(const std::vector<Case>& cases, const PipelineOptions& options) {
  for (const Case& c : cases) {
    SurfaceParams params;
    params.triangulation = c.triangulation;
    const Surface surface = make_surface(c.surface, params);
    const Score score = run_case(surface, c.noise, 101, options);
    INFO(c.surface << " (" << triangulation_name(c.triangulation) << "), noise " << c.noise << " h: ridge coverage "
                   << score.ridge.coverage << ", precision " << score.ridge.precision << ", fragments "
                   << score.ridge.fragments << "; valley coverage " << score.valley.coverage << ", precision "
                   << score.valley.precision << ", fragments " << score.valley.fragments);
    if (const KnownMiss* miss = known_miss(c)) {
      for (const TypeScore* t : {&score.ridge, &score.valley}) {
        CHECK(t->coverage >= miss->coverage);
        CHECK(t->precision >= miss->precision);
        CHECK(t->fragments <= miss->fragments);
      }
      CHECK(score.spurious_valleys() == 0);
    } else {
      CHECK(target_failures(score) == "");
    }
    if (c.noise == 0) {
      INFO("offset " << score.offset() << " mean edges");
      CHECK(score.offset() >= 0);
      CHECK(score.offset() <= offset_bound(c));
    }
  }
}

std::vector<Polyline> truth_as_lines(const Surface& s) {
  std::vector<Polyline> lines;
  for (const TrueCurve& c : s.curves) {
    Polyline l;
    l.type = c.type;
    l.points = c.points;
    l.curvature.assign(c.points.size(), 1.0);
    l.closed = c.closed;
    measure_polyline(l);
    lines.push_back(std::move(l));
  }
  return lines;
}

}  // namespace

TEST_CASE("the metrics score the truth itself as perfect, and nothing as nothing", "[quality]") {
  for (const std::string& name : surface_names()) {
    INFO(name);
    const Surface s = make_surface(name, {});
    const double h = mean_edge_length(repair_mesh(s.soup).mesh);
    const Score perfect = score_lines(s, truth_as_lines(s), h);
    for (const TypeScore* t : {&perfect.ridge, &perfect.valley}) {
      CHECK(t->coverage == Approx(1.0));
      CHECK(t->precision == Approx(1.0));
      if (t->true_curves > 0) CHECK(t->fragments <= 1.0);
    }
    CHECK(perfect.offset() < 1e-9);
    const Score empty = score_lines(s, {}, h);
    if (empty.ridge.true_curves > 0) CHECK(empty.ridge.coverage == 0);
    CHECK(empty.offset() == -1);
  }
  // The sine's true lines are level (constant z): lifted by 0.3 h they lie
  // exactly 0.3 mean edges from the truth.
  const Surface sine = make_surface("sine", {});
  const double h = mean_edge_length(repair_mesh(sine.soup).mesh);
  std::vector<Polyline> lifted = truth_as_lines(sine);
  for (Polyline& l : lifted)
    for (Vec3& q : l.points) q.z() += 0.3 * h;
  CHECK(score_lines(sine, lifted, h).offset() == Approx(0.3).epsilon(1e-6));
}

// Every scored surface, every meshing, every noise level of issues 9 and 13,
// with the defaults (automatic pre-smoothing, smoothing and threshold): 120
// runs, about 10 s (30 under the sanitizers: quality_case_runs).
TEST_CASE("defaults meet the targets on every surface, meshing and noise level but the known misses",
          "[quality][noise]") {
  std::vector<Case> cases;
  std::size_t index = 0;
  for (const std::string& name : surface_names()) {
    if (make_surface(name, {}).control) continue;
    for (Triangulation t : triangulations())
      for (double noise : {0.0, 0.1, 0.25, 0.5})
        if (quality_case_runs(index++, 4)) cases.push_back({name, t, noise});
  }
  REQUIRE(index == 120);
  check_targets(cases, {});
}

// The matrices above and in creases_quality_test.cpp under the sanitizers.
TEST_CASE("the sanitizers' subset runs every surface, meshing and noise level", "[quality]") {
  const char* set = std::getenv("CRESTLINE_QUALITY_SUBSET");
  const std::string before = set ? set : "";
  setenv("CRESTLINE_QUALITY_SUBSET", "1", 1);
  // 30 rows (5 surfaces × 6 meshings) of 4 noise levels: one level per row.
  std::vector<int> per_row(30), per_level(4);
  for (std::size_t i = 0; i < 120; ++i)
    if (quality_case_runs(i, 4)) ++per_row[i / 4], ++per_level[i % 4];
  if (set)
    setenv("CRESTLINE_QUALITY_SUBSET", before.c_str(), 1);
  else
    unsetenv("CRESTLINE_QUALITY_SUBSET");
  CHECK(per_row == std::vector<int>(30, 1));
  CHECK(per_level == std::vector<int>{8, 8, 7, 7});
  if (!set) CHECK(quality_case_runs(2, 4));
}

TEST_CASE("extremality smoothing makes noisy lines longer and cleaner", "[quality][noise]") {
  SurfaceParams params;
  const Surface surface = make_surface("sine", params);
  PipelineOptions smoothed, raw;
  raw.smoothing.steps = 0;
  const Score with = run_case(surface, 0.25, 101, smoothed), without = run_case(surface, 0.25, 101, raw);
  CHECK(with.ridge.precision > without.ridge.precision);
  CHECK(with.ridge.fragments < without.ridge.fragments);
  CHECK(with.valley.fragments < without.valley.fragments);
}

TEST_CASE("closed feature curves come out as closed lines", "[quality][polylines]") {
  // The ripple's ridge (r = 1) and inner valley (r = ½) about (1.6, 1.6) lie inside the patch.
  const Surface surface = make_surface("ripple", {});
  for (double noise : {0.0, 0.1, 0.25}) {
    Mesh mesh = repair_mesh(surface.soup).mesh;
    testing::add_normal_noise(mesh, noise * mean_edge_length(mesh), 101);
    Pipeline p(std::move(mesh));
    p.run();
    // One closed line of the right type along each of the two circles.
    const double h = p.stats().mean_edge_length;
    auto closed_along = [&](LineType type, double radius) {
      int n = 0;
      for (const Polyline& l : p.lines()) {
        bool along = l.closed && l.type == type;
        for (const Vec3& q : l.points) along = along && std::abs(std::hypot(q.x() - 1.6, q.y() - 1.6) - radius) < 2 * h;
        n += along;
      }
      return n;
    };
    INFO("noise " << noise);
    CHECK(closed_along(LineType::Ridge, 1.0) == 1);
    CHECK(closed_along(LineType::Valley, 0.5) == 1);
  }
}
