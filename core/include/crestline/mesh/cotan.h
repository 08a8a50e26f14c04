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

/// Area of each triangle, and unit normals (zero for zero-area triangles).
void triangle_areas_normals(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                            std::vector<double>& areas, std::vector<Vec3>& normals);

}  // namespace crestline
