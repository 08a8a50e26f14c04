#include "crestline/mesh/repair.h"

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "analytic_meshes.h"
#include "crestline/error.h"
#include "crestline/mesh/topology.h"
#include "on_threads.h"
#include "same_topology.h"

using namespace crestline;
using crestline::testing::add_triangle;
using crestline::testing::add_vertex;

namespace {

// A unit cube stored like a glTF export: every face has its own 4 vertices.
TriangleSoup split_cube() {
  TriangleSoup s;
  const int faces[6][4][3] = {
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
  for (int f = 0; f < 6; ++f) {
    const uint32_t base = static_cast<uint32_t>(s.vertex_count());
    for (int k = 0; k < 4; ++k) add_vertex(s, Vec3(faces[f][k][0], faces[f][k][1], faces[f][k][2]));
    add_triangle(s, base, base + 1, base + 2);
    add_triangle(s, base, base + 2, base + 3);
  }
  return s;
}

double signed_volume(const Mesh& m) {
  double v = 0;
  for (const Triangle& t : m.triangles) v += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]])) / 6;
  return v;
}

RepairResult repair_on(int threads, const TriangleSoup& soup) {
  return testing::on_threads(threads, [&] { return repair_mesh(soup); });
}

// The topology repair returns is the one build_topology finds on its mesh
// (recorded while pairing, or built again after a cut or split).
void check_own_topology(const RepairResult& r) { testing::check_same_topology(r.topology, build_topology(r.mesh)); }

// The components repair returns are those component_frames' union-find
// finds on its mesh, numbered alike (the vertices' own where there are
// several; none where one): vertex-connected pieces are the edge-connected
// ones once every vertex is one fan.
void check_own_components(const RepairResult& r) {
  const ComponentFrames found = component_frames(r.mesh, r.topology);
  CHECK(r.components.count == r.report.components);
  REQUIRE(r.components.count == found.count());
  if (found.count() == 1)
    CHECK(r.components.vertex.empty());
  else
    CHECK(r.components.vertex == found.vertex_component);
  // Given them, the frames are the same bits.
  const ComponentFrames given = component_frames(r.mesh, r.topology, r.components);
  CHECK(given.centre == found.centre);
  CHECK(given.scale == found.scale);
  CHECK(given.triangle_count == found.triangle_count);
  for (uint32_t v = 0; v < r.mesh.vertex_count(); ++v) CHECK(given.component(v) == found.component(v));
}

}  // namespace

TEST_CASE("repair welds seam vertices and orients a closed mesh outwards", "[repair]") {
  RepairResult r = repair_mesh(split_cube());
  CHECK(r.mesh.vertex_count() == 8);
  CHECK(r.mesh.triangle_count() == 12);
  CHECK(r.report.welded_vertices == 16);
  CHECK(r.report.boundary_edges == 0);
  CHECK(r.report.components == 1);
  CHECK(signed_volume(r.mesh) == Approx(1.0));

  // The same cube inside out comes back outwards.
  TriangleSoup inverted = split_cube();
  for (size_t t = 0; t < inverted.triangle_count(); ++t)
    std::swap(inverted.indices[3 * t + 1], inverted.indices[3 * t + 2]);
  RepairResult r2 = repair_mesh(inverted);
  CHECK(signed_volume(r2.mesh) == Approx(1.0));
  CHECK(r2.report.flipped_triangles == 12);
}

TEST_CASE("repair drops degenerate, duplicate, non-finite and unreferenced data", "[repair]") {
  TriangleSoup s = split_cube();
  add_triangle(s, 0, 1, 2);  // duplicate of the first
  add_triangle(s, 2, 1, 0);  // the same three vertices, reversed
  add_triangle(s, 3, 3, 4);  // repeated corner
  add_vertex(s, Vec3(NAN, 0, 0));
  add_triangle(s, 0, 1, static_cast<uint32_t>(s.vertex_count() - 1));
  add_vertex(s, Vec3(5, 5, 5));  // unreferenced
  RepairResult r = repair_mesh(s);
  CHECK(r.mesh.triangle_count() == 12);
  CHECK(r.report.duplicate_triangles == 2);
  CHECK(r.report.degenerate_triangles == 1);
  CHECK(r.report.nonfinite_triangles == 1);
  CHECK(r.report.unreferenced_vertices == 2);
  CHECK(r.report.notes().size() >= 4);
}

TEST_CASE("repair of a soup given up to it releases its arrays and repairs as from a copy", "[repair]") {
  TriangleSoup s = split_cube();
  add_triangle(s, 2, 1, 0);      // a duplicate, reversed
  add_vertex(s, Vec3(5, 5, 5));  // unreferenced
  s.notes.push_back("a reader's note");
  const RepairResult kept = repair_mesh(s);
  TriangleSoup given = s;
  const RepairResult released = repair_mesh(std::move(given));
  CHECK(given.positions.capacity() == 0);
  CHECK(given.indices.capacity() == 0);
  CHECK(given.notes == s.notes);  // the caller reports them
  CHECK(released.mesh.positions == kept.mesh.positions);
  CHECK(released.mesh.triangles == kept.mesh.triangles);
  CHECK(released.report.notes() == kept.report.notes());
  CHECK(released.components.count == kept.components.count);
  testing::check_same_topology(released.topology, kept.topology);

  // Released also when repair throws; the message still names the index.
  TriangleSoup bad = split_cube();
  bad.indices[5] = 999;
  CHECK_THROWS_WITH(repair_mesh(std::move(bad)), Catch::Contains("999"));
  CHECK(bad.positions.capacity() == 0);
  CHECK(bad.indices.capacity() == 0);
}

