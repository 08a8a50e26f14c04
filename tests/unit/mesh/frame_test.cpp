#include "crestline/mesh/frame.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "analytic_meshes.h"
#include "crestline/lines/creases.h"
#include "crestline/mesh/topology.h"
#include "on_threads.h"

using namespace crestline;

namespace {

ComponentFrames frames_on(int threads, const Mesh& mesh) {
  const Topology topology = build_topology(mesh);
  return testing::on_threads(threads, [&] { return component_frames(mesh, topology); });
}

// The frames as one serial pass computes them (the code before the frames
// were computed on every thread): union-find, components numbered as they
// first appear among the triangles, boxes and sums in vertex and triangle order.
ComponentFrames serial_frames(const Mesh& mesh) {
  const size_t nv = mesh.positions.size();
  std::vector<uint32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  for (const Triangle& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) parent[find(t[k])] = find(t[0]);
  ComponentFrames f;
  f.vertex_component.assign(nv, 0);
  std::vector<uint32_t> root_component(nv, kNone);
  for (const Triangle& t : mesh.triangles)
    for (uint32_t v : t) {
      uint32_t& c = root_component[find(v)];
      if (c == kNone) c = uint32_t(f.triangle_count.size()), f.triangle_count.push_back(0);
      f.vertex_component[v] = c;
    }
  const size_t n = f.triangle_count.size();
  std::vector<Vec3> lo(n, Vec3::Constant(INFINITY)), hi(n, Vec3::Constant(-INFINITY));
  for (size_t v = 0; v < nv; ++v) {
    const uint32_t c = f.vertex_component[v];
    lo[c] = lo[c].cwiseMin(mesh.positions[v]), hi[c] = hi[c].cwiseMax(mesh.positions[v]);
  }
  std::vector<double> extent(n), sum(n, 0.0);
  for (size_t c = 0; c < n; ++c) {
    f.centre.push_back(0.5 * lo[c] + 0.5 * hi[c]);
    extent[c] = std::max((hi[c] - f.centre[c]).maxCoeff(), (f.centre[c] - lo[c]).maxCoeff());
    if (!(extent[c] > 0)) extent[c] = 1;
  }
  // The sides as side_sums adds them: integer multiples of 2^-62 of the
  // power of two above the longest side, in 128 bits.
  const auto side = [&](const Triangle& t, int k) {
    const uint32_t c = f.vertex_component[t[0]];
    return ((mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]) / extent[c]).norm();
  };
  double longest = 0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) longest = std::max(longest, side(t, k));
  int exponent = 0;
  std::frexp(longest, &exponent);
  __extension__ typedef unsigned __int128 Wide;
  std::vector<Wide> quanta(n, 0);
  for (const Triangle& t : mesh.triangles) {
    const uint32_t c = f.vertex_component[t[0]];
    ++f.triangle_count[c];
    for (int k = 0; k < 3; ++k) quanta[c] += uint64_t(side(t, k) * std::ldexp(1.0, 62 - exponent));
  }
  for (size_t c = 0; c < n; ++c) sum[c] = std::ldexp(static_cast<double>(quanta[c]), exponent - 62);
  for (size_t c = 0; c < n; ++c) {
    const double mean = sum[c] / (3.0 * f.triangle_count[c]);
    f.scale.push_back(mean > 0 ? extent[c] * mean : extent[c]);
  }
  return f;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void check_same_frames(const ComponentFrames& got, const ComponentFrames& want) {
  CHECK(got.vertex_component == want.vertex_component);
  CHECK(got.triangle_count == want.triangle_count);
  REQUIRE(got.count() == want.count());
  size_t differ = 0;
  for (size_t c = 0; c < want.count(); ++c) {
    differ += !same_bits(got.scale[c], want.scale[c]);
    for (int i = 0; i < 3; ++i) differ += !same_bits(got.centre[c][i], want.centre[c][i]);
  }
  CHECK(differ == 0);
}

// Appends a soup's vertices and triangles to a mesh, moved by `offset`.
void append(Mesh& mesh, const TriangleSoup& soup, const Vec3& offset) {
  const uint32_t base = uint32_t(mesh.positions.size());
  for (size_t i = 0; i < soup.vertex_count(); ++i)
    mesh.positions.push_back(Vec3(soup.positions[3 * i], soup.positions[3 * i + 1], soup.positions[3 * i + 2]) +
                             offset);
  for (size_t t = 0; t < soup.triangle_count(); ++t)
    mesh.triangles.push_back(
        {base + soup.indices[3 * t], base + soup.indices[3 * t + 1], base + soup.indices[3 * t + 2]});
}

}  // namespace

