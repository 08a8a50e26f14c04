#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "crestline/io/read_mesh.h"
#include "quality_metrics.h"
#include "run_pipeline.h"
#include "test_meshes.h"

using namespace crestline;

namespace {

std::vector<std::string> obj_files(const char* folder) {
  std::vector<std::string> out;
  const auto dir = testing::meshes_dir() / folder;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".obj") out.push_back(std::string(folder) + "/" + entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

bool finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// Every traced node lies on its mesh edge (or inside its trisector triangle),
// both in the working frame.
void check_on_surface(const Pipeline& p, const FeatureGraph& g, double tolerance) {
  const Mesh& m = p.working_surface();
  for (size_t i = 0; i < g.points.size(); ++i) {
    const Vec3& q = g.points[i];
    REQUIRE(q.allFinite());
    if (g.trisector[i]) {
      const Triangle& t = m.triangles[g.source[i]];
      CHECK((q - (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3).norm() < tolerance);
      continue;
    }
    const auto& e = p.working_topology().edges[g.source[i]];
    const Vec3 a = m.positions[e[0]], b = m.positions[e[1]];
    const double t = (q - a).dot(b - a) / (b - a).squaredNorm();
    CHECK(t >= -1e-9);
    CHECK(t <= 1 + 1e-9);
    CHECK((a + t * (b - a) - q).norm() < tolerance);
  }
}

}  // namespace

TEST_CASE("invariants over every real mesh", "[real]") {
  SKIP_WITHOUT_MESHES();
  std::vector<std::string> files;
  for (const char* folder : {"classic", "cad", "smooth"}) {
    const auto more = obj_files(folder);
    files.insert(files.end(), more.begin(), more.end());
  }
  REQUIRE(files.size() > 10);
  for (size_t i = 0; i < files.size(); ++i) {
    // Under the sanitizers (CRESTLINE_QUALITY_SUBSET) every other file: 121 s of ASan's 510.
    if (!quality::quality_case_runs(i, 2)) continue;
    const std::string& name = files[i];
    INFO("mesh " << name);
    TriangleSoup soup;
    try {
      soup = io::read_mesh(testing::mesh_path(name));
    } catch (const std::exception& e) {
      FAIL("reading failed: " << e.what());
    }
    Pipeline p = testing::run_pipeline(soup);
    const Curvature& c = p.curvature();
    CHECK(finite(c.kappa_max));
    CHECK(finite(c.kappa_min));
    CHECK(finite(p.extremality().e_max));
    CHECK(finite(p.extremality().e_min));
    // Lengths in the working frame are in mean edges.
    check_on_surface(p, p.segments().lines.ridges, 1e-9);
    check_on_surface(p, p.segments().lines.valleys, 1e-9);

    // Well-formed polylines, and fairing moves no point farther than its bound.
    const std::vector<Polyline> faired = p.all_lines();
    for (const Polyline& l : faired) {
      CHECK(l.points.size() >= (l.closed ? 3u : 2u));
      CHECK(l.points.size() == l.curvature.size());
      CHECK(std::isfinite(l.strength));
      CHECK(l.strength >= 0);
    }
    PipelineOptions o = p.options();
    // Each component is faired in its own mean edge length: bound by the largest.
    const std::vector<double>& scales = p.frames().scale;
    const double bound = o.fairing.hausdorff_bound * *std::max_element(scales.begin(), scales.end());
    o.fairing.hausdorff_bound = 0;
    p.set_options(o);
    p.run();
    const std::vector<Polyline>& raw = p.all_lines();
    REQUIRE(raw.size() == faired.size());
    double worst = 0;
    for (size_t i = 0; i < raw.size(); ++i)
      for (size_t k = 0; k < raw[i].points.size(); ++k)
        worst = std::max(worst, (raw[i].points[k] - faired[i].points[k]).norm());
    CHECK(worst <= bound * (1 + 1e-9));
  }
}

// Paper Table 2: frequency of singular triangles (we count them for the
// κ_max direction field; the κ_min field differs by a few triangles).
TEST_CASE("singular triangle frequency matches the paper's Table 2", "[real][table2]") {
  SKIP_WITHOUT_MESHES();
  auto frequency = [](const std::string& name, int presmooth_steps) {
    PipelineOptions o;
    o.presmooth.steps = presmooth_steps;
    const Pipeline p = testing::run_pipeline(io::read_mesh(testing::mesh_path(name)), o);
    const double f = 100.0 * p.stats().singular_max / p.stats().triangles;
    WARN(name << " presmooth " << presmooth_steps << ": " << f << " % singular triangles");
    return f;
  };
  // mannequin: paper 2.73 %, the same file (23,402 triangles); we measure 2.6 %.
  const double mannequin = frequency("classic/mannequin.obj", 0);
  CHECK(mannequin > 2.2);
  CHECK(mannequin < 3.2);
  // bunny: paper 10.49 % on 69,473 triangles; ours has 69,451 (bun_zipper)
  // and measures 10.5 %. One implicit pre-smoothing step (time step 1 mean
  // edge²) brings it to 2.5 %, two to 1.1 %: the paper's 1.56 % lies between,
  // its pre-smoothing strength is not given.
  const double bunny = frequency("classic/stanford-bunny.obj", 0);
  CHECK(bunny > 9.5);
  CHECK(bunny < 11.5);
  const double bunny_smooth = frequency("classic/stanford-bunny.obj", 1);
  CHECK(bunny_smooth < 3.0);
  CHECK(frequency("classic/stanford-bunny.obj", 2) < bunny_smooth);
  // feline: paper 2.82 %, same triangle count; we measure 4.8 % (and 1.5 %
  // after one pre-smoothing step). README, Table 2 paragraph, lists what was
  // measured and ruled out; recorded as a regression.
  const double feline = frequency("classic/feline.obj", 0);
  CHECK(feline > 4.3);
  CHECK(feline < 5.3);
}

TEST_CASE("featureless real meshes draw no lines", "[real]") {
  SKIP_WITHOUT_MESHES();
  // An icosphere stored with float coordinates: umbilic everywhere.
  const Pipeline p = testing::run_pipeline(io::read_mesh(testing::mesh_path("smooth/sphere.obj")));
  CHECK(p.lines().empty());
}