TEST_CASE("repair cuts non-manifold edges and splits non-manifold vertices", "[repair]") {
  // Three triangles around one edge (a "book" with three pages).
  TriangleSoup book;
  add_vertex(book, Vec3(0, 0, 0));
  add_vertex(book, Vec3(0, 0, 1));
  add_vertex(book, Vec3(1, 0, 0.5));
  add_vertex(book, Vec3(-1, 0, 0.5));
  add_vertex(book, Vec3(0, 1, 0.5));
  add_triangle(book, 0, 1, 2);
  add_triangle(book, 1, 0, 3);
  add_triangle(book, 0, 1, 4);
  RepairResult r = repair_mesh(book);
  CHECK(r.report.nonmanifold_edges == 1);
  CHECK(r.mesh.triangle_count() == 3);
  CHECK_NOTHROW(build_topology(r.mesh));
  check_own_topology(r);

  // Two tetrahedra touching at a single vertex.
  TriangleSoup bowtie;
  const Vec3 tip(0, 0, 0);
  add_vertex(bowtie, tip);
  for (int side : {1, -1}) {
    const uint32_t b = static_cast<uint32_t>(bowtie.vertex_count());
    add_vertex(bowtie, Vec3(side, 0, 0));
    add_vertex(bowtie, Vec3(side, 1, 0));
    add_vertex(bowtie, Vec3(side, 0, 1));
    add_triangle(bowtie, 0, b, b + 1);
    add_triangle(bowtie, 0, b + 1, b + 2);
    add_triangle(bowtie, 0, b + 2, b);
    add_triangle(bowtie, b, b + 2, b + 1);
  }
  RepairResult r2 = repair_mesh(bowtie);
  CHECK(r2.report.nonmanifold_vertices == 1);
  CHECK(r2.mesh.vertex_count() == 8);
  CHECK(r2.report.components == 2);
  check_own_topology(r2);

  // Seven tetrahedra at one tip: 21 triangles there (more than the 16 that
  // split_fans compares pairwise), one tip per tetrahedron.
  TriangleSoup star;
  add_vertex(star, tip);
  const int tetrahedra = 7;
  for (int i = 0; i < tetrahedra; ++i) {
    const double a = 2 * crestline::testing::kPi * i / tetrahedra, c = std::cos(a), s = std::sin(a);
    const uint32_t b = static_cast<uint32_t>(star.vertex_count());
    add_vertex(star, Vec3(2 * c, 2 * s, 0)), add_vertex(star, Vec3(2 * c - 0.5 * s, 2 * s + 0.5 * c, 0.5));
    add_vertex(star, Vec3(2 * c + 0.5 * s, 2 * s - 0.5 * c, 0.5));
    add_triangle(star, 0, b, b + 1), add_triangle(star, 0, b + 1, b + 2), add_triangle(star, 0, b + 2, b);
    add_triangle(star, b, b + 2, b + 1);
  }
  const RepairResult r3 = repair_mesh(star);
  CHECK(r3.report.nonmanifold_vertices == 1);
  CHECK(r3.report.components == size_t(tetrahedra));
  REQUIRE(r3.mesh.vertex_count() == size_t(4 * tetrahedra));
  std::set<uint32_t> tips;
  for (int i = 0; i < tetrahedra; ++i) {
    // Each tetrahedron's three triangles at the tip share one vertex at the tip's position.
    std::set<uint32_t> at_tip;
    for (int k = 0; k < 3; ++k)
      for (uint32_t v : r3.mesh.triangles[size_t(4 * i + k)])
        if (r3.mesh.positions[v] == tip) at_tip.insert(v);
    CHECK(at_tip.size() == 1);
    tips.insert(at_tip.begin(), at_tip.end());
  }
  CHECK(tips.size() == size_t(tetrahedra));
  check_own_topology(r3);
}

TEST_CASE("repair cuts a Moebius strip into an orientable surface", "[repair]") {
  TriangleSoup s;
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * crestline::testing::kPi * i / n;
    for (double w : {-0.3, 0.3}) {
      const double r = 1 + w * std::cos(a / 2);
      add_vertex(s, Vec3(r * std::cos(a), r * std::sin(a), w * std::sin(a / 2)));
    }
  }
  for (int i = 0; i < n; ++i) {
    uint32_t a = 2 * i, b = 2 * i + 1, c = 2 * ((i + 1) % n), d = c + 1;
    if (i == n - 1) std::swap(c, d);  // the half twist
    add_triangle(s, a, c, b);
    add_triangle(s, b, c, d);
  }
  RepairResult r = repair_mesh(s);
  CHECK(r.mesh.triangle_count() == 2 * n);
  check_own_topology(r);
  const Topology topo = build_topology(r.mesh);
  // Every interior edge is traversed in opposite directions by its two triangles.
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    if (topo.is_boundary_edge(static_cast<uint32_t>(e))) continue;
    int forward = 0;
    for (uint32_t t : topo.edge_triangles[e]) {
      const Triangle& f = r.mesh.triangles[t];
      for (int k = 0; k < 3; ++k) forward += f[k] == topo.edges[e][0] && f[(k + 1) % 3] == topo.edges[e][1];
    }
    CHECK(forward == 1);
  }
}

