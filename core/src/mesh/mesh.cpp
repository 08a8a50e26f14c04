#include "crestline/mesh/mesh.h"

#include <cmath>

namespace crestline {

double mean_edge_length(const Mesh& mesh) {
  // Every interior edge is seen twice and boundary edges once; the bias is
  // negligible for a length unit and avoids building edges here.
  double sum = 0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) sum += (mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]).norm();
  return mesh.triangles.empty() ? 0 : sum / (3.0 * mesh.triangles.size());
}

}  // namespace crestline
