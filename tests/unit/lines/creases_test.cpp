// The crease stage (lines/creases.h) on meshes whose sharp edges are known:
// a cube tessellated face by face, its mirror image (every edge concave) and
// a sphere (none).
#include "crestline/lines/creases.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>
#include <random>

#include "../mesh/on_threads.h"
#include "../mesh/same_topology.h"
#include "analytic_meshes.h"
#include "crestline/mesh/cut.h"
#include "crestline/mesh/presmooth.h"
#include "crestline/mesh/repair.h"
#include "crestline/pipeline.h"

using namespace crestline;

namespace {

// The cube [−1, 1]³, each face an n × n grid, outward.
TriangleSoup cube(int n) {
  TriangleSoup soup;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      testing::GridOptions grid;
      grid.nu = grid.nv = n;
      const TriangleSoup face = testing::parametric_grid(
          [&](double a, double b) {
            Vec3 p;
            p[axis] = side;
            // Swap the parameters on the negative side so that the normal points outwards.
            p[u] = side > 0 ? 2 * a - 1 : 2 * b - 1;
            p[v] = side > 0 ? 2 * b - 1 : 2 * a - 1;
            return p;
          },
          grid);
      const uint32_t base = static_cast<uint32_t>(soup.vertex_count());
      soup.positions.insert(soup.positions.end(), face.positions.begin(), face.positions.end());
      for (uint32_t i : face.indices) soup.indices.push_back(base + i);
    }
  return soup;
}

struct Run {
  Mesh mesh;
  Topology topology;
  CreaseAngles angles;
};

// filter_steps < 0: automatic. The coarse cubes below measure as noisy
// (their creases span most vertex rings), so the exact tests ask for raw normals.
Run measure(Mesh mesh, int filter_steps = 0) {
  Run r{std::move(mesh), {}, {}};
  r.topology = build_topology(r.mesh);
  r.angles = measure_crease_angles(r.mesh, r.topology, {filter_steps});
  return r;
}

}  // namespace

TEST_CASE("a cube's twelve edges are twelve convex creases of 90°, split at its corners", "[creases]") {
  const Run r = measure(repair_mesh(cube(6)).mesh);
  int sharp = 0;
  for (double a : r.angles.angle) {
    if (std::abs(a) < 1e-9) continue;
    ++sharp;
    CHECK(a == Approx(testing::kPi / 2).epsilon(1e-12));  // convex: positive
  }
  CHECK(sharp == 12 * 6);  // 6 mesh edges along each cube edge
  CHECK(r.angles.median == Approx(0).margin(1e-9));
  // Two of a face's three edges run along the axes (2/6 long), one diagonally.
  CHECK(r.angles.median_edge_length == Approx(2.0 / 6));

  const double h = mean_edge_length(r.mesh);
  const CreaseResult creases = select_creases(r.mesh, r.topology, r.angles, {}, h);
  CHECK(creases.angle == kDefaultCreaseAngle);
  REQUIRE(creases.lines.size() == 12);
  for (const Polyline& l : creases.lines) {
    CHECK(l.type == LineType::Crease);
    CHECK(l.convex);
    CHECK_FALSE(l.closed);
    CHECK(l.points.size() == 7);
    CHECK(l.length == Approx(2.0));
    // strength = ∑ |angle|·length / h
    CHECK(l.strength == Approx(testing::kPi / 2 * 2.0 / h).epsilon(1e-6));
  }
  CHECK(creases.edges.size() == 72);
}

