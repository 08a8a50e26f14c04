// Issue 16's crease targets on the CAD-like surfaces (cad_surfaces.h), and no
// creases on the smooth surfaces of the ridge/valley harness.
// crestline_crease_report prints every case.
#include <catch2/catch.hpp>

#include "analytic_meshes.h"
#include "cad_surfaces.h"
#include "crestline/lines/creases.h"
#include "crestline/mesh/repair.h"
#include "quality_metrics.h"

using namespace crestline;
using namespace crestline::quality;

namespace {

CreaseScore run_crease_case(const std::string& name, Triangulation t, double noise) {
  CadParams p;
  p.triangulation = t;
  const CadSurface surface = make_cad_surface(name, p);
  Mesh mesh = repair_mesh(surface.soup).mesh;
  const double h = mean_edge_length(mesh);
  testing::add_normal_noise(mesh, noise * h, 101);
  const Topology topology = build_topology(mesh);
  const CreaseAngles angles = measure_crease_angles(mesh, topology, {});
  return score_creases(surface, select_creases(mesh, topology, angles, {}, h).lines, h);
}

}  // namespace

TEST_CASE("the crease metrics score the truth itself as perfect", "[quality][creases]") {
  for (const std::string& name : cad_surface_names()) {
    INFO(name);
    const CadSurface s = make_cad_surface(name, {});
    std::vector<Polyline> truth;
    for (const SharpEdge& e : s.edges) {
      Polyline l;
      l.type = LineType::Crease;
      l.points = e.points;
      l.closed = e.closed;
      l.convex = e.convex;
      truth.push_back(l);
    }
    const CreaseScore score = score_creases(s, truth, 0.05);
    CHECK(score.coverage == Approx(1.0));
    CHECK(score.precision == Approx(1.0));
    CHECK(score.fragments == Approx(1.0));
    CHECK(score.wrong_sign == 0);
    CHECK(score_creases(s, {}, 0.05).coverage == 0);
  }
}

// Measured (crestline_crease_report, seed 1): at σ = 0 every case is exact;
// at σ = 0.1 coverage ≥ 0.969, precision 1.000, fragments ≤ 1.67, every
// sign right; at σ = 0.25
// precision ≥ 0.99 but coverage falls to 0.40–0.96: the 45° chamfer and the
// 62° concave edge are lost in the noise (see README).
TEST_CASE("creases of the CAD-like surfaces: targets at σ = 0, measured limits at σ = 0.1", "[quality][creases]") {
  for (const std::string& name : cad_surface_names())
    for (Triangulation t : {Triangulation::Uniform, Triangulation::Alternating, Triangulation::Irregular})
      for (double noise : {0.0, 0.1}) {
        const CreaseScore s = run_crease_case(name, t, noise);
        INFO(name << " (" << triangulation_name(t) << "), noise " << noise << ": coverage " << s.coverage
                  << ", precision " << s.precision << ", fragments " << s.fragments << ", wrong sign " << s.wrong_sign);
        if (noise == 0) {
          CHECK(crease_target_failures(s) == "");
          CHECK(s.fragments == 1.0);
        } else {
          CHECK(s.coverage >= 0.95);
          CHECK(s.precision >= 0.95);
          CHECK(s.fragments <= 1.7);
          CHECK(s.wrong_sign == 0);
        }
      }
}

TEST_CASE("creases at σ = 0.25: what is found is right", "[quality][creases]") {
  for (const std::string& name : cad_surface_names()) {
    const CreaseScore s = run_crease_case(name, Triangulation::Irregular, 0.25);
    INFO(name << ": coverage " << s.coverage << ", precision " << s.precision);
    CHECK(s.precision >= 0.95);
    if (name == "filleted-box") CHECK(s.coverage >= 0.94);  // its creases are 90°
  }
}

TEST_CASE("the smooth surfaces of the ridge/valley harness have no creases", "[quality][creases]") {
  for (const std::string& name : surface_names())
    for (Triangulation t : {Triangulation::Uniform, Triangulation::Alternating, Triangulation::Irregular})
      for (double noise : {0.0, 0.1, 0.25}) {
        SurfaceParams p;
        p.triangulation = t;
        double h = 0;
        const Mesh mesh = noisy_mesh(make_surface(name, p), noise, 101, h);
        const Topology topology = build_topology(mesh);
        const CreaseAngles angles = measure_crease_angles(mesh, topology, {});
        INFO(name << " (" << triangulation_name(t) << "), noise " << noise);
        CHECK(select_creases(mesh, topology, angles, {}, h).lines.empty());
      }
}
