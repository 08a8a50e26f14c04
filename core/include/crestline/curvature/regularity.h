#pragma once
// Paper §3, Definition 1: regular and singular triangles, per direction field.
#include <array>
#include <cstdint>
#include <vector>

#include "crestline/curvature/shape_operator.h"

namespace crestline {

/// Signs s_k ∈ {+1,-1} with s_0 = +1 making the three directions mutually
/// positive (Definition 1), or false if the triangle is singular.
bool consistent_signs(const Vec3& d0, const Vec3& d1, const Vec3& d2, std::array<double, 3>& signs);

struct Regularity {
  std::vector<uint8_t> regular_max;  // per triangle, for the κ_max directions
  std::vector<uint8_t> regular_min;  // per triangle, for the κ_min directions
  size_t singular_max = 0;
  size_t singular_min = 0;
};

Regularity classify_triangles(const Mesh& mesh, const Curvature& curvature);

}  // namespace crestline
