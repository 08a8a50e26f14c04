#pragma once
// The two mesh forms of the pipeline: the unwelded soup a reader returns, and
// the welded, repaired, consistently oriented manifold mesh every stage uses.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace crestline {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<uint32_t, 3>;

/// What a reader produces: flat positions (x,y,z per vertex) and triangle
/// indices (3 per triangle), possibly with duplicated seam vertices,
/// degenerate triangles and other defects. `notes` lists what the reader
/// skipped or changed (one sentence each), for the user.
struct TriangleSoup {
  std::vector<double> positions;
  std::vector<uint32_t> indices;
  std::vector<std::string> notes;

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return indices.size() / 3; }
};

/// An indexed triangle mesh. After `repair_mesh` it is welded, free of
/// degenerate/duplicate triangles and unreferenced vertices, consistently
/// oriented per component, and edge- and vertex-manifold (possibly with
/// boundary).
struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return triangles.size(); }
};

/// Mean length over all edges; the length unit of every unitless parameter.
double mean_edge_length(const Mesh& mesh);

}  // namespace crestline
