#pragma once
// CAD-like surfaces with known sharp edges, for the crease part of the
// quality harness (issue 16). Each is tessellated the way CAD exporters do:
// every face meshed on its own, with vertices on the sharp edges, welded by
// position (repair_mesh). Flat caps are meshed in rings around a centre
// (valence about 6 inside), walls as grids with the chosen diagonals.
#include <string>
#include <vector>

#include "crestline/lines/creases.h"
#include "crestline/lines/polylines.h"
#include "crestline/mesh/mesh.h"
#include "crestline/pipeline.h"
#include "quality_surfaces.h"

namespace crestline::quality {

/// One true sharp edge between corners (or a closed loop), densely sampled.
struct SharpEdge {
  std::vector<Vec3> points;  // spacing far below an edge length
  bool closed = false;
  bool convex = true;
  double angle = 0;  // dihedral, degrees
};

struct CadSurface {
  std::string name;
  TriangleSoup soup;
  std::vector<SharpEdge> edges;
};

struct CadParams {
  double edge = 0.05;  // target edge length (the shapes are about 2 units across)
  Triangulation triangulation = Triangulation::Irregular;
  unsigned seed = 1;
};

/// A 2 × 2 × 1 box whose two vertical edges at x = +1 are filleted (radius
/// 0.3, 6 edges) and every other edge sharp: 6 sharp edges between corners.
CadSurface filleted_box(const CadParams& p);
/// A cylinder (radius 1, height 1.2) with a 45° chamfer of 0.25 at the top:
/// three sharp circles (90° at the bottom, 45° on either side of the chamfer).
CadSurface chamfered_cylinder(const CadParams& p);
/// A pentagon with one re-entrant corner, extruded by 1: 15 sharp edges, one
/// of them concave.
CadSurface notched_prism(const CadParams& p);

std::vector<std::string> cad_surface_names();
CadSurface make_cad_surface(const std::string& name, const CadParams& p);

/// One case of the harness: a surface, its repaired mesh with normal noise
/// σ = noise·h (h the clean mesh's mean edge length), and h.
struct CadCase {
  CadSurface surface;
  Mesh clean, mesh;
  double h = 0;
};
CadCase make_cad_case(const std::string& name, Triangulation t, double noise, unsigned noise_seed,
                      CadParams params = {});

/// The crease stage alone (measure, then select) on a mesh; the measured
/// angles in `angles` if given.
CreaseResult find_creases(const Mesh& mesh, const Topology& topology, const CreaseOptions& options, double h,
                          CreaseAngles* angles = nullptr);

/// The creases found on a smooth surface of the ridge/valley harness (none expected).
CreaseResult smooth_surface_creases(const std::string& name, Triangulation t, double noise,
                                    const CreaseOptions& options = {}, CreaseAngles* angles = nullptr);

/// The true sharp edges as crease lines (type Crease, their sign).
std::vector<Polyline> sharp_edges_as_lines(const CadSurface& surface);

/// Ridges and valleys beside sharp edges, in mean edges h: how much of their
/// length lies within `radius` h of one of `sharp` (what crease boundaries
/// should bring to ~0), and their whole length. Crease lines in `lines` are
/// skipped. Samples within `away_radius` h of one of `away` (the creases
/// found) do not count as near: what is left lies in the creases' gaps.
struct SmoothNearCreases {
  double near_length = 0;
  double length = 0;
  int lines = 0;
};
SmoothNearCreases smooth_lines_near(const std::vector<Polyline>& sharp, const std::vector<Polyline>& lines, double h,
                                    double radius = 1.0, const std::vector<Polyline>& away = {},
                                    double away_radius = 2.0);

/// Runs the whole pipeline on the case's noisy mesh.
Pipeline run_cad_pipeline(const CadCase& c, const PipelineOptions& options = {});

/// Scores of the crease lines of one surface. Distances in mean edges h.
struct CreaseScore {
  int true_edges = 0;
  double true_length = 0;
  /// Share of the true sharp edges' length within 1 h of a crease line.
  double coverage = 0;
  double extracted_length = 0;
  /// Share of the crease lines' length within 1 h of a true sharp edge (1 if none).
  double precision = 1;
  /// Crease lines running along a true edge (≥ 3 h of them within 1 h), per
  /// true edge: 1 is perfect.
  double fragments = 0;
  int lines = 0;
  int wrong_sign = 0;  // lines along a true edge whose convex flag differs from it
};

CreaseScore score_creases(const CadSurface& surface, const std::vector<Polyline>& creases, double mean_edge);

/// Issue 16's targets: coverage ≥ 0.98, precision ≥ 0.95, fragments ≤ 1.2,
/// every sign right. Empty if met, else what failed.
std::string crease_target_failures(const CreaseScore& score);

}  // namespace crestline::quality