TEST_CASE("repair rejects unusable input with one clear sentence", "[repair]") {
  TriangleSoup empty;
  CHECK_THROWS_WITH(repair_mesh(empty), Catch::Contains("no triangles"));
  TriangleSoup bad = split_cube();
  bad.indices[5] = 999;
  try {
    repair_mesh(bad);
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidInput);
    CHECK(std::string(e.what()).find("999") != std::string::npos);
  }
  TriangleSoup flat;
  for (int i = 0; i < 3; ++i) add_vertex(flat, Vec3(i, i, i));
  add_triangle(flat, 0, 1, 2);
  CHECK_THROWS_AS(repair_mesh(flat), Error);
  RepairOptions small;
  small.max_triangles = 5;
  try {
    repair_mesh(split_cube(), small);
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::TooLarge);
  }
}

TEST_CASE("welding tolerance is relative to the model size", "[repair]") {
  for (double scale : {1e-6, 1.0, 1e6}) {
    TriangleSoup s = split_cube();
    for (size_t i = 0; i < s.positions.size(); ++i)
      s.positions[i] = s.positions[i] * scale + (i % 3 == 0 ? 1e3 * scale : 0);
    RepairResult r = repair_mesh(s);
    CHECK(r.mesh.vertex_count() == 8);
  }
}

TEST_CASE("welding picks the earliest representative within tolerance, as a brute-force search does", "[repair]") {
  // Clusters of 8 vertices scattered within 1.5 tolerances of their centre, so
  // that pairs straddle the tolerance and the weld grid's cells in every
  // direction; each vertex opens a triangle with vertices of the next two
  // clusters. Reference: every vertex, in input order, joins the earliest
  // earlier representative within tolerance, or becomes one. 6,400 vertices:
  // on 1 thread the weld inserts representatives as it goes, on 2 its
  // searches split over the threads (chains of welds among them).
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1), signed_unit(-1, 1);
  const int clusters = 800, per_cluster = 8;
  TriangleSoup s;
  std::vector<Vec3> centres(clusters);
  for (Vec3& c : centres) c = Vec3(unit(random), unit(random), unit(random)) + Vec3(1e3, -2e3, 0);
  // The clusters lie inside [1e3, 1e3 + 1] × …; two corner vertices fix the diagonal.
  const Vec3 lo(1e3 - 0.1, -2e3 - 0.1, -0.1), hi(1e3 + 1.1, -2e3 + 1.1, 1.1);
  const double tolerance = RepairOptions().weld_tolerance * (hi - lo).norm();
  // Two clusters touch the box's corners, where the weld's grid begins and ends.
  centres[0] = lo + Vec3::Constant(1.5 * tolerance), centres[1] = hi - Vec3::Constant(1.5 * tolerance);
  for (int c = 0; c < clusters; ++c)
    for (int k = 0; k < per_cluster; ++k) {
      Vec3 offset;
      do offset = Vec3(signed_unit(random), signed_unit(random), signed_unit(random));
      while (offset.norm() > 1);
      add_vertex(s, centres[c] + 1.5 * tolerance * offset);
    }
  const uint32_t corner_lo = uint32_t(s.vertex_count());
  add_vertex(s, lo), add_vertex(s, hi), add_vertex(s, Vec3(lo.x(), hi.y(), lo.z()));
  for (uint32_t i = 0; i < uint32_t(clusters * per_cluster); ++i) {
    const uint32_t c = i / per_cluster;
    add_triangle(s, i, ((c + 1) % clusters) * per_cluster + random() % per_cluster,
                 ((c + 2) % clusters) * per_cluster + random() % per_cluster);
  }
  add_triangle(s, corner_lo, corner_lo + 1, corner_lo + 2);

  std::vector<Vec3> points(s.vertex_count());
  for (size_t i = 0; i < points.size(); ++i)
    points[i] = Vec3(s.positions[3 * i], s.positions[3 * i + 1], s.positions[3 * i + 2]);
  std::vector<uint32_t> representative(points.size()), representatives;
  size_t welded = 0;
  for (uint32_t i = 0; i < points.size(); ++i) {
    representative[i] = i;
    for (uint32_t j : representatives)
      if ((points[j] - points[i]).norm() <= tolerance) {
        representative[i] = j, ++welded;
        break;
      }
    if (representative[i] == i) representatives.push_back(i);
  }
  REQUIRE(welded > 200);                               // the test welds many vertices …
  REQUIRE(representatives.size() > size_t(clusters));  // … but not every cluster into one

  // Expected triangles: welded corners, the first of each vertex set kept.
  std::vector<std::array<uint32_t, 3>> expected;
  std::set<std::array<uint32_t, 3>> seen;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    std::array<uint32_t, 3> f{representative[s.indices[3 * t]], representative[s.indices[3 * t + 1]],
                              representative[s.indices[3 * t + 2]]};
    std::sort(f.begin(), f.end());
    if (seen.insert(f).second) expected.push_back(f);
  }
  const int threads = GENERATE(1, 2);
  INFO("threads: " << threads);
  const RepairResult r = repair_on(threads, s);
  CHECK(r.report.welded_vertices == welded);
  REQUIRE(r.mesh.triangle_count() == expected.size());
  size_t mismatches = 0;
  for (size_t t = 0; t < expected.size(); ++t) {
    std::array<Vec3, 3> want, got;
    for (int k = 0; k < 3; ++k) want[k] = points[expected[t][k]], got[k] = r.mesh.positions[r.mesh.triangles[t][k]];
    auto less = [](const Vec3& a, const Vec3& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    };
    std::sort(want.begin(), want.end(), less), std::sort(got.begin(), got.end(), less);
    mismatches += want != got;
  }
  CHECK(mismatches == 0);
}

