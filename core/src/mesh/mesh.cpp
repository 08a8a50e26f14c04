#include "crestline/mesh/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "crestline/numerics/parallel.h"

namespace crestline {

double mean_edge_length(const Mesh& mesh) {
  // Every interior edge is seen twice and boundary edges once; the bias is
  // negligible for a length unit and avoids building edges here. The lengths
  // are measured on every thread, a block of triangles at a time, and added
  // on the calling thread in triangle order: the same sum for any number.
  constexpr size_t kBlock = size_t{1} << 14;
  const size_t nt = mesh.triangles.size();
  std::vector<std::array<double, 3>> lengths(std::min(nt, kBlock));
  double sum = 0;
  for (size_t begin = 0; begin < nt; begin += kBlock) {
    const size_t end = std::min(nt, begin + kBlock);
    parallel_for(end - begin, [&](size_t first, size_t last) {
      for (size_t i = first; i < last; ++i) {
        const Triangle& t = mesh.triangles[begin + i];
        for (int k = 0; k < 3; ++k) lengths[i][k] = (mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]).norm();
      }
    });
    for (size_t i = 0; i < end - begin; ++i)
      for (int k = 0; k < 3; ++k) sum += lengths[i][k];
  }
  return nt == 0 ? 0 : sum / (3.0 * nt);
}

}  // namespace crestline
