#pragma once
// The paper's Table 1 as one object that keeps every stage's result, so a
// changed parameter re-runs only the stages after it:
//   mesh ─ presmooth ─► curvature ─► extremality ─► regularity ─ smoothing ─►
//   tracing ─► singular ─► polylines ─► fairing ─► filter
// (Fairing runs on every line before filtering so that re-thresholding is a
// pure selection: instant.) Beside them, on the input mesh and depending on
// nothing else, the sharp creases (lines/creases.h): their stage is
// reported last and runs only when its own options changed (its work is
// done first, while the input's adjacency and crease angles are at hand). Unless CreaseOptions::boundaries is
// off, the creases of the automatic angle are measured first and the smooth
// stages run on the mesh cut open along them (mesh/cut.h); without such
// creases they run on the input mesh itself, exactly as without the option.
//
// Every stage computes in the working frame of mesh/frame.h: each connected
// component centred on its bounding box and measured in its own mean edge
// length. So the lines do not depend on where the model sits or on its unit
// (translation and uniform scale change only round-off), and a second object
// in the file changes neither the first one's noise level, pre-smoothing,
// smoothing, joining nor automatic threshold. What the user sees is mapped
// back: lines(), all_lines(), surface() and the lengths in stats() are in the
// input's coordinates; the per-stage fields (curvature(), extremality(),
// segments(), …) stay in the working frame (lengths in mean edges of their
// component, curvatures in 1 / mean edge).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "crestline/curvature/extremality_smoothing.h"
#include "crestline/curvature/shape_operator_averaging.h"
#include "crestline/lines/clearance.h"
#include "crestline/lines/creases.h"
#include "crestline/lines/fairing.h"
#include "crestline/lines/filter.h"
#include "crestline/lines/singular.h"
#include "crestline/mesh/cut.h"
#include "crestline/mesh/frame.h"
#include "crestline/mesh/presmooth.h"

namespace crestline {

struct PipelineOptions {
  PresmoothOptions presmooth;
  ShapeOperatorAveragingOptions averaging;
  /// smoothing.frozen_boundary_rings is set from trace.boundary_rings.
  ExtremalitySmoothingOptions smoothing;
  TraceOptions trace;
  FairingOptions fairing;
  FilterOptions filter;
  CreaseOptions creases;
  /// How far the smooth lines stop from the boundary creases (only where the
  /// mesh was cut along creases).
  ClearanceOptions clearance;
};

enum class Stage : int {
  Presmooth = 0,
  Curvature,
  Extremality,
  Regularity,
  Smoothing,
  Tracing,
  Singular,
  Polylines,
  Fairing,
  Filter,
  Creases,  // independent of the others; runs (and reports) first, only when its options change
  Count
};

const char* stage_name(Stage stage);  // "presmooth", "curvature", …

/// Called between and inside stages; return false to cancel (run() then
/// throws Cancelled and the pipeline stays valid up to the last finished stage).
/// During the smoothing's solves the working mesh's positions and edges are
/// released (Pipeline::run): the callback must not read the Pipeline.
using ProgressCallback = std::function<bool(Stage stage, double fraction)>;

struct Cancelled : std::exception {
  const char* what() const noexcept override { return "cancelled"; }
};

struct PipelineStats {
  size_t vertices = 0, triangles = 0;
  size_t singular_max = 0, singular_min = 0;
  size_t ridges = 0, valleys = 0;  // kept lines
  double ridge_length = 0, valley_length = 0;
  size_t creases = 0;
  double crease_length = 0;
  double crease_angle = 0;  // degrees, the threshold used
  size_t components = 0;    // connected components, each processed on its own
  // Per component, reported for the largest one (most triangles):
  double threshold = 0;                                 // used by the filter
  double noise_level = 0;                               // surface_noise_level of the input
  int presmooth_steps = 0;                              // used (the automatic choice resolved)
  double mean_edge_length = 0;                          // over the whole input, in its units
  size_t smoothing_iterations = 0;                      // the smoothing's solver iterations, all steps
  double seconds[static_cast<int>(Stage::Count)] = {};  // last run time per stage
  // Around the stages: the Pipeline constructor times itself as topology
  // (the adjacency unless repair_mesh's is given, the component frames and
  // noise levels); the caller fills in reading, repair and writing (0 where
  // it did none).
  double read_seconds = 0, repair_seconds = 0, topology_seconds = 0, write_seconds = 0;
};

class Pipeline {
 public:
  /// Takes a repaired mesh (see repair_mesh).
  explicit Pipeline(Mesh mesh);
  /// The same with the mesh's adjacency, build_topology(mesh), as
  /// repair_mesh returns it (not built again).
  Pipeline(Mesh mesh, Topology topology);
  /// The same with the mesh's components too, as repair_mesh returns them
  /// (not found again).
  Pipeline(Mesh mesh, Topology topology, VertexComponents components);