// repair_mesh counts boundary edges without grouping the repaired mesh's
// half-edges again (only the cut ones): on random soups, dense in
// non-manifold edges, fans and non-orientable loops, the count must be what
// the repaired mesh's adjacency says.
TEST_CASE("the repair report counts the repaired mesh's boundary edges", "[repair]") {
  std::mt19937 random(7);
  size_t with_cuts = 0;
  for (int round = 0; round < 200; ++round) {
    TriangleSoup s;
    const uint32_t nv = 6 + round % 20;
    for (uint32_t v = 0; v < nv; ++v) add_vertex(s, Vec3(random() % 7, random() % 7, random() % 7));
    std::uniform_int_distribution<uint32_t> vertex(0, nv - 1);
    for (uint32_t t = 0; t < 3 * nv; ++t) add_triangle(s, vertex(random), vertex(random), vertex(random));
    RepairResult r;
    try {
      r = repair_mesh(s);
    } catch (const Error&) {
      continue;  // nothing usable (all degenerate)
    }
    const Topology topo = build_topology(r.mesh);
    size_t boundary = 0;
    for (size_t e = 0; e < topo.edges.size(); ++e) boundary += topo.is_boundary_edge(static_cast<uint32_t>(e));
    INFO("round " << round);
    CHECK(r.report.boundary_edges == boundary);
    check_own_topology(r);
    with_cuts += r.report.nonmanifold_edges > 0 && r.report.nonmanifold_vertices > 0;
  }
  CHECK(with_cuts > 50);  // the soups exercise the cuts
}

TEST_CASE("repair gives the same mesh and report on 1 and 2 threads", "[repair][threads]") {
  // 20,000 triangles (enough for the parallel loops to split), seams welded
  // from a copy of every vertex, some triangles repeated or collapsed.
  testing::GridOptions grid;
  grid.nu = grid.nv = 100;
  grid.jitter = 0.2;
  grid.random_diagonals = true;
  TriangleSoup s = testing::height_field([](double x, double y) { return 0.1 * std::sin(5 * x + 3 * y); }, 2, 2, grid);
  const uint32_t nv = uint32_t(s.vertex_count());
  for (uint32_t v = 0; v < nv; ++v)
    add_vertex(s, Vec3(s.positions[3 * v], s.positions[3 * v + 1], s.positions[3 * v + 2]));
  for (size_t t = 0; t < s.triangle_count(); t += 7) s.indices[3 * t] += nv;  // the copy: welded back
  const size_t nt = s.triangle_count();
  for (size_t t = 0; t < nt; t += 50) add_triangle(s, s.indices[3 * t + 1], s.indices[3 * t], s.indices[3 * t + 2]);
  for (size_t t = 0; t < nt; t += 90) add_triangle(s, s.indices[3 * t], s.indices[3 * t], s.indices[3 * t + 1]);
  // Fins: a triangle on an edge of the grid (a non-manifold edge, cut) and a
  // triangle touching the grid at one vertex only (a second fan there).
  for (size_t t = 0; t < nt; t += 61) {
    const uint32_t a = s.indices[3 * t], b = s.indices[3 * t + 1], top = uint32_t(s.vertex_count());
    add_vertex(s, Vec3(s.positions[3 * a], s.positions[3 * a + 1], s.positions[3 * a + 2] + 0.5));
    add_vertex(s, Vec3(s.positions[3 * a] + 0.1, s.positions[3 * a + 1], s.positions[3 * a + 2] + 0.5));
    add_triangle(s, a, b, top);
    add_triangle(s, s.indices[3 * t + 2], top + 1, top);
  }
  const RepairResult one = repair_on(1, s), two = repair_on(2, s);
  CHECK(one.report.welded_vertices > 1000);  // the referenced copies
  CHECK(one.report.duplicate_triangles > 0);
  CHECK(one.report.degenerate_triangles > 0);
  CHECK(one.report.nonmanifold_edges > 50);
  CHECK(one.report.nonmanifold_vertices > 100);
  CHECK(one.report.notes() == two.report.notes());
  CHECK(one.report.boundary_edges == two.report.boundary_edges);
  CHECK(one.mesh.triangles == two.mesh.triangles);
  CHECK(one.mesh.positions == two.mesh.positions);
}

