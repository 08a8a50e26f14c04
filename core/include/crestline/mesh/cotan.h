#pragma once
// Cotan Laplacian weights and lumped masses [PP93], shared by surface
// pre-smoothing and extremality smoothing.
#include <vector>

#include "crestline/mesh/topology.h"

namespace crestline {

struct CotanWeights {
  /// Per edge: ½(cot α + cot β) over the angles opposite it, clamped to
  /// [0, 5]: at 0 so that M + t·L stays positive definite on obtuse
  /// triangulations, at 5 so that slivers do not stall the solvers (cotan.cpp).
  std::vector<double> edge_weight;
  /// Per vertex: area(star)/3, the lumped (barycentric) mass.
  std::vector<double> vertex_mass;
};

CotanWeights cotan_weights(const std::vector<Vec3>& positions, const Mesh& mesh, const Topology& topology);

/// Twice the area of the triangle (p0, p1, p2), and its unit normal in
/// `normal` (zero where the area is): |(p1 − p0) × (p2 − p0)| and that
/// vector over its length. Inline: the same bits wherever a stage forms it
/// (compute_curvature forms each triangle's where it reads it).
inline double triangle_normal(const Vec3& p0, const Vec3& p1, const Vec3& p2, Vec3& normal) {
  const Vec3 n = (p1 - p0).cross(p2 - p0);
  const double len = n.norm();
  normal = len > 0 ? Vec3(n / len) : Vec3::Zero();
  return len;
}

/// Area of each triangle, and unit normals (zero for zero-area triangles):
/// ½ triangle_normal and its normal (the crease measure's face normals too).
void triangle_areas_normals(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                            std::vector<double>& areas, std::vector<Vec3>& normals);
/// The unit normals alone, the same bits as triangle_areas_normals'.
void triangle_normals(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                      std::vector<Vec3>& normals);

}  // namespace crestline