TEST_CASE("low-poly solids get every edge as a crease: a piecewise-planar mesh keeps the default angle",
          "[creases][pipeline]") {
  // Half of a 12-triangle box's edges turn by 90°: 12× the median dihedral
  // capped the automatic angle at 180°, and each edge, one mesh edge from
  // corner to corner, was dropped as a shortcut across a corner.
  Pipeline box(repair_mesh(cube(1)).mesh);
  box.run();
  CHECK(box.stats().noise_level == 0);
  CHECK(box.stats().crease_angle == kDefaultCreaseAngle);
  CHECK(box.stats().creases == 12);
  CHECK(box.stats().crease_length == Approx(24.0));
  for (const Polyline& l : box.creases()) CHECK(l.points.size() == 2);
  // Nor do its corners make ridges any more.
  CHECK(box.stats().ridges == 0);
  CHECK(box.stats().valleys == 0);

  // The icosahedron's edges turn by 41.8°.
  Pipeline icosahedron(repair_mesh(testing::icosphere(0)).mesh);
  icosahedron.run();
  CHECK(icosahedron.stats().noise_level < 1e-6);
  CHECK(icosahedron.stats().crease_angle == kDefaultCreaseAngle);
  CHECK(icosahedron.stats().creases == 30);
  CHECK(icosahedron.stats().crease_length == Approx(30 * 4 / std::sqrt(10 + 2 * std::sqrt(5.0))).epsilon(1e-9));

  // Subdivided once and projected it is a coarse sphere, no longer planar:
  // its edges turn by ~20° everywhere and the median rule keeps them.
  Pipeline sphere(repair_mesh(testing::icosphere(1)).mesh);
  sphere.run();
  CHECK(sphere.stats().noise_level > 1e-3);
  CHECK(sphere.stats().crease_angle > 90);
  CHECK(sphere.stats().creases == 0);
}

TEST_CASE("re-thresholding the crease angle is a selection over the measured angles", "[creases]") {
  const Run r = measure(repair_mesh(cube(4)).mesh);
  const double h = mean_edge_length(r.mesh);
  CreaseOptions options;
  options.angle = 89;
  CHECK(select_creases(r.mesh, r.topology, r.angles, options, h).lines.size() == 12);
  options.angle = 91;
  CHECK(select_creases(r.mesh, r.topology, r.angles, options, h).lines.empty());
}

TEST_CASE("a cube turned inside out has concave creases", "[creases]") {
  Mesh mesh = repair_mesh(cube(4)).mesh;
  for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
  const Run r = measure(std::move(mesh));
  const CreaseResult creases = select_creases(r.mesh, r.topology, r.angles, {}, mean_edge_length(r.mesh));
  REQUIRE(creases.lines.size() == 12);
  for (const Polyline& l : creases.lines) CHECK_FALSE(l.convex);
  for (double a : r.angles.angle) CHECK(a <= 1e-9);
}

TEST_CASE("a chain turning sharper than the limit is split there", "[creases]") {
  // Only the cube's top outline: four edges of 90° meeting at degree-2
  // corners where the chain turns by 90°.
  const Run r = measure(repair_mesh(cube(4)).mesh);
  CreaseAngles top = r.angles;
  for (size_t e = 0; e < top.angle.size(); ++e) {
    const Vec3& a = r.mesh.positions[r.topology.edges[e][0]];
    const Vec3& b = r.mesh.positions[r.topology.edges[e][1]];
    if (!(a.z() > 0.99 && b.z() > 0.99)) top.angle[e] = top.support[e] = 0;
  }
  const double h = mean_edge_length(r.mesh);
  CreaseOptions options;
  const CreaseResult split = select_creases(r.mesh, r.topology, top, options, h);
  CHECK(split.lines.size() == 4);  // 90° turns at the four corners
  options.max_turn = 100;
  const CreaseResult loop = select_creases(r.mesh, r.topology, top, options, h);
  REQUIRE(loop.lines.size() == 1);
  CHECK(loop.lines[0].closed);
  CHECK(loop.lines[0].length == Approx(8.0));
}

TEST_CASE("under noise the filtered normals keep a cube's creases, one line each", "[creases]") {
  Mesh mesh = repair_mesh(cube(24)).mesh;
  const double h = mean_edge_length(mesh);
  testing::add_normal_noise(mesh, 0.1 * h, 7);
  const Run raw = measure(mesh, 0), filtered = measure(mesh, -1);
  CHECK(filtered.angles.normal_filter_steps > 0);
  CreaseOptions at35;
  at35.angle = 35;
  const CreaseResult from_raw = select_creases(raw.mesh, raw.topology, raw.angles, at35, h);
  const CreaseResult from_filtered = select_creases(filtered.mesh, filtered.topology, filtered.angles, {}, h);
  // All of the twelve edges, in about twelve lines: under noise a corner may
  // join two edges into one line or cut a piece off (tests/quality scores this).
  double length = 0;
  for (const Polyline& l : from_filtered.lines) length += l.length;
  CHECK(length == Approx(24.0).epsilon(0.05));
  CHECK(from_filtered.lines.size() >= 11);
  CHECK(from_filtered.lines.size() <= 13);
  // A single-edge test on the raw normals flickers: edges off the cube's
  // edges reach 35°; after filtering none does.
  auto flat_over_35 = [&](const Run& r) {
    int n = 0;
    for (size_t e = 0; e < r.angles.angle.size(); ++e) {
      const Vec3 mid = 0.5 * (r.mesh.positions[r.topology.edges[e][0]] + r.mesh.positions[r.topology.edges[e][1]]);
      int on_faces = 0;  // coordinates within 2 edges of ±1
      for (int k = 0; k < 3; ++k) on_faces += std::abs(std::abs(mid[k]) - 1) < 2 * h;
      n += on_faces < 2 && std::abs(r.angles.angle[e]) >= 35 * testing::kPi / 180;
    }
    return n;
  };
  CHECK(flat_over_35(raw) > 0);
  CHECK(flat_over_35(filtered) == 0);
  CHECK(from_raw.lines.size() >= 12);
  // And the automatic angle, from the raw normals' median, rises above 90°.
  CHECK(automatic_crease_angle(raw.angles) > 90);
}

