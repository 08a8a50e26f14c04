#pragma once
// Paper §3, Definition 1: regular and singular triangles, per direction field.
#include <array>
#include <cstdint>
#include <vector>

#include "crestline/curvature/shape_operator.h"

namespace crestline {

/// A triangle's entry in Regularity for one direction field, from the
/// directions d0, d1, d2 at its corners (Definition 1). The triangle is
/// regular if signs s_k ∈ {+1, −1} can be chosen that make s_0 d0, s_1 d1,
/// s_2 d2 mutually positive (a consistent choice). With s_0 = +1 the only
/// candidate is s_k = +1 where ⟨d0, dk⟩ ≥ 0, −1 elsewhere (the other
/// consistent choice is its flip), and it is consistent when both ⟨d0, dk⟩
/// are nonzero and s_1 s_2 ⟨d1, d2⟩ > 0.
/// The code is 0 for a singular triangle; else bit 0 is set, and bits 1 and
/// 2 where s_1, s_2 = −1, so that the tracer reads the signs (code_signs)
/// instead of the three directions again.
/// s_1 s_2 ⟨d1, d2⟩ > 0 is tested as ⟨d1, d2⟩ > 0 where s_1 = s_2 and
/// ⟨d1, d2⟩ < 0 where they differ (the product by ±1 is exact; a NaN fails
/// both), the tests combined without branches on the signs, which mispredict
/// (classify_triangles at 1.1M: 227.7 → 204.8 M instructions against the
/// branching form that the regularity tests keep as their reference).
inline uint8_t regularity_code(const Vec3& d0, const Vec3& d1, const Vec3& d2) {
  const double a = d0.dot(d1), b = d0.dot(d2), c = d1.dot(d2);
  const bool a_up = a >= 0, b_up = b >= 0;
  const bool same = a_up == b_up;
  const bool regular = (a != 0) & (b != 0) & ((same & (c > 0)) | (!same & (c < 0)));
  return regular ? static_cast<uint8_t>(1u | (a_up ? 0u : 2u) | (b_up ? 0u : 4u)) : 0;
}
/// The same for stored directions, widened to double.
inline uint8_t regularity_code(const Direction& d0, const Direction& d1, const Direction& d2) {
  return regularity_code(widen(d0), widen(d1), widen(d2));
}

/// The signs of a regular triangle's code (regularity_code).
inline std::array<double, 3> code_signs(uint8_t code) { return {1.0, code & 2u ? -1.0 : 1.0, code & 4u ? -1.0 : 1.0}; }

struct Regularity {
  // Per triangle, regularity_code for the κ_max and κ_min directions:
  // nonzero where the triangle is regular.
  std::vector<uint8_t> regular_max;
  std::vector<uint8_t> regular_min;
  size_t singular_max = 0;
  size_t singular_min = 0;
};

Regularity classify_triangles(const Mesh& mesh, const Curvature& curvature);

}  // namespace crestline