  /// Stores options and marks the first stage whose options changed (and
  /// everything after it) for recomputation. Cheap.
  void set_options(const PipelineOptions& options);
  const PipelineOptions& options() const { return options_; }

  /// Recomputes the stages marked dirty.
  void run(const ProgressCallback& progress = {});

  /// A run releases its triangles (the working frame's copy or the crease
  /// cut has them); rebuilt here (the same) when asked for.
  const Mesh& input_mesh() const { return input(); }
  /// The mesh after optional pre-smoothing, in the input's coordinates.
  /// Where pre-smoothed, made from working_surface() when asked for (a run
  /// releases it).
  const Mesh& surface() const;
  /// The same in the working frame: all curvature lives on it, and segments()
  /// lie on its edges. Its vertices are the input's, followed by one copy
  /// per extra side of each vertex on a boundary crease (working_cut()); the
  /// per-vertex fields (curvature(), extremality()) have its vertex count.
  const Mesh& working_surface() const { return presmoothed_ ? working_surface_ : smooth_input(); }
  /// Its vertex_component is empty where there is one component (component()).
  const ComponentFrames& frames() const { return frames_; }
  /// The input mesh's adjacency. While a crease cut serves the smooth stages
  /// a run releases it before them; rebuilt here (the same) when asked for.
  const Topology& topology() const;
  /// working_surface()'s adjacency: topology() unless creases cut the mesh.
  /// A run releases its triangle lists after the curvature stage, the last
  /// to read them (release_triangle_lists); restored here when asked for.
  const Topology& working_topology() const;
  /// The cut along the boundary creases (no copies when there is none).
  const CutMesh& working_cut() const { return cut_; }
  /// The crease edges (into topology().edges, ascending) the smooth stages
  /// treat as boundaries; empty when CreaseOptions::boundaries is off.
  const std::vector<uint32_t>& boundary_creases() const { return boundary_edges_; }
  /// The per-stage fields; a run releases those it is about to recompute, so
  /// they are empty after a run cancelled before their stage finished.
  /// curvature() keeps what the stages after extremality read: its
  /// vertex_normals and star_area are empty.
  const Curvature& curvature() const { return curvature_; }
  const Extremality& raw_extremality() const { return raw_extremality_; }
  const Extremality& extremality() const { return extremality_; }  // after smoothing
  const Regularity& regularity() const { return regularity_; }
  /// The line graphs: the regular triangles' segments (tracing) with the
  /// singular triangles' added (the singular stage), and the singular counts.
  /// Released when a run re-traces (so a re-smoothing does not hold them
  /// through its solves): empty after a run cancelled before the singular stage.
  /// Their edge_node and excluded, read only by the singular stage, are empty.
  const SingularResult& segments() const { return singular_; }
  /// Every joined, faired line, before the threshold filter (input's coordinates).
  const std::vector<Polyline>& all_lines() const { return faired_; }
  const FilterResult& filtered() const { return filtered_; }
  /// The lines that pass the filter, ridges first then valleys.
  std::vector<Polyline> lines() const;
  /// The sharp creases of the input mesh (type LineType::Crease).
  const std::vector<Polyline>& creases() const { return creases_.lines; }
  const CreaseResult& crease_result() const { return creases_; }
  /// Its angle and support are empty after a run (measured again while a
  /// crease cut serves, else kept compact; either way the same when needed).
  const CreaseAngles& crease_angles() const { return crease_angles_; }
  /// lines() followed by creases(): what the writers draw.
  std::vector<Polyline> all_kinds() const;
  PipelineStats stats() const;