TEST_CASE("the crease angles, supports, medians and selection are the same on 1, 2 and 3 threads",
          "[creases][threads]") {
  // 6 × 2 × 40² triangles: the edge loop splits over the threads. Raw normals
  // with a 1-ring support, filtered ones with the wider rings, and a very
  // noisy cube whose supports are suppressed off their local maxima.
  Mesh mesh = repair_mesh(cube(40)).mesh;
  const double h = mean_edge_length(mesh);
  for (double noise : {0.0, 0.1, 0.6}) {
    Mesh noisy = mesh;
    testing::add_normal_noise(noisy, noise * h, 11);
    const Topology topology = build_topology(noisy);
    const auto angles = [&](int threads) {
      return testing::on_threads(threads, [&] { return measure_crease_angles(noisy, topology, {-1}); });
    };
    const CreaseAngles one = angles(1);
    INFO("noise " << noise << ", filter steps " << one.normal_filter_steps);
    if (noise > 0) CHECK(one.normal_filter_steps > 0);
    size_t supported = 0;
    for (double s : one.support) supported += s > 0;
    CHECK(supported >= 10 * 40);  // most of the cube's 12 × 40 edges
    if (noise > 0.5) CHECK(one.noise_level > kVeryNoisyCreaseLevel);
    for (int threads : {2, 3}) {
      const CreaseAngles many = angles(threads);
      CHECK(many.angle == one.angle);
      CHECK(many.support == one.support);
      CHECK(many.median == one.median);
      CHECK(many.median_edge_length == one.median_edge_length);
      CHECK(many.noise_level == one.noise_level);
      // The selection's first pass over the edges splits over the threads too.
      const auto select = [&](int n) {
        return testing::on_threads(n, [&] { return select_creases(noisy, topology, one, {}, h); });
      };
      const CreaseResult selected = select(1), selected_many = select(threads);
      CHECK(selected_many.edges == selected.edges);
      CHECK(selected_many.lines.size() == selected.lines.size());
    }
  }
}

TEST_CASE("a sphere has no creases, also under noise", "[creases]") {
  for (double noise : {0.0, 0.1}) {
    Mesh mesh = repair_mesh(testing::icosphere(4)).mesh;
    testing::add_normal_noise(mesh, noise * mean_edge_length(mesh), 7);
    const Run r = measure(std::move(mesh), -1);
    INFO("noise " << noise);
    CHECK(select_creases(r.mesh, r.topology, r.angles, {}, mean_edge_length(r.mesh)).lines.empty());
  }
}

TEST_CASE("the pipeline reports creases and re-runs only their selection for a new angle", "[creases][pipeline]") {
  Pipeline p(repair_mesh(cube(24)).mesh);
  p.run();
  CHECK(p.stats().creases == 12);
  CHECK(p.stats().crease_length == Approx(24.0));
  CHECK(p.stats().crease_angle == kDefaultCreaseAngle);
  CHECK(p.all_kinds().size() == p.lines().size() + 12);
  const CreaseResult first = p.crease_result();

  PipelineOptions o = p.options();
  o.creases.angle = 95;
  p.set_options(o);
  std::vector<Stage> ran;
  p.run([&](Stage s, double fraction) {
    if (fraction == 0) ran.push_back(s);
    return true;
  });
  CHECK(ran == std::vector<Stage>{Stage::Creases});
  CHECK(p.stats().creases == 0);

  // The first run took the creases from the boundaries' selection (the same
  // automatic angle); back at that angle, selected on their own: the same lines.
  o.creases.angle = -1;
  p.set_options(o);
  p.run();
  CHECK(p.crease_result().edges == first.edges);
  REQUIRE(p.creases().size() == first.lines.size());
  for (size_t i = 0; i < first.lines.size(); ++i) CHECK(p.creases()[i].points == first.lines[i].points);
}

