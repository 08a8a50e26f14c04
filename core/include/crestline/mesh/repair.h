#pragma once
// Stage 0: from a reader's triangle soup to a mesh every later stage can trust.
#include <string>
#include <vector>

#include "crestline/mesh/frame.h"
#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"

namespace crestline {

struct RepairOptions {
  /// Vertices closer than this fraction of the bounding-box diagonal are one
  /// vertex (glTF/OBJ split vertices at UV and normal seams).
  double weld_tolerance = 1e-7;
  /// Refuse meshes with more triangles than this before allocating anything
  /// proportional to them.
  size_t max_triangles = 50'000'000;
};

/// What was repaired, for the user ("welded 1,113 seam vertices", …).
struct RepairReport {
  size_t input_vertices = 0;
  size_t input_triangles = 0;
  size_t welded_vertices = 0;        // vertices merged into another one
  size_t nonfinite_triangles = 0;    // dropped: a corner had NaN/inf coordinates
  size_t degenerate_triangles = 0;   // dropped: repeated corner or zero area
  size_t duplicate_triangles = 0;    // dropped: same three vertices as another
  size_t unreferenced_vertices = 0;  // dropped
  size_t nonmanifold_edges = 0;      // cut: more than two triangles met there
  size_t nonmanifold_vertices = 0;   // split: more than one triangle fan met there
  size_t flipped_triangles = 0;      // reoriented to agree with their neighbours
  size_t components = 0;             // edge-connected pieces after repair
  size_t boundary_edges = 0;

  /// One sentence per non-zero repair, for logs and the UI.
  std::vector<std::string> notes() const;
};

struct RepairResult {
  Mesh mesh;
  RepairReport report;
  /// build_topology(mesh), found while repairing: pass it on to the Pipeline.
  Topology topology;
  /// The mesh's components (report.components of them; each vertex's where
  /// there are several), numbered as component_frames numbers them: pass
  /// them on to the Pipeline too.
  VertexComponents components;
};

/// Welds, drops degenerate/duplicate/non-finite triangles and unreferenced
/// vertices, orients each component consistently and cuts non-manifold edges
/// and vertices into manifold pieces. Throws Error(InvalidInput) when no
/// usable triangle remains or an index is out of range, and Error(TooLarge)
/// beyond options.max_triangles.
/// The vertices are numbered in the order the kept triangles first use them
/// (a triangle's corners in the input's order; a split vertex's copies
/// last), so that a triangle's corners, and its neighbours', lie near each
/// other in memory for every later stage. The triangles keep the input's
/// order. So the repaired numbering is not the input's, even on a clean
/// mesh: a per-vertex field given for the input's vertices has to be mapped
/// (by position, say).
RepairResult repair_mesh(const TriangleSoup& soup, const RepairOptions& options = {});
/// The same, releasing the soup's positions and indices as soon as they are
/// read (its notes stay): the input's 24 bytes a vertex and 12 a triangle
/// are not held beside repair's own arrays (an indexed mesh of 1.1M
/// triangles: 27 MB; a soup of three vertices a triangle, as STL files
/// give: 93 MB). The soup is left with no vertices and no triangles, also
/// when this throws. The WASM session repairs this way (its heap after
/// loading the 1.1M mesh 190 -> 185 MB, the dragon as a soup 194 -> 160
/// MB); the CLI does not: under glibc the early free moved its peak RSS by
/// -0.5 (the dragon) to +6 MB (1.1M), as the heap's layout fell.
RepairResult repair_mesh(TriangleSoup&& soup, const RepairOptions& options = {});

}  // namespace crestline