TEST_CASE("repair drops duplicates wherever they sit, as a set of vertex triples does, on 1 and 2 threads",
          "[repair][threads]") {
  // Duplicates are found while the half-edges are paired (two triangles with
  // one opposite corner across a shared edge): copies inside the surface
  // (edges of three or four triangles), reversed and rotated copies, three
  // copies, and an isolated pair (a manifold edge of exactly the two). Over
  // 2^15 triangles, so the groupings split over threads; a clean grid has none.
  testing::GridOptions grid;
  grid.nu = grid.nv = 130;
  grid.random_diagonals = true;
  TriangleSoup s = testing::height_field([](double x, double y) { return 0.1 * std::sin(3 * x + 5 * y); }, 2, 2, grid);
  const size_t clean = s.triangle_count();
  CHECK(repair_mesh(s).report.duplicate_triangles == 0);
  for (size_t t = 0; t < clean; t += 37) {
    const uint32_t a = s.indices[3 * t], b = s.indices[3 * t + 1], c = s.indices[3 * t + 2];
    add_triangle(s, b, c, a);                  // rotated
    if (t % 3 == 0) add_triangle(s, a, c, b);  // reversed: a third copy
    if (t % 5 == 0) add_triangle(s, c, a, b);  // a fourth
  }
  const uint32_t base = uint32_t(s.vertex_count());
  add_vertex(s, Vec3(5, 0, 0)), add_vertex(s, Vec3(6, 0, 0)), add_vertex(s, Vec3(5, 1, 0));
  add_triangle(s, base, base + 1, base + 2), add_triangle(s, base + 2, base + 1, base);  // an isolated pair

  std::set<std::array<uint32_t, 3>> seen;
  std::vector<std::array<uint32_t, 3>> firsts;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    std::array<uint32_t, 3> f{s.indices[3 * t], s.indices[3 * t + 1], s.indices[3 * t + 2]};
    std::sort(f.begin(), f.end());
    if (seen.insert(f).second) firsts.push_back(f);
  }
  const size_t duplicates = s.triangle_count() - firsts.size();
  REQUIRE(duplicates > 1000);
  REQUIRE(s.triangle_count() > size_t{1} << 15);
  const RepairResult one = repair_on(1, s), two = repair_on(2, s);
  CHECK(one.report.duplicate_triangles == duplicates);
  CHECK(one.report.nonmanifold_edges == 0);  // the copies leave nothing to cut
  REQUIRE(one.mesh.triangle_count() == firsts.size());
  size_t mismatches = 0;  // the first of each vertex set stays, in input order
  for (size_t t = 0; t < firsts.size(); ++t) {
    std::array<uint32_t, 3> got = one.mesh.triangles[t];
    std::array<Vec3, 3> want_p, got_p;
    for (int k = 0; k < 3; ++k)
      want_p[k] =
          Vec3(s.positions[3 * firsts[t][k]], s.positions[3 * firsts[t][k] + 1], s.positions[3 * firsts[t][k] + 2]),
      got_p[k] = one.mesh.positions[got[k]];
    auto less = [](const Vec3& a, const Vec3& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    };
    std::sort(want_p.begin(), want_p.end(), less), std::sort(got_p.begin(), got_p.end(), less);
    mismatches += want_p != got_p;
  }
  CHECK(mismatches == 0);
  CHECK(two.report.duplicate_triangles == duplicates);
  CHECK(one.mesh.triangles == two.mesh.triangles);
  CHECK(one.mesh.positions == two.mesh.positions);
}

// split_fans walks each vertex's fans over the half-edge pairing; before
// (2ff2dda) it grouped every vertex's corners and joined triangles with a
// common uncut edge. On random soups dense in non-manifold edges, flipped
// triangles, non-orientable loops and vertices of several fans, the repaired
// meshes must be those of the grouping, whose FNV-1a hash over the
// reports, positions and triangles is recorded here; and each vertex of
// several fans keeps the fan of its first triangle, its copies (after every
// input vertex, in vertex order) taking the other fans in the order of their
// first triangles.
TEST_CASE("repair splits fans as the per-vertex grouping of 2ff2dda did", "[repair]") {
  std::mt19937 random(11);
  uint64_t hash = 1469598103934665603ull;
  auto mix = [&](uint64_t x) {
    for (int i = 0; i < 8; ++i) hash = (hash ^ ((x >> (8 * i)) & 0xff)) * 1099511628211ull;
  };
  size_t split = 0, rounds = 0, several = 0;
  // The last round is large enough for the walk to split over threads.
  for (int round = 0; round <= 300; ++round) {
    TriangleSoup s;
    const uint32_t nv = round < 300 ? 5 + round % 30 : 4000;
    // The draws in a fixed order: the last coordinate or corner first, as
    // g++ evaluated the arguments when the hash was recorded (the order of
    // a call's arguments is unspecified; clang++ takes the first first).
    for (uint32_t v = 0; v < nv; ++v) {
      const double z = double(random() % 17), y = double(random() % 17), x = double(random() % 17);
      add_vertex(s, Vec3(x, y, z));
    }
    const uint32_t nt = (2 + round % 4) * nv;
    for (uint32_t t = 0; t < nt; ++t) {
      const auto c = uint32_t(random() % nv), b = uint32_t(random() % nv), a = uint32_t(random() % nv);
      add_triangle(s, a, b, c);
    }
    RepairResult one, two;
    try {
      one = repair_on(1, s), two = repair_on(2, s);
    } catch (const Error&) {
      continue;  // nothing usable (all degenerate)
    }
    ++rounds;
    INFO("round " << round);
    CHECK(one.mesh.triangles == two.mesh.triangles);
    CHECK(one.mesh.positions == two.mesh.positions);
    CHECK(one.report.nonmanifold_vertices == two.report.nonmanifold_vertices);
    check_own_components(one);
    check_own_components(two);
    several += one.report.components > 1 && one.report.nonmanifold_vertices > 0;
    const Mesh& m = one.mesh;
    for (size_t n : {one.report.nonmanifold_edges, one.report.nonmanifold_vertices, one.report.flipped_triangles,
                     one.report.components, one.report.boundary_edges, m.vertex_count(), m.triangle_count()})
      mix(n);
    for (const Vec3& p : m.positions)
      for (int i = 0; i < 3; ++i) mix(uint64_t(p[i]));
    for (const Triangle& t : m.triangles)
      for (uint32_t v : t) mix(v);
    // Every vertex is one fan now (build_topology rejects any other), and
    // the copies follow the rule above. Welded vertices lie apart, so a
    // vertex's copies are the later vertices at its position.
    CHECK_NOTHROW(build_topology(m));
    std::vector<uint32_t> original(m.vertex_count()), first_triangle(m.vertex_count(), kNone);
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      original[v] = v;
      for (uint32_t u = 0; u < v; ++u)
        if (m.positions[u] == m.positions[v]) {
          original[v] = u;
          break;
        }
    }
    for (uint32_t t = 0; t < m.triangle_count(); ++t)
      for (uint32_t v : m.triangles[t]) first_triangle[v] = std::min(first_triangle[v], t);
    uint32_t copies = 0, last_original = 0, last_first = 0;
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      if (original[v] == v) {
        CHECK(copies == 0);  // copies come after every input vertex
        continue;
      }
      ++copies;
      const uint32_t o = original[v];
      CHECK(first_triangle[o] < first_triangle[v]);
      CHECK(o >= last_original);
      if (o == last_original) CHECK(first_triangle[v] > last_first);
      last_original = o, last_first = first_triangle[v];
    }
    split += copies > 0;
  }
  CHECK(rounds > 250);
  CHECK(split > 100);                    // the soups exercise the split
  CHECK(several > 100);                  // and components next to it
  CHECK(hash == 0x7a4cc39a6973665dull);  // 0xe651af74da85eb42 before the vertices were numbered by first use
}