// Crease boundaries (mesh/cut.h): the cube cut along its 90° edges falls
// into its six faces; a slit inside a flat grid opens between its ends.
TEST_CASE("cutting along creases splits each crease vertex into its sides", "[creases][cut]") {
  const Run r = measure(repair_mesh(cube(6)).mesh);
  std::vector<uint32_t> sharp;
  for (uint32_t e = 0; e < r.topology.edges.size(); ++e)
    if (std::abs(r.angles.angle[e]) > 80 * testing::kPi / 180) sharp.push_back(e);
  REQUIRE(sharp.size() == 12 * 6);
  const CutMesh cut = cut_along_edges(r.mesh, r.topology, sharp);
  // 8 corners with 3 sides, 12 × 5 edge vertices with 2.
  CHECK(cut.copy_of.size() == 8 * 2 + 12 * 5);
  CHECK(cut.mesh.triangles.size() == r.mesh.triangles.size());
  const Topology t = build_topology(cut.mesh);
  size_t boundary = 0;
  for (uint32_t e = 0; e < t.edges.size(); ++e) boundary += t.is_boundary_edge(e);
  CHECK(boundary == 2 * sharp.size());
  // Every triangle keeps its corners' positions.
  for (size_t f = 0; f < r.mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      CHECK(cut.source(cut.mesh.triangles[f][k]) == r.mesh.triangles[f][k]);
      CHECK(cut.mesh.positions[cut.mesh.triangles[f][k]] == r.mesh.positions[r.mesh.triangles[f][k]]);
    }
  // Copies meet again at their mean.
  std::vector<Vec3> moved = cut.mesh.positions;
  const uint32_t copy = static_cast<uint32_t>(cut.input_vertices);
  moved[copy] += Vec3(0.3, 0, 0);
  merge_copies(cut, moved);
  const uint32_t v = cut.copy_of[0];
  size_t sides = 1;
  for (uint32_t s : cut.copy_of) sides += s == v;
  CHECK((moved[v] - (r.mesh.positions[v] + Vec3(0.3 / sides, 0, 0))).norm() < 1e-12);
  CHECK(moved[copy] == moved[v]);

  // A slit of three edges through a flat grid: its two inner vertices split,
  // its ends stay; three edges become six boundary edges.
  testing::GridOptions grid;
  grid.nu = grid.nv = 8;
  const Mesh flat = repair_mesh(testing::parametric_grid([](double a, double b) { return Vec3(a, b, 0); }, grid)).mesh;
  const Topology ft = build_topology(flat);
  std::vector<uint32_t> slit;
  for (uint32_t e = 0; e < ft.edges.size(); ++e) {
    const Vec3 &a = flat.positions[ft.edges[e][0]], &b = flat.positions[ft.edges[e][1]];
    if (std::abs(a.y() - 0.5) < 1e-9 && std::abs(b.y() - 0.5) < 1e-9 && std::min(a.x(), b.x()) > 0.3 &&
        std::max(a.x(), b.x()) < 0.8)
      slit.push_back(e);
  }
  REQUIRE(slit.size() == 3);
  const CutMesh open = cut_along_edges(flat, ft, slit);
  CHECK(open.copy_of.size() == 2);
  const Topology ot = build_topology(open.mesh);
  size_t flat_boundary = 0, open_boundary = 0;
  for (uint32_t e = 0; e < ft.edges.size(); ++e) flat_boundary += ft.is_boundary_edge(e);
  for (uint32_t e = 0; e < ot.edges.size(); ++e) open_boundary += ot.is_boundary_edge(e);
  CHECK(open_boundary == flat_boundary + 6);
  // Nothing to cut: the same mesh.
  CHECK(cut_along_edges(flat, ft, {}).copy_of.empty());
}

