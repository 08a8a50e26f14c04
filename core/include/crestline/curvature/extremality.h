#pragma once
// Paper §3, eq. (4): discrete extremality coefficients.
#include <functional>
#include <vector>

#include "crestline/curvature/shape_operator.h"

namespace crestline {

/// e_i(p) = 1/area(star p) · Σ_{T∋p} area(T) ⟨∇κ_i(T), κ⃗_i(p)⟩ for i = max, min.
/// Pointwise, units 1/length². The sign of e_i(p) is relative to the
/// (arbitrary) sign of dir_i(p) in Curvature; only products that also flip
/// with it (σ_pq e(q), consistent triangle choices) are meaningful.
struct Extremality {
  std::vector<double> e_max;
  std::vector<double> e_min;
};

/// progress, if set, is called on the calling thread between blocks of
/// triangles (fractions of the stage) and may throw to abandon it.
Extremality compute_extremality(const Mesh& mesh, const Curvature& curvature,
                                const std::function<void(double)>& progress = {});

}  // namespace crestline