 private:
  void mark_dirty(Stage from);
  const Mesh& input() const;
  std::vector<Triangle> input_triangles() const;
  const Mesh& local_input();
  void release_local_input();
  // progress (fractions of the measure), if set, may throw to abandon it.
  void measure_creases(const std::function<void(double)>& progress = {});
  void compact_crease_angles();
  struct BoundarySelection {
    std::optional<std::vector<uint32_t>> changed;  // the boundary creases, when they changed
    // The selection when it is also the creases' (the automatic angle,
    // creases due), so that the creases stage need not select again.
    std::optional<CreaseResult> automatic;
  };
  BoundarySelection select_boundaries(const std::function<void(double)>& measure_progress);
  // Cuts the input along the boundary creases; takes over its working-frame
  // mesh and adjacency when the cut splits any vertex.
  void measure_boundary_segments(const Topology& topology, const Mesh& local);
  void cut_along_boundaries(std::vector<uint32_t> edges);
  // The creases stage's work; returns its seconds.
  double select_crease_lines(std::optional<CreaseResult> automatic,
                             const std::function<void(double)>& measure_progress);
  const Mesh& smooth_input() const { return cut_active_ ? cut_.mesh : local_input_; }
  // smooth_input()'s positions and smooth_topology()'s edges, which the
  // smoothing's solves do not read: released through them, then restored
  // from input_, the frames and the triangles (the same values).
  void release_smooth_geometry();
  void restore_smooth_geometry();
  // working_topology() as it stands (its triangle lists perhaps released).
  Topology& smooth_topology() { return cut_active_ ? cut_topology_ : topology_; }

  PipelineOptions options_;
  Stage first_dirty_ = Stage::Presmooth;
  mutable Mesh input_;  // its triangles released by a run (input())
  ComponentFrames frames_;
  Mesh local_input_;  // input_ in the working frame; released while a cut serves (local_input())
  bool local_input_valid_ = false;
  size_t released_edges_ = 0;  // smooth_topology()'s edge count while its edges are released
  Mesh working_surface_;       // pre-smoothed only; else local_input_ serves
  mutable Mesh surface_;       // pre-smoothed only (see surface()); else input_ serves
  mutable Topology topology_;  // see topology()
  mutable bool topology_valid_ = false;
  double mean_edge_ = 0;
  std::vector<double> noise_levels_;  // per component
  std::vector<int> presmooth_steps_;  // per component
  bool presmoothed_ = false;
  Curvature curvature_;
  Extremality raw_extremality_;
  SmoothedExtremality extremality_;
  Regularity regularity_;
  TraceResult traced_;
  SingularResult singular_;
  std::vector<Polyline> joined_;          // working frame
  std::vector<uint32_t> line_component_;  // of each joined line
  std::vector<Polyline> faired_local_;
  std::vector<Polyline> faired_;  // input's coordinates
  FilterResult filtered_;
  bool creases_dirty_ = true;
  bool crease_angles_valid_ = false;
  bool boundaries_dirty_ = true;
  std::vector<uint32_t> boundary_edges_;
  // boundary_edges_ in the working frame, with the mean edge at their ends,
  // for the clearance (the cut renumbers the edges; its mesh keeps the
  // input's positions, which the lines are placed on).
  std::vector<CreaseSegment> boundary_segments_;
  bool cut_active_ = false;
  CutMesh cut_;                    // of local_input_, in the working frame
  mutable Topology cut_topology_;  // see working_topology()
  CreaseAngles crease_angles_;
  // crease_angles_'s angle and support where either is not 0 (compact_crease_angles).
  struct CreaseEdge {
    uint32_t edge;
    double angle, support;
  };
  std::vector<CreaseEdge> crease_edges_;
  size_t crease_edge_count_ = 0;
  bool crease_angles_compact_ = false;
  CreaseResult creases_;
  double seconds_[static_cast<int>(Stage::Count)] = {};
  double topology_seconds_ = 0;
};

}  // namespace crestline
