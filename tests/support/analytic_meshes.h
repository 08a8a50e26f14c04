#pragma once
// Meshes with known differential geometry, for tests and the quality harness.
// Every generator is deterministic (seeded) and returns a TriangleSoup that
// goes through repair_mesh like any file would.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <utility>

#include "crestline/mesh/mesh.h"
#include "crestline/mesh/repair.h"

namespace crestline::testing {

inline constexpr double kPi = 3.14159265358979323846;

// push_back rather than insert({…}): GCC 12 warns falsely (stringop-overflow) on the latter.
inline void add_vertex(TriangleSoup& s, const Vec3& p) {
  for (int k = 0; k < 3; ++k) s.positions.push_back(p[k]);
}
inline void add_triangle(TriangleSoup& s, uint32_t a, uint32_t b, uint32_t c) {
  for (uint32_t v : {a, b, c}) s.indices.push_back(v);
}

/// Geodesic sphere: an icosahedron subdivided `levels` times, projected.
inline TriangleSoup icosphere(int levels, double radius = 1.0) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Triangle> f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& p : v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<uint32_t>(v.size() - 1);
    };
    std::vector<Triangle> next;
    for (const Triangle& t3 : f) {
      const uint32_t a = midpoint(t3[0], t3[1]), b = midpoint(t3[1], t3[2]), c = midpoint(t3[2], t3[0]);
      next.insert(next.end(), {{t3[0], a, c}, {t3[1], b, a}, {t3[2], c, b}, {a, b, c}});
    }
    f.swap(next);
  }
  TriangleSoup s;
  for (const Vec3& p : v) add_vertex(s, radius * p);
  for (const Triangle& t3 : f) add_triangle(s, t3[0], t3[1], t3[2]);
  return s;
}

/// A closed parametric grid surface (u and/or v periodic) or open patch.
/// Quads are split along one diagonal direction (every vertex has valence
/// 6), in a checkerboard (valences 4 and 8), or at random.
enum class Diagonals { Uniform, Alternating, Random };

struct GridOptions {
  int nu = 32, nv = 32;
  bool periodic_u = false, periodic_v = false;
  bool random_diagonals = false;  // shorthand for diagonals = Random
  Diagonals diagonals = Diagonals::Uniform;
  double jitter = 0;  // in parameter cells, tangential randomisation
  unsigned seed = 1;
};

inline TriangleSoup parametric_grid(const std::function<Vec3(double, double)>& surface, const GridOptions& o) {
  TriangleSoup s;
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> jit(-o.jitter, o.jitter);
  const int cu = o.periodic_u ? o.nu : o.nu + 1, cv = o.periodic_v ? o.nv : o.nv + 1;
  for (int j = 0; j < cv; ++j)
    for (int i = 0; i < cu; ++i) {
      double du = 0, dv = 0;
      const bool edge_u = !o.periodic_u && (i == 0 || i == o.nu), edge_v = !o.periodic_v && (j == 0 || j == o.nv);
      if (o.jitter > 0) {
        du = edge_u ? 0 : jit(rng);
        dv = edge_v ? 0 : jit(rng);
      }
      add_vertex(s, surface((i + du) / o.nu, (j + dv) / o.nv));
    }
  auto id = [&](int i, int j) { return static_cast<uint32_t>((j % cv) * cu + (i % cu)); };
  std::bernoulli_distribution coin(0.5);
  for (int j = 0; j < o.nv; ++j)
    for (int i = 0; i < o.nu; ++i) {
      const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      const Diagonals kind = o.random_diagonals ? Diagonals::Random : o.diagonals;
      const bool flip = kind == Diagonals::Random        ? coin(rng)
                        : kind == Diagonals::Alternating ? (i + j) % 2 == 0
                                                         : true;
      if (flip)
        add_triangle(s, a, b, c), add_triangle(s, a, c, d);
      else
        add_triangle(s, a, b, d), add_triangle(s, b, c, d);
    }
  return s;
}