namespace {

// Appends a soup to another, moved by `offset`, each triangle reversed with
// probability `flip`; with `seam`, every vertex is appended twice and the
// triangles use either copy at random (welded back).
void append_soup(TriangleSoup& s, const TriangleSoup& part, const Vec3& offset, double flip, bool seam,
                 std::mt19937& random) {
  const uint32_t base = uint32_t(s.vertex_count()), nv = uint32_t(part.vertex_count());
  for (int copy = 0; copy < (seam ? 2 : 1); ++copy)
    for (uint32_t v = 0; v < nv; ++v)
      add_vertex(s, Vec3(part.positions[3 * v], part.positions[3 * v + 1], part.positions[3 * v + 2]) + offset);
  std::bernoulli_distribution reversed(flip), second(0.5);
  for (size_t t = 0; t < part.triangle_count(); ++t) {
    uint32_t f[3];
    for (int k = 0; k < 3; ++k) f[k] = base + part.indices[3 * t + k] + (seam && second(random) ? nv : 0);
    if (reversed(random)) std::swap(f[1], f[2]);
    add_triangle(s, f[0], f[1], f[2]);
  }
}

// A Moebius strip of n × 2 quads around the z axis.
TriangleSoup moebius(int n) {
  TriangleSoup s;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * crestline::testing::kPi * i / n;
    for (double w : {-0.3, 0.0, 0.3}) {
      const double r = 1 + w * std::cos(a / 2);
      add_vertex(s, Vec3(r * std::cos(a), r * std::sin(a), w * std::sin(a / 2)));
    }
  }
  for (int i = 0; i < n; ++i)
    for (uint32_t k = 0; k < 2; ++k) {
      uint32_t a = 3 * i + k, b = a + 1, c = 3 * ((i + 1) % n) + k, d = c + 1;
      if (i == n - 1) c = 3 * ((i + 1) % n) + 2 - k, d = c - 1;  // the half twist
      add_triangle(s, a, c, b);
      add_triangle(s, b, c, d);
    }
  return s;
}

// A torus of nu × nv cells (closed, seams to weld, 30 % of its triangles
// reversed) and a sphere inside out.
TriangleSoup torus_and_sphere(int nu, int nv, std::mt19937& random) {
  TriangleSoup parts;
  testing::GridOptions grid;
  grid.nu = nu, grid.nv = nv;
  append_soup(parts, testing::torus(3, 1, grid), Vec3(0, 0, 0), 0.3, true, random);
  append_soup(parts, testing::icosphere(4, 1), Vec3(10, 0, 0), 1.0, false, random);
  return parts;
}

// The triangles of `parts` in random order.
TriangleSoup shuffled(const TriangleSoup& parts, std::mt19937& random) {
  std::vector<uint32_t> order(parts.triangle_count());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), random);
  TriangleSoup s;
  s.positions = parts.positions;
  for (uint32_t t : order) add_triangle(s, parts.indices[3 * t], parts.indices[3 * t + 1], parts.indices[3 * t + 2]);
  return s;
}

void check_same_repair(const RepairResult& got, const RepairResult& want) {
  CHECK(got.mesh.triangles == want.mesh.triangles);
  CHECK(got.mesh.positions == want.mesh.positions);
  testing::check_same_topology(got.topology, want.topology);
  for (const auto& [a, b] : {std::pair{got.report.welded_vertices, want.report.welded_vertices},
                             {got.report.degenerate_triangles, want.report.degenerate_triangles},
                             {got.report.duplicate_triangles, want.report.duplicate_triangles},
                             {got.report.unreferenced_vertices, want.report.unreferenced_vertices},
                             {got.report.nonmanifold_edges, want.report.nonmanifold_edges},
                             {got.report.nonmanifold_vertices, want.report.nonmanifold_vertices},
                             {got.report.flipped_triangles, want.report.flipped_triangles},
                             {got.report.components, want.report.components},
                             {got.report.boundary_edges, want.report.boundary_edges}})
    CHECK(a == b);
}

}  // namespace