TEST_CASE("component frames are those of one serial pass, on 1, 2 and 3 threads", "[frame][threads]") {
  // A torus, a sphere and a hundred small tetrahedra, in random vertex and
  // triangle order, 2^15 triangles and more so that every step splits over
  // threads; and a soup of single triangles (more components than the
  // boxes are kept per thread for). One flat component has its smallest x
  // at both −0 and +0, at either end of the vertex order: the box keeps the
  // first, as a serial pass does.
  testing::GridOptions grid;
  grid.nu = 180, grid.nv = 100;
  Mesh several;
  append(several, testing::torus(3, 1, grid), Vec3(10, 0, 0));
  append(several, testing::icosphere(4, 2), Vec3(-1e3, 5, 2));
  const TriangleSoup tetrahedron = testing::icosphere(0, 0.1);
  for (int i = 0; i < 100; ++i) append(several, tetrahedron, Vec3(i, -i, 0.5 * i));
  Mesh mesh = testing::shuffled(several, 3);
  const uint32_t nv = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.begin(), Vec3(-0.0, 1, 1));
  for (Triangle& t : mesh.triangles)
    for (uint32_t& v : t) ++v;
  mesh.positions.push_back(Vec3(0.0, 2, 1)), mesh.positions.push_back(Vec3(0.0, 2, 2));
  mesh.triangles.push_back({nv + 1, 0, nv + 2});
  REQUIRE(mesh.triangles.size() > size_t{1} << 15);

  Mesh singles;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (uint32_t t = 0; t < 40000; ++t) {
    for (int k = 0; k < 3; ++k) singles.positions.push_back(Vec3(unit(random), unit(random), unit(random)));
    singles.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  singles = testing::shuffled(singles, 4);

  for (const Mesh* m : {&mesh, &singles}) {
    const ComponentFrames want = serial_frames(*m);
    CHECK(want.count() == (m == &mesh ? 103u : 40000u));
    for (int threads : {1, 2, 3}) {
      INFO("threads: " << threads << ", components: " << want.count());
      check_same_frames(frames_on(threads, *m), want);
    }
  }
  // Other orders of the same triangles give the same scales, bit for bit
  // (the components are numbered otherwise: compared sorted).
  const auto scales = [](const ComponentFrames& f) {
    std::vector<double> sorted = f.scale;
    std::sort(sorted.begin(), sorted.end());
    return sorted;
  };
  const std::vector<double> once = scales(frames_on(2, several));
  for (unsigned seed : {3u, 8u, 9u}) CHECK(scales(frames_on(2, testing::shuffled(several, seed))) == once);
  // The flat component's centre is at x = −0 (its first smallest x).
  const ComponentFrames f = frames_on(2, mesh);
  CHECK(std::signbit(f.centre[f.vertex_component[0]].x()));
}

TEST_CASE("components that do not fit the mesh are found again, not read", "[frame]") {
  // Two tetrahedra: given components of the wrong size (or several without
  // an array) give the frames found without them.
  Mesh mesh;
  const TriangleSoup tetrahedron = testing::icosphere(0, 1);
  append(mesh, tetrahedron, Vec3(0, 0, 0));
  append(mesh, tetrahedron, Vec3(5, 0, 0));
  const Topology topology = build_topology(mesh);
  const ComponentFrames want = component_frames(mesh, topology);
  REQUIRE(want.count() == 2);
  for (VertexComponents wrong : {VertexComponents{{0, 1}, 2}, VertexComponents{{}, 2},
                                 VertexComponents{std::vector<uint32_t>(mesh.positions.size() + 1, 0), 1}}) {
    const ComponentFrames got = component_frames(mesh, topology, wrong);
    CHECK(got.count() == 2);
    CHECK(got.vertex_component == want.vertex_component);
    CHECK(got.centre == want.centre);
    CHECK(got.scale == want.scale);
  }
}

TEST_CASE("the median interior edge is measured over interior edges, in mean edges", "[frame]") {
  // An open cylinder one cell high, 4 cells round (radius 1, height 10):
  // interior edges 4 of 10 and 4 diagonals of √102; the 8 rim edges (√2) on
  // the boundary are left out, or the upper median would be 10.
  testing::GridOptions grid;
  grid.nu = 4, grid.nv = 1;
  Mesh mesh;
  append(mesh, testing::cylinder(1, 10, grid), Vec3(0, 0, 0));
  const ComponentFrames f = frames_on(1, mesh);
  const double mean = (2 * (40 + 4 * std::sqrt(102.0)) + 8 * std::sqrt(2.0)) / 24;
  CHECK(f.scale[0] == Approx(mean).epsilon(1e-12));
  CHECK(f.median_edge_length == Approx(std::sqrt(102.0) / mean).epsilon(1e-6));
  // A closed surface only: a mesh of boundary edges has no median.
  Mesh single;
  single.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  single.triangles = {{0, 1, 2}};
  CHECK(frames_on(1, single).median_edge_length == 0);
}

TEST_CASE("the median interior edge is the crease measure's own, for any numbering, threads and power-of-two scale",
          "[frame][threads]") {
  // Components at scales 1000 apart, with boundaries (an open cylinder and a
  // jittered height field) and without (a sphere): each edge in its own
  // component's mean edges. The crease measure on the working-frame mesh
  // measures the same median from positions (single precision): the same
  // bits. 2^15 triangles and more so that the pass splits over threads.
  testing::GridOptions grid;
  grid.nu = 120, grid.nv = 60, grid.jitter = 0.3;
  Mesh mesh;
  append(mesh, testing::cylinder(1, 3, grid), Vec3(0, 0, 0));
  append(mesh, testing::height_field([](double x, double y) { return 0.1 * x * y; }, 2e3, 1e3, grid), Vec3(5, 0, 0));
  append(mesh, testing::icosphere(5, 1e-3), Vec3(0, 7, 0));
  REQUIRE(mesh.triangles.size() > size_t{1} << 15);
  const ComponentFrames f = frames_on(1, mesh);
  REQUIRE(f.count() == 3);
  const Topology topology = build_topology(mesh);
  const double own = measure_crease_angles(to_local(mesh, f), topology, {0}).median_edge_length;
  CHECK(same_bits(f.median_edge_length, own));
  CHECK(f.median_edge_length > 0.5);
  for (int threads : {2, 3}) CHECK(same_bits(frames_on(threads, mesh).median_edge_length, own));
  for (unsigned seed : {1u, 2u}) CHECK(same_bits(frames_on(2, testing::shuffled(mesh, seed)).median_edge_length, own));
  Mesh scaled = mesh;
  for (Vec3& p : scaled.positions) p *= 1024.0;
  CHECK(same_bits(frames_on(1, scaled).median_edge_length, own));
}
