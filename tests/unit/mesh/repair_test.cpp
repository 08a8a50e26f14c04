#include "crestline/mesh/repair.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "analytic_meshes.h"
#include "crestline/error.h"
#include "crestline/mesh/topology.h"

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