// On one thread repair orients by one traversal from each component's seed;
// on several, by a union-find on every thread, traversing only the
// non-orientable components. Over 2^15 triangles, in random order so that
// every component spans the threads' ranges: a torus (closed, a third of
// its triangles reversed), a sphere (closed, inside out), Moebius strips,
// open patches with fins on their edges (non-manifold, cut) and seams to
// weld, a hundred tetrahedra, and a random soup dense in non-manifold edges
// and non-orientable loops. 1, 2 and 3 threads give the same mesh and report.
TEST_CASE("repair gives the same mesh and report on 1, 2 and 3 threads, components in any order", "[repair][threads]") {
  std::mt19937 random(17);
  TriangleSoup parts = torus_and_sphere(120, 60, random);
  testing::GridOptions grid;
  for (int i = 0; i < 3; ++i) append_soup(parts, moebius(200 + 50 * i), Vec3(-10, 3.0 * i, 0), 0.1, i == 1, random);
  grid.nu = grid.nv = 40;
  for (int i = 0; i < 2; ++i) {
    append_soup(parts, testing::height_field([](double x, double y) { return 0.1 * std::sin(3 * x + y); }, 2, 2, grid),
                Vec3(0, 10 + 3.0 * i, 0), 0.05, true, random);
    const uint32_t first = uint32_t(parts.triangle_count() - 2 * 40 * 40);
    for (uint32_t t = first; t < parts.triangle_count(); t += 97) {  // fins
      const uint32_t a = parts.indices[3 * t], b = parts.indices[3 * t + 1], top = uint32_t(parts.vertex_count());
      add_vertex(parts, Vec3(parts.positions[3 * a], parts.positions[3 * a + 1], parts.positions[3 * a + 2] + 0.3));
      add_triangle(parts, b, a, top);
    }
  }
  for (int i = 0; i < 100; ++i) append_soup(parts, testing::icosphere(0, 0.2), Vec3(i, -5, 0), 0.5, false, random);
  {
    TriangleSoup noise;
    const uint32_t nv = 3000;
    for (uint32_t v = 0; v < nv; ++v)
      add_vertex(noise, Vec3(double(random() % 13), double(random() % 13), double(random() % 13)));
    for (uint32_t t = 0; t < 3 * nv; ++t)
      add_triangle(noise, uint32_t(random() % nv), uint32_t(random() % nv), uint32_t(random() % nv));
    append_soup(parts, noise, Vec3(0, -30, 0), 0.0, false, random);
  }
  TriangleSoup s = shuffled(parts, random);
  REQUIRE(s.triangle_count() > size_t{1} << 15);

  const RepairResult one = repair_on(1, s);
  check_own_topology(one);
  CHECK(one.report.welded_vertices > 10000);
  CHECK(one.report.nonmanifold_edges > 50);
  CHECK(one.report.nonmanifold_vertices > 100);
  CHECK(one.report.flipped_triangles > 10000);
  CHECK(one.report.components > 150);
  check_own_components(one);
  for (int threads : {2, 3}) {
    INFO("threads: " << threads);
    const RepairResult other = repair_on(threads, s);
    check_same_repair(other, one);
    check_own_components(other);
  }
}

TEST_CASE("repair records its mesh's topology while pairing, on 1, 2 and 3 threads", "[repair][threads]") {
  // Nothing to cut or split (so the edges recorded while pairing are the
  // mesh's): seams to weld, flipped triangles, duplicates, degenerate
  // triangles and unreferenced vertices renumber the triangles and vertices
  // before and after the pairing; closed and open components in any order.
  // (A Moebius strip's cut splits vertices: the tests above cover it.)
  std::mt19937 random(23);
  TriangleSoup parts = torus_and_sphere(150, 80, random);
  testing::GridOptions grid;
  grid.nu = grid.nv = 40;
  for (int i = 0; i < 3; ++i)
    append_soup(parts, testing::height_field([](double x, double y) { return 0.1 * std::sin(3 * x + y); }, 2, 2, grid),
                Vec3(0, 10 + 3.0 * i, 0), 0.05, true, random);
  for (int i = 0; i < 50; ++i) append_soup(parts, testing::icosphere(0, 0.2), Vec3(i, -5, 0), 0.5, false, random);
  TriangleSoup s = shuffled(parts, random);
  add_vertex(s, Vec3(100, 100, 100));  // unreferenced
  const size_t nt = s.triangle_count();
  for (size_t t = 0; t < nt; t += 83) add_triangle(s, s.indices[3 * t + 2], s.indices[3 * t + 1], s.indices[3 * t]);
  for (size_t t = 0; t < nt; t += 89) add_triangle(s, s.indices[3 * t], s.indices[3 * t], s.indices[3 * t + 1]);
  REQUIRE(s.triangle_count() > size_t{1} << 15);

  const RepairResult one = repair_on(1, s);
  CHECK(one.report.nonmanifold_edges == 0);
  CHECK(one.report.nonmanifold_vertices == 0);
  CHECK(one.report.welded_vertices > 10000);
  CHECK(one.report.duplicate_triangles > 100);
  CHECK(one.report.degenerate_triangles > 100);
  CHECK(one.report.unreferenced_vertices > 0);
  CHECK(one.report.flipped_triangles > 10000);
  CHECK(one.report.boundary_edges == 3 * 4 * 40);  // the height fields' borders
  CHECK(one.report.components == 55);
  check_own_topology(one);
  check_own_components(one);
  for (int threads : {2, 3}) {
    INFO("threads: " << threads);
    const RepairResult other = repair_on(threads, s);
    check_own_topology(other);
    check_same_repair(other, one);
  }
}