/// Torus around the z axis: tube radius r, centre-line radius R. Outwards.
inline TriangleSoup torus(double R, double r, const GridOptions& o) {
  GridOptions g = o;
  g.periodic_u = g.periodic_v = true;
  return parametric_grid(
      [&](double u, double v) {
        const double a = 2 * kPi * u, b = 2 * kPi * v;
        return Vec3((R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a), r * std::sin(b));
      },
      g);
}

/// Open cylinder of radius r along z, height h, normals outwards.
inline TriangleSoup cylinder(double r, double h, const GridOptions& o) {
  GridOptions g = o;
  g.periodic_u = true;
  return parametric_grid(
      [&](double u, double v) { return Vec3(r * std::cos(2 * kPi * u), r * std::sin(2 * kPi * u), h * (v - 0.5)); }, g);
}

/// Height field z = f(x, y) over [0,wx]×[0,wy], normals up (+z).
inline TriangleSoup height_field(const std::function<double(double, double)>& f, double wx, double wy,
                                 const GridOptions& o) {
  return parametric_grid([&](double u, double v) { return Vec3(u * wx, v * wy, f(u * wx, v * wy)); }, o);
}

/// The mesh numbered otherwise: its vertices and triangles in a random order
/// (components interleave in both), each triangle's corners rotated at
/// random (its orientation kept).
inline Mesh shuffled(const Mesh& mesh, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<uint32_t> order(mesh.positions.size()), rename(mesh.positions.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), random);
  Mesh out;
  for (uint32_t i = 0; i < order.size(); ++i) rename[order[i]] = i, out.positions.push_back(mesh.positions[order[i]]);
  for (const Triangle& t : mesh.triangles) {
    const int r = int(random() % 3);
    out.triangles.push_back({rename[t[r]], rename[t[(r + 1) % 3]], rename[t[(r + 2) % 3]]});
  }
  std::shuffle(out.triangles.begin(), out.triangles.end(), random);
  return out;
}

/// The soup repaired, its vertices numbered as the soup numbers them (each
/// at its earliest copy) instead of by first use: for tests whose data are
/// defined per vertex in the input's order (noise drawn vertex by vertex,
/// values pinned at vertex numbers). For soups whose triangles all survive
/// repair, which keeps their order.
inline Mesh repaired_in_input_order(const TriangleSoup& soup) {
  const Mesh m = repair_mesh(soup).mesh;
  if (m.triangles.size() != soup.triangle_count()) throw std::runtime_error("repair dropped triangles");
  std::vector<uint32_t> earliest(m.vertex_count(), UINT32_MAX);
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (uint32_t v : m.triangles[t])
      for (int k = 0; k < 3; ++k) {  // repair may have turned the triangle round: any corner at v's position
        const uint32_t i = soup.indices[3 * t + k];
        if (Vec3(soup.positions[3 * i], soup.positions[3 * i + 1], soup.positions[3 * i + 2]) == m.positions[v])
          earliest[v] = std::min(earliest[v], i);
      }
  std::vector<uint32_t> order(m.vertex_count()), rename(m.vertex_count());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return earliest[a] != earliest[b] ? earliest[a] < earliest[b]
                                      : a < b;  // a split vertex's copies: in repair's order
  });
  Mesh out;
  for (uint32_t i = 0; i < order.size(); ++i) rename[order[i]] = i, out.positions.push_back(m.positions[order[i]]);
  for (const Triangle& t : m.triangles) out.triangles.push_back({rename[t[0]], rename[t[1]], rename[t[2]]});
  return out;
}

/// Moves every vertex along its (area-weighted) normal by N(0, sigma²).
inline void add_normal_noise(Mesh& mesh, double sigma, unsigned seed) {
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  for (const Triangle& t : mesh.triangles) {
    const Vec3 n = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (uint32_t v : t) normals[v] += n;
  }
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (size_t v = 0; v < normals.size(); ++v)
    if (normals[v].norm() > 0) mesh.positions[v] += noise(rng) * normals[v].normalized();
}

}  // namespace crestline::testing
