#pragma once
// The traced zero sets before they are joined into polylines: nodes on mesh
// edges (or at trisector barycentres) and segments between them.
#include <array>
#include <cstdint>
#include <vector>

#include "crestline/mesh/mesh.h"

namespace crestline {

/// Ridges and valleys are the paper's smooth lines; creases are sharp edges
/// of the mesh (lines/creases.h).
enum class LineType : uint8_t { Ridge = 0, Valley = 1, Crease = 2 };

const char* line_type_name(LineType type);  // "ridge" / "valley" / "crease"

struct FeatureGraph {
  LineType type = LineType::Ridge;
  std::vector<Vec3> points;
  /// |κ| of the line's own principal curvature at the node (κ_max for
  /// ridges, κ_min for valleys), pointwise, linearly interpolated.
  std::vector<double> curvature;
  /// Edge index for edge crossings, triangle index for trisector centres.
  std::vector<uint32_t> source;
  /// For edge crossings, the parameter t of the node on its edge e:
  /// point = (1−t)·x[edges[e][0]] + t·x[edges[e][1]]. Unused for trisectors.
  std::vector<double> edge_parameter;
  std::vector<uint8_t> trisector;  // 1 for trisector barycentres
  /// Node per mesh edge, kNone where the zero set does not cross or no
  /// accepted segment ends there.
  std::vector<uint32_t> edge_node;
  std::vector<std::array<uint32_t, 2>> segments;
};

/// Moves every node to the same place on `mesh`, a mesh with the same
/// connectivity as the one traced (same edge parameter, same barycentre):
/// lines traced on a pre-smoothed surface are drawn on the input surface.
void place_nodes_on(FeatureGraph& graph, const Mesh& mesh, const std::vector<std::array<uint32_t, 2>>& edges);

}  // namespace crestline