TEST_CASE("per-vertex values extend to a cut's copies, grown on any thread count or within capacity",
          "[creases][cut]") {
  CutMesh cut;
  cut.input_vertices = 10000;
  cut.copy_of = {0, 3, 3, 9999};
  std::vector<Vec3> points(cut.input_vertices);
  for (size_t v = 0; v < points.size(); ++v) points[v] = Vec3(double(v), -double(v), 0.5);
  std::vector<Vec3> want = points;
  for (uint32_t v : cut.copy_of) want.push_back(points[v]);
  for (int threads : {1, 2, 3}) {
    INFO("threads " << threads);
    CHECK(testing::on_threads(threads, [&] { return on_cut_vertices(cut, points); }) == want);
  }
  std::vector<Vec3> roomy = points;
  roomy.reserve(points.size() + 10);
  const Vec3* const storage = roomy.data();
  const std::vector<Vec3> extended = on_cut_vertices(cut, std::move(roomy));
  CHECK(extended == want);
  CHECK(extended.data() == storage);  // extended in place
  std::vector<uint32_t> labels(cut.input_vertices);
  std::iota(labels.begin(), labels.end(), 0u);
  labels = testing::on_threads(2, [&] { return on_cut_vertices(cut, labels); });
  REQUIRE(labels.size() == cut.input_vertices + 4);
  CHECK(std::vector<uint32_t>(labels.end() - 4, labels.end()) == cut.copy_of);
  CHECK(labels[1234] == 1234);
}

// cut_topology regroups only the edges at split vertices; it must give
// exactly the adjacency build_topology gives the cut mesh: on a closed mesh
// (the cube along its creases), and with random cuts of every density on an
// open jittered grid (boundary edges among them) and on a sphere.
TEST_CASE("the cut mesh's adjacency from the input's is build_topology's", "[creases][cut]") {
  auto check = [](const Mesh& mesh, const Topology& topology, const std::vector<uint32_t>& edges) {
    const CutMesh cut = cut_along_edges(mesh, topology, edges);
    testing::check_same_topology(cut_topology(topology, cut), build_topology(cut.mesh));
    return cut.copy_of.size();
  };
  const Run box = measure(repair_mesh(cube(6)).mesh);
  std::vector<uint32_t> sharp;
  for (uint32_t e = 0; e < box.topology.edges.size(); ++e)
    if (std::abs(box.angles.angle[e]) > 1) sharp.push_back(e);
  CHECK(check(box.mesh, box.topology, sharp) > 0);

  testing::GridOptions grid;
  grid.nu = grid.nv = 20;
  grid.jitter = 0.2;
  grid.random_diagonals = true;
  const Mesh sheet =
      repair_mesh(testing::height_field([](double x, double y) { return 0.2 * std::sin(3 * x * y); }, 2, 2, grid)).mesh;
  const Topology topology = build_topology(sheet);
  const Mesh ball = repair_mesh(testing::icosphere(4)).mesh;
  const Topology ball_topology = build_topology(ball);
  std::mt19937 random(3);
  size_t copies = 0;
  for (double density : {0.02, 0.1, 0.3, 0.7}) {
    std::bernoulli_distribution pick(density);
    for (const auto& [mesh, topology] : {std::pair{&sheet, &topology}, std::pair{&ball, &ball_topology}}) {
      std::vector<uint32_t> edges;
      for (uint32_t e = 0; e < topology->edges.size(); ++e)
        if (pick(random)) edges.push_back(e);
      INFO("density " << density << (mesh == &ball ? ", sphere" : ", grid"));
      copies += check(*mesh, *topology, edges);
    }
  }
  CHECK(copies > 1000);
}

