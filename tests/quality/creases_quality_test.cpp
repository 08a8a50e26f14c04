// Issue 16's crease targets on the CAD-like surfaces (cad_surfaces.h), and no
// creases on the smooth surfaces of the ridge/valley harness.
// crestline_crease_report prints every case.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "analytic_meshes.h"
#include "cad_surfaces.h"
#include "crestline/lines/creases.h"
#include "quality_metrics.h"

using namespace crestline;
using namespace crestline::quality;

namespace {

CreaseScore run_crease_case(const std::string& name, Triangulation t, double noise) {
  const CadCase c = make_cad_case(name, t, noise, 101);
  return score_creases(c.surface, find_creases(c.mesh, build_topology(c.mesh), {}, c.h).lines, c.h);
}

}  // namespace

TEST_CASE("the crease metrics score the truth itself as perfect", "[quality][creases]") {
  for (const std::string& name : cad_surface_names()) {
    INFO(name);
    const CadSurface s = make_cad_surface(name, {});
    const std::vector<Polyline> truth = sharp_edges_as_lines(s);
    const CreaseScore score = score_creases(s, truth, 0.05);
    CHECK(score.coverage == Approx(1.0));
    CHECK(score.precision == Approx(1.0));
    CHECK(score.fragments == Approx(1.0));
    CHECK(score.wrong_sign == 0);
    CHECK(score_creases(s, {}, 0.05).coverage == 0);
  }
}

// Measured (crestline_crease_report, seeds 1–3): at σ = 0 and σ = 0.1 every
// case meets issue 16's targets (at σ = 0.1 since gaps are bridged, 20 of 27
// before); at σ = 0.25 precision ≥ 0.95 but coverage 0.66–1.0 and up to 2.7
// lines per edge: the 45° chamfer is lost in the noise (see README).
TEST_CASE("creases of the CAD-like surfaces: targets at σ = 0 and 0.1", "[quality][creases]") {
  for (const std::string& name : cad_surface_names())
    for (Triangulation t : {Triangulation::Uniform, Triangulation::Alternating, Triangulation::Irregular})
      for (double noise : {0.0, 0.1}) {
        const CreaseScore s = run_crease_case(name, t, noise);
        INFO(name << " (" << triangulation_name(t) << "), noise " << noise << ": coverage " << s.coverage
                  << ", precision " << s.precision << ", fragments " << s.fragments << ", wrong sign " << s.wrong_sign);
        CHECK(crease_target_failures(s) == "");
        if (noise == 0) CHECK(s.fragments == 1.0);
      }
}

