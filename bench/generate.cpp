#include "generate.h"

#include <cmath>
#include <random>

#include "crestline/mesh/cotan.h"
#include "crestline/mesh/topology.h"

namespace crestline::bench {

TriangleSoup subdivide(const Mesh& mesh) {
  const Topology topology = build_topology(mesh);
  const size_t nv = mesh.positions.size(), ne = topology.edges.size(), nt = mesh.triangles.size();

  std::vector<double> areas;
  std::vector<Vec3> face_normals;
  triangle_areas_normals(mesh.positions, mesh.triangles, areas, face_normals);
  std::vector<Vec3> normals(nv, Vec3::Zero());
  for (size_t t = 0; t < nt; ++t)
    for (uint32_t v : mesh.triangles[t]) normals[v] += areas[t] * face_normals[t];
  for (Vec3& n : normals) n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();

  TriangleSoup soup;
  soup.positions.reserve(3 * (nv + ne));
  for (const Vec3& p : mesh.positions) soup.positions.insert(soup.positions.end(), {p.x(), p.y(), p.z()});
  for (const auto& [a, b] : topology.edges) {
    // Hermite midpoint: ½(p_a + p_b) + (m_a − m_b)/8 with m = e − ⟨e,n⟩n.
    const Vec3 e = mesh.positions[b] - mesh.positions[a];
    const Vec3 m = 0.5 * (mesh.positions[a] + mesh.positions[b]) +
                   (e.dot(normals[b]) * normals[b] - e.dot(normals[a]) * normals[a]) / 8.0;
    soup.positions.insert(soup.positions.end(), {m.x(), m.y(), m.z()});
  }
  soup.indices.reserve(12 * nt);
  for (size_t t = 0; t < nt; ++t) {
    const Triangle& f = mesh.triangles[t];
    // Edge k joins corners k and k+1.
    const uint32_t m0 = static_cast<uint32_t>(nv + topology.triangle_edges[t][0]);
    const uint32_t m1 = static_cast<uint32_t>(nv + topology.triangle_edges[t][1]);
    const uint32_t m2 = static_cast<uint32_t>(nv + topology.triangle_edges[t][2]);
    soup.indices.insert(soup.indices.end(), {f[0], m0, m2, m0, f[1], m1, m2, m1, f[2], m0, m1, m2});
  }
  return soup;
}

TriangleSoup add_normal_noise(const Mesh& mesh, double sigma, uint64_t seed) {
  std::vector<double> areas;
  std::vector<Vec3> face_normals;
  triangle_areas_normals(mesh.positions, mesh.triangles, areas, face_normals);
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (uint32_t v : mesh.triangles[t]) normals[v] += areas[t] * face_normals[t];
  const double step = sigma * mean_edge_length(mesh);
  std::mt19937_64 random(seed);
  // A uniform deviate in (0, 1]: 53 random bits, never 0 (the logarithm's argument).
  const auto uniform = [&random] { return static_cast<double>((random() >> 11) + 1) * 0x1p-53; };
  TriangleSoup soup;
  soup.positions.reserve(3 * mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const double radius = std::sqrt(-2.0 * std::log(uniform())), angle = 2.0 * M_PI * uniform();
    const Vec3 n = normals[v].norm() > 0 ? Vec3(normals[v].normalized()) : Vec3::Zero();
    const Vec3 p = mesh.positions[v] + step * radius * std::cos(angle) * n;
    soup.positions.insert(soup.positions.end(), {p.x(), p.y(), p.z()});
  }
  soup.indices.reserve(3 * mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) soup.indices.insert(soup.indices.end(), t.begin(), t.end());
  return soup;
}

}  // namespace crestline::bench