TEST_CASE("crease boundaries: without creases the smooth stages run on the input mesh itself", "[creases][cut]") {
  const Mesh sphere = repair_mesh(testing::icosphere(3)).mesh;
  for (bool on : {false, true}) {
    Pipeline p(sphere);
    PipelineOptions o;
    o.creases.boundaries = on;
    p.set_options(o);
    p.run();
    INFO("boundaries " << on);
    CHECK(p.boundary_creases().empty());
    CHECK(&p.working_topology() == &p.topology());
    CHECK(p.working_surface().positions.size() == sphere.positions.size());
  }
  // The cube: its 12 edges are boundaries; the working mesh has the copies,
  // the lines and the pre-smoothed surface stay on the input's vertices.
  const Mesh box = repair_mesh(cube(12)).mesh;
  Pipeline p(box);
  PipelineOptions with_boundaries;
  with_boundaries.creases.boundaries = true;
  p.set_options(with_boundaries);
  p.run();
  CHECK(p.boundary_creases().size() >= 12 * 10);
  CHECK(&p.working_topology() != &p.topology());
  CHECK(p.working_surface().positions.size() == box.positions.size() + p.working_cut().copy_of.size());
  CHECK(p.curvature().kappa_max.size() == p.working_surface().positions.size());
  CHECK(p.surface().positions.size() == box.positions.size());
  // Flat faces, boundaries along every edge: no smooth line anywhere.
  CHECK(p.lines().empty());
  // The crease angle stays a selection: the boundaries do not follow it.
  const std::vector<uint32_t> before = p.boundary_creases();
  PipelineOptions steep = with_boundaries;
  steep.creases.angle = 120;
  p.set_options(steep);
  std::vector<Stage> ran;
  p.run([&](Stage s, double) {
    if (ran.empty() || ran.back() != s) ran.push_back(s);
    return true;
  });
  CHECK(ran == std::vector<Stage>{Stage::Creases});
  CHECK(p.creases().empty());
  CHECK(p.boundary_creases() == before);
  // Brush weights are painted on the input's vertices; the copies take
  // their vertex's (weight 0 everywhere: nothing is smoothed).
  PipelineOptions frozen = with_boundaries;
  frozen.smoothing.vertex_weights.assign(box.positions.size(), 0.0);
  p.set_options(frozen);
  REQUIRE_NOTHROW(p.run());
  CHECK(p.extremality().e_max.size() == p.working_surface().positions.size());
  CHECK(p.extremality().e_max == p.raw_extremality().e_max);
  CHECK(p.extremality().e_min == p.raw_extremality().e_min);
}

TEST_CASE("a given noise level is the one measured and gives the same angles", "[creases]") {
  // The Pipeline hands its own measure over (one component): the stage must
  // then read exactly what it would have measured itself.
  Mesh mesh = repair_mesh(cube(20)).mesh;
  testing::add_normal_noise(mesh, 0.3 * mean_edge_length(mesh), 5);
  const Topology topology = build_topology(mesh);
  const CreaseAngles measured = measure_crease_angles(mesh, topology, {-1});
  REQUIRE(measured.noise_measured);
  CHECK(measured.noise_level == surface_noise_level(mesh, topology));
  CHECK(measured.normal_filter_steps > 0);
  const CreaseAngles given = measure_crease_angles(mesh, topology, {-1, measured.noise_level});
  CHECK(given.noise_level == measured.noise_level);
  CHECK(given.normal_filter_steps == measured.normal_filter_steps);
  CHECK(given.angle == measured.angle);
  CHECK(given.support == measured.support);
  // A level other than the mesh's is taken as given: the filter follows it.
  CHECK(measure_crease_angles(mesh, topology, {-1, 0.0}).normal_filter_steps == 0);
}

namespace {

// A closed cylinder of radius 1 and height 0.4, its caps fans round a centre
// vertex, its 16 rim vertices a little off the regular angles (by up to 0.1
// of a step, a different amount at each), so that its rims' turns vary
// round the loop as a tessellated hole's do.
Mesh jittered_cylinder() {
  constexpr int kRim = 16;
  Mesh m;
  for (double z : {0.0, 0.4}) {
    for (int k = 0; k < kRim; ++k) {
      const double a = 2 * testing::kPi * (k + 0.1 * std::sin(7.0 * k)) / kRim;
      m.positions.emplace_back(std::cos(a), std::sin(a), z);
    }
  }
  m.positions.emplace_back(0, 0, 0), m.positions.emplace_back(0, 0, 0.4);
  const uint32_t bottom = 2 * kRim, top = bottom + 1;
  for (uint32_t k = 0; k < kRim; ++k) {
    const uint32_t next = (k + 1) % kRim;
    m.triangles.push_back({k, next, kRim + next}), m.triangles.push_back({k, kRim + next, kRim + k});
    m.triangles.push_back({bottom, next, k}), m.triangles.push_back({top, kRim + k, kRim + next});
  }
  return m;
}

// Each line as its points: what a relabelling must not change.
std::vector<std::vector<Vec3>> line_points(const CreaseResult& result) {
  std::vector<std::vector<Vec3>> lines;
  for (const Polyline& line : result.lines) lines.push_back(line.points);
  return lines;
}

}  // namespace