// At σ = 0.25 the targets hold in most cases; asserted over the 27 cases of
// crestline_crease_report --seeds 3 (seeds 1–3, three mesh kinds), one case
// alone varies too much. Regression guards at the values measured
// (creases.cpp): 4 cases met every target before redundant chains were
// dropped, 7 after, 12 once bridge walks took their direction over their
// last 3 edges, 13 once they stepped over strong edges outside their cone,
// 24 (spurs dropped before shortcuts, half-bridges, the end direction
// in the surface, bridging again after the spur rounds), 26 (long weak
// runs whose mean holds: the chamfer's last gaps on the checker meshes), 27
// now (sign blips flipped: a notch edge beside the re-entrant corner);
// coverage mean 0.902 → 0.901 → 0.954 → 0.969 → 0.995 → 0.997 → 0.999, min
// 0.684 → 0.684 → 0.789 → 0.846 → 0.967 (the 45° chamfer) → 0.979 → 0.992;
// precision min 0.983 →
// 0.987 → 0.963 (the walks now also join false pieces on a fillet of the
// box, seed 3); lines per true edge mean 1.39 → 1.21 → 1.08 → 1.06 → 1.01,
// max 2.25 → 2.00 → 1.33 → 1.33 → 1.17.
TEST_CASE("creases at σ = 0.25: what is found is right", "[quality][creases]") {
  int cases = 0, met = 0;
  double coverage_sum = 0, coverage_min = 1, fragments_sum = 0, fragments_max = 0;
  for (unsigned seed = 1; seed <= 3; ++seed)
    for (const std::string& name : cad_surface_names())
      for (Triangulation t : {Triangulation::Uniform, Triangulation::Alternating, Triangulation::Irregular}) {
        CadParams params;
        params.seed = seed;
        const CadCase c = make_cad_case(name, t, 0.25, 100 + seed, params);
        const CreaseScore s =
            score_creases(c.surface, find_creases(c.mesh, build_topology(c.mesh), {}, c.h).lines, c.h);
        INFO(name << " (" << triangulation_name(t) << "), seed " << seed << ": coverage " << s.coverage
                  << ", precision " << s.precision << ", fragments " << s.fragments);
        CHECK(s.precision >= 0.96);
        CHECK(s.wrong_sign == 0);
        if (name == "filleted-box") CHECK(s.coverage >= 0.99);  // its creases are 90°
        ++cases;
        met += crease_target_failures(s).empty();
        coverage_sum += s.coverage, coverage_min = std::min(coverage_min, s.coverage);
        fragments_sum += s.fragments, fragments_max = std::max(fragments_max, s.fragments);
      }
  INFO(met << " of " << cases << " met; coverage mean " << coverage_sum / cases << ", min " << coverage_min
           << "; fragments mean " << fragments_sum / cases << ", max " << fragments_max);
  CHECK(cases == 27);
  CHECK(met == 27);
  CHECK(coverage_sum / cases >= 0.999);
  CHECK(coverage_min >= 0.99);
  CHECK(fragments_sum / cases <= 1.015);
  CHECK(fragments_max <= 1.18);
}

// Every mesh kind up to σ = 0.25 (at 0.25 the anisotropic meshes had 9 false
// crease lines in 4 cases before the 3-ring support and its non-maximum
// suppression, creases.cpp). At 0.5: 9 lines in the 36 cases (140 before
// it, 11 before redundant chains were dropped).
TEST_CASE("the smooth surfaces of the ridge/valley harness have no creases", "[quality][creases]") {
  std::size_t index = 0;
  for (const std::string& name : surface_names())
    for (Triangulation t : triangulations())
      for (double noise : {0.0, 0.1, 0.25}) {
        if (!quality_case_runs(index++, 3)) continue;
        INFO(name << " (" << triangulation_name(t) << "), noise " << noise);
        CHECK(smooth_surface_creases(name, t, noise).lines.empty());
      }
}

// Issue 16: the smooth lines respect the creases. Without crease boundaries
// the ridges and valleys run along the sharp edges (measured, irregular
// walls: 83–116 mean edges of line within 1 edge of a sharp edge at σ = 0,
// 120–363 at σ = 0.1, 125–369 at σ = 0.25); with them (--crease-boundaries)
// none at σ = 0 and 0.1 (0–8.5 at σ = 0.1 before gaps in the 45° chamfer's
// creases were bridged). At σ = 0.25 (noise level 0.211–0.222) boundaries
// are on since kBoundaryNoiseLimit is 0.225 (0.15 before, so these meshes
// kept their 125–369 h beside the edges), and none either since the creases'
// gaps close (creases.cpp: half-bridges, bridging after the spur rounds);
// before, 41.4 h of the cylinder's and 5.9 h of the prism's lines ran in
// those gaps (chamfer coverage 0.85).
TEST_CASE("smooth lines keep off the sharp edges with crease boundaries", "[quality][creases]") {
  for (const std::string& name : cad_surface_names())
    for (double noise : {0.0, 0.1, 0.25}) {
      const CadCase c = make_cad_case(name, Triangulation::Irregular, noise, 101);
      const std::vector<Polyline> sharp = sharp_edges_as_lines(c.surface);
      PipelineOptions off;
      off.creases.boundaries = false;
      const SmoothNearCreases without = smooth_lines_near(sharp, run_cad_pipeline(c, off).lines(), c.h);
      PipelineOptions on;
      on.creases.boundaries = true;
      const std::vector<Polyline> lines_with = run_cad_pipeline(c, on).lines();
      const SmoothNearCreases with = smooth_lines_near(sharp, lines_with, c.h);
      // Issue 16 asks for no smooth line within 2 edges of a crease. Within
      // 2 h, before the lines were cut back to 2 h from the creases found
      // (ClearanceOptions): the fillets' ridges ended 1–2 h from the box's
      // sharp edges (0.9 h of 29), weak lines on the cylinder's wall where the
      // tracer's band of 2 rings ends, 1.74 h from its creases (2.5 and 5.1 h
      // of 165 and 162; 4.4 of 155 at σ = 0.25), none on the prism. Since:
      // 0–0.5 h (the found creases lie up to a noise amplitude off the true
      // edges, and fairing moves inner points up to 0.25 h).
      const SmoothNearCreases with2 = smooth_lines_near(sharp, lines_with, c.h, 2.0);
      INFO(name << ", noise " << noise << ": within 1 h of a sharp edge " << without.near_length << " h of "
                << without.length << " without boundaries, " << with.near_length << " h of " << with.length
                << " with them, " << with2.near_length << " h within 2 h");
      if (noise == 0.25) CHECK(without.near_length > 100);
      CHECK(without.near_length > 5);
      CHECK(with.near_length < 0.5);
      CHECK(with2.near_length < 1.0);
    }
}