namespace {

// The median over the triangles of the span of their corners' numbers.
uint32_t median_corner_span(const std::vector<Triangle>& tris) {
  std::vector<uint32_t> span;
  for (const Triangle& t : tris) span.push_back(std::max({t[0], t[1], t[2]}) - std::min({t[0], t[1], t[2]}));
  std::nth_element(span.begin(), span.begin() + ptrdiff_t(span.size() / 2), span.end());
  return span[span.size() / 2];
}

// Whether the vertices are numbered in the order the triangles first use
// them, corner by corner.
bool numbered_by_first_use(const Mesh& m) {
  uint32_t seen = 0;
  for (const Triangle& t : m.triangles)
    for (uint32_t v : t) {
      if (v > seen) return false;
      if (v == seen) ++seen;
    }
  return seen == m.vertex_count();
}

}  // namespace

// Subdivision appends each edge's midpoint after the old vertices, so a
// triangle's corners lie far apart in the input's numbering (the 1.1M bench
// mesh: a median of 320k numbers apart); repair numbers the vertices by
// first use, so they lie close. The mesh repair returns then does not depend
// on how the input numbers its vertices: the icosphere with its vertices
// shuffled, or with two copies of each (a seam, welded), repairs to the same
// mesh, topology and components, on 1 and 2 threads.
TEST_CASE("repair numbers the vertices in the order the triangles first use them", "[repair][threads]") {
  const TriangleSoup sphere = testing::icosphere(6);  // 81,920 triangles: over 2^15, split over threads
  REQUIRE(sphere.triangle_count() > size_t{1} << 15);
  CHECK(median_corner_span(repair_on(1, sphere).mesh.triangles) < 100);
  {
    std::vector<Triangle> input(sphere.triangle_count());
    for (size_t t = 0; t < input.size(); ++t)
      for (int k = 0; k < 3; ++k) input[t][k] = sphere.indices[3 * t + k];
    CHECK(median_corner_span(input) > 10000);
  }
  std::mt19937 random(29);
  std::vector<uint32_t> new_number(sphere.vertex_count());
  std::iota(new_number.begin(), new_number.end(), 0u);
  std::shuffle(new_number.begin(), new_number.end(), random);
  TriangleSoup shuffled_vertices, seam;
  shuffled_vertices.positions.resize(sphere.positions.size());
  for (size_t v = 0; v < sphere.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) shuffled_vertices.positions[3 * new_number[v] + k] = sphere.positions[3 * v + k];
  for (uint32_t v : sphere.indices) shuffled_vertices.indices.push_back(new_number[v]);
  append_soup(seam, sphere, Vec3::Zero(), 0.0, true, random);

  const RepairResult want = repair_on(1, sphere);
  CHECK(numbered_by_first_use(want.mesh));
  CHECK(want.report.flipped_triangles == 0);
  check_own_topology(want);
  {
    // Its own numbering is kept: repairing the repaired mesh changes nothing.
    TriangleSoup again;
    for (const Vec3& p : want.mesh.positions) add_vertex(again, p);
    for (const Triangle& t : want.mesh.triangles) add_triangle(again, t[0], t[1], t[2]);
    check_same_repair(repair_on(1, again), want);
  }
  for (int threads : {1, 2}) {
    INFO("threads: " << threads);
    for (const TriangleSoup* input : std::array<const TriangleSoup*, 3>{&sphere, &shuffled_vertices, &seam}) {
      const RepairResult got = repair_on(threads, *input);
      CHECK(got.mesh.triangles == want.mesh.triangles);
      CHECK(got.mesh.positions == want.mesh.positions);
      testing::check_same_topology(got.topology, want.topology);
      CHECK(got.components.count == 1);
      // The seam's copies either welded or never used.
      CHECK(got.report.welded_vertices + got.report.unreferenced_vertices ==
            (input == &seam ? sphere.vertex_count() : 0));
    }
  }
}

// Welded, unreferenced and only-on-dropped-triangle vertices get no number;
// the others keep the first use's order past dropped and duplicate
// triangles.
TEST_CASE("repair numbers by first use past dropped triangles and vertices", "[repair]") {
  TriangleSoup s;
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(9, 9, 9), Vec3(1, 1, 0), Vec3(2, 1, 0.5),
                        Vec3(3, 1, 0), Vec3(3, 1, 0), Vec3(NAN, 0, 0)})
    add_vertex(s, p);        // 0 and 3 unreferenced, 7 a copy of 6
  add_triangle(s, 5, 4, 8);  // non-finite: dropped (8 then unused)
  add_triangle(s, 6, 6, 2);  // degenerate: dropped
  add_triangle(s, 7, 5, 2);  // 7 welded into 6
  add_triangle(s, 2, 5, 7);  // a duplicate (the same vertex set): dropped
  add_triangle(s, 1, 2, 5);
  add_triangle(s, 1, 5, 4);
  const RepairResult r = repair_mesh(s);
  CHECK(r.report.welded_vertices == 1);
  CHECK(r.report.nonfinite_triangles == 1);
  CHECK(r.report.degenerate_triangles == 1);
  CHECK(r.report.duplicate_triangles == 1);
  CHECK(r.report.unreferenced_vertices == 3);  // 0, 3 and 8
  CHECK(r.report.flipped_triangles == 0);
  REQUIRE(r.mesh.vertex_count() == 5);
  // Numbered as the kept triangles first use them: 6, 5, 2, then 1, then 4.
  const std::vector<Vec3> want = {Vec3(3, 1, 0), Vec3(2, 1, 0.5), Vec3(2, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)};
  for (uint32_t v = 0; v < 5; ++v) CHECK(r.mesh.positions[v] == want[v]);
  CHECK(r.mesh.triangles == std::vector<Triangle>{{0, 1, 2}, {3, 2, 1}, {3, 1, 4}});
  check_own_topology(r);
  check_own_components(r);
}