TEST_CASE("a small round rim, sharp at every vertex over the turn span, stays one closed crease", "[creases]") {
  // Every rim vertex turns by more than 60° over 2 mean edges; the turns'
  // local maxima fall where the tessellation puts them. Cut at each of them
  // (before 2026-12-07) the rims fell into pieces shorter than 2 mean
  // edges, which went as shortcuts across corners, and the rest as spurs.
  // The angle given: a low-poly cylinder's automatic one reads its median
  // dihedral (its 16 side edges' 22.5°) and takes 12 times that.
  const Run r = measure(jittered_cylinder());
  CreaseOptions options;
  options.angle = 35;
  const CreaseResult result = select_creases(r.mesh, r.topology, r.angles, options, mean_edge_length(r.mesh));
  REQUIRE(result.lines.size() == 2);
  for (const Polyline& line : result.lines) {
    CHECK(line.closed);
    CHECK(line.points.size() == 16);
    CHECK(line.convex);
  }
  CHECK(result.edges.size() == 32);
}

TEST_CASE("the creases do not depend on how the mesh is numbered", "[creases]") {
  // The same surfaces with their vertices, triangles and corners numbered at
  // random: the same lines, point for point, in the same order (chains are
  // oriented and ordered by position). Before 2026-12-07 the chains ran from
  // where the walks began, which moved the turn splits' ties: a relabelled
  // casting.obj had 43 creases instead of 51.
  const std::vector<Mesh> meshes = {jittered_cylinder(), repair_mesh(cube(6)).mesh};
  for (size_t i = 0; i < meshes.size(); ++i) {
    const Run base = measure(meshes[i]);
    const double h = mean_edge_length(base.mesh);
    CreaseOptions options;
    options.angle = 35;  // as above
    const CreaseResult expected = select_creases(base.mesh, base.topology, base.angles, options, h);
    REQUIRE(!expected.lines.empty());
    for (unsigned seed : {1u, 2u, 3u}) {
      INFO("mesh " << i << ", seed " << seed);
      const Run other = measure(testing::shuffled(meshes[i], seed));
      const CreaseResult got = select_creases(other.mesh, other.topology, other.angles, options, h);
      CHECK(got.edges.size() == expected.edges.size());
      CHECK(line_points(got) == line_points(expected));
    }
  }
}

TEST_CASE("the automatic angle's medians do not depend on how the mesh is numbered", "[creases]") {
  // A noisy subdivided sphere, its vertices, triangles and corners numbered
  // at random: the medians over every interior edge are the same (the
  // angles to the bits of their float rounding, as the normals' corners
  // turn; the lengths exactly). A sample of every fourth edge in edge order,
  // before 2026-12-07, gave another median for each numbering.
  Mesh mesh = repair_mesh(testing::icosphere(4)).mesh;
  testing::add_normal_noise(mesh, 0.2 * mean_edge_length(mesh), 5);
  const Run base = measure(mesh);
  REQUIRE(base.angles.median > 1.0);  // degrees: the noise turns the edges
  for (unsigned seed : {1u, 2u, 3u}) {
    const Run relabelled = measure(testing::shuffled(mesh, seed));
    CHECK(relabelled.angles.median == Approx(base.angles.median).epsilon(1e-6));
    CHECK(relabelled.angles.median_edge_length == base.angles.median_edge_length);
  }
}

TEST_CASE("a given median edge length is passed through, not measured", "[creases]") {
  // The Pipeline gives its frames' (ComponentFrames::median_edge_length);
  // the angles and the median angle are those measured without it.
  const Run r = measure(repair_mesh(cube(6)).mesh);
  CreaseMeasureOptions options{0};
  options.median_edge_length = 0.25;
  const CreaseAngles given = measure_crease_angles(r.mesh, r.topology, options);
  CHECK(given.median_edge_length == 0.25);
  CHECK(r.angles.median_edge_length == Approx(2.0 / 6));
  CHECK(given.median == r.angles.median);
  CHECK(given.angle == r.angles.angle);
  CHECK(given.support == r.angles.support);
}