// The same over the noisiest cases, with the Pipeline's own creases (in its
// working frame, so they differ a little from find_creases'): ridges and
// valleys within 1 h of a sharp edge, with crease boundaries, at σ = 0.25,
// seeds 1–3, the cylinder and the prism on the three mesh kinds (the box had
// none). They lie where the creases have gaps (crestline_crease_report's
// last columns). Measured (creases.cpp): the cylinder 37.7 h in all (8.0,
// 5.5 and 24.2 h in three cases, the chamfer's gaps) before weak runs whose
// mean holds closed those gaps (kLongWeakSpan), none since; the prism 34.3 h
// both, 19.4 h at most (seed 2, uniform mesh: a notch edge lost whole, its
// doubled trace cut by the shortcut rule into pieces the spur rule drops),
// 1.5 h since sign blips flip and shortcuts keep both ends on very noisy
// surfaces (creases.cpp; the 1.5 h, seed 2, uniform mesh, was the end of a
// ridge that ran 1.2–2 h above the bottom edge of the notch's opposite wall,
// whose crease was traced two rows inside the cap), none since splices
// (creases.cpp, kSpliceShare). Within 2 h: the prism 24.1 h (that ridge)
// before splices, none since; the cylinder's wall lines ended there (3.7–4.6 h
// per case, crossing at right angles) until they were cut back to 2 h from
// the creases found (ClearanceOptions): 0–0.3 h per case, 1.1 h in all.
TEST_CASE("smooth lines keep off the sharp edges at σ = 0.25 over seeds 1–3", "[quality][creases]") {
  double total = 0, prism_within_2 = 0, within_2 = 0;
  for (const std::string& name : {std::string("chamfered-cylinder"), std::string("notched-prism")})
    for (unsigned seed = 1; seed <= 3; ++seed)
      for (Triangulation t : {Triangulation::Uniform, Triangulation::Alternating, Triangulation::Irregular}) {
        CadParams params;
        params.seed = seed;
        const CadCase c = make_cad_case(name, t, 0.25, 100 + seed, params);
        const std::vector<Polyline> sharp = sharp_edges_as_lines(c.surface), lines = run_cad_pipeline(c, {}).lines();
        const SmoothNearCreases near = smooth_lines_near(sharp, lines, c.h);
        const SmoothNearCreases near2 = smooth_lines_near(sharp, lines, c.h, 2.0);
        INFO(name << " (" << triangulation_name(t) << "), seed " << seed << ": " << near.near_length << " h of "
                  << near.length << " within 1 h of a sharp edge, " << near2.near_length << " h within 2 h");
        CHECK(near.near_length < 0.5);
        CHECK(near2.near_length < 1.0);
        if (name == "notched-prism") prism_within_2 += near2.near_length;
        total += near.near_length, within_2 += near2.near_length;
      }
  INFO("in all " << total << " h within 1 h, " << within_2 << " h within 2 h (the prism " << prism_within_2 << ")");
  CHECK(total < 0.5);
  CHECK(within_2 < 2.0);
  CHECK(prism_within_2 < 0.5);
}

// The cut itself (ClearanceOptions): every ridge and valley point is at least
// the clearance, in edge lengths at the crease (the mean edge at its two
// ends, at most the mean edge h), from the creases the Pipeline cut along; ends that were cut exactly
// at it (fairing keeps ends; inner points move up to its bound, in mean
// edges). Without it the cylinder's wall lines end 1.74 h from its creases,
// where the tracer's band of 2 rings ends (its rows are 0.87 h apart).
TEST_CASE("smooth lines stop the clearance away from the creases they were cut along", "[quality][creases]") {
  for (const std::string& name : cad_surface_names())
    for (double noise : {0.0, 0.1, 0.25})
      for (double clearance : {0.0, 2.0, 3.0}) {
        const CadCase c = make_cad_case(name, Triangulation::Irregular, noise, 101);
        PipelineOptions options;
        options.clearance.distance = clearance;
        const Pipeline pipeline = run_cad_pipeline(c, options);
        REQUIRE(pipeline.frames().count() == 1);
        const double h = pipeline.frames().scale[0];
        const Mesh& mesh = pipeline.input_mesh();
        const Topology& topology = pipeline.topology();
        const std::vector<uint32_t>& creases = pipeline.boundary_creases();
        REQUIRE_FALSE(creases.empty());
        std::vector<double> star_sum(mesh.positions.size()), star_count(mesh.positions.size());
        for (const auto& [a, b] : topology.edges) {
          const double length = (mesh.positions[b] - mesh.positions[a]).norm();
          star_sum[a] += length, star_sum[b] += length, ++star_count[a], ++star_count[b];
        }
        // Distance in edge lengths at the crease, least over the creases.
        auto clearance_at = [&](const Vec3& p) {
          double least = INFINITY;
          for (uint32_t e : creases) {
            const auto [i, j] = topology.edges[e];
            const Vec3 &a = mesh.positions[i], &b = mesh.positions[j];
            const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
            const double edge = std::min(h, (star_sum[i] + star_sum[j]) / (star_count[i] + star_count[j]));
            least = std::min(least, (a + t * (b - a) - p).norm() / edge);
          }
          return least;
        };
        double nearest_end = INFINITY, nearest = INFINITY, edge_min = INFINITY, edge_max = 0;
        for (uint32_t e : creases) {
          const auto [i, j] = topology.edges[e];
          const double edge = std::min(h, (star_sum[i] + star_sum[j]) / (star_count[i] + star_count[j])) / h;
          edge_min = std::min(edge_min, edge), edge_max = std::max(edge_max, edge);
        }
        for (const Polyline& line : pipeline.lines())
          for (size_t i = 0; i < line.points.size(); ++i) {
            const double d = clearance_at(line.points[i]);
            nearest = std::min(nearest, d);
            if (!line.closed && (i == 0 || i + 1 == line.points.size())) nearest_end = std::min(nearest_end, d);
          }
        INFO(name << ", noise " << noise << ", clearance " << clearance << ": nearest end " << nearest_end
                  << " edges, nearest point " << nearest << " edges; edges at the creases " << edge_min << "–"
                  << edge_max << " h");
        // The harness's meshes are even: their edges at a crease are about h
        // (at most h: the Pipeline caps them there).
        CHECK(edge_min > 0.7);
        if (clearance > 0) {
          CHECK(nearest_end >= clearance * (1 - 1e-9));
          CHECK(nearest >= clearance - options.fairing.hausdorff_bound / edge_min);
        } else if (name == "chamfered-cylinder") {
          CHECK(nearest_end < 1.9);
        }
      }
}
