#pragma once
// Sharp creases (issue 16): the third kind of line, beside the paper's
// smooth ridges and valleys. A crease is a chain of mesh edges whose dihedral
// angle exceeds a threshold: the sharp edges of CAD parts and machined
// objects, where the one-ring of a vertex spans two surfaces and the
// curvature of §3 means nothing.
//
// Two steps, so that a new crease angle is a pure selection:
//   measure_crease_angles  — a signed dihedral angle per edge, from face
//                            normals denoised by a feature-preserving filter;
//   select_creases         — threshold, chain, split, drop spurs.
#include <cstdint>
#include <functional>
#include <vector>

#include "crestline/lines/polylines.h"
#include "crestline/mesh/mesh.h"
#include "crestline/mesh/topology.h"

namespace crestline {

/// Default crease angle (degrees), the least the automatic choice takes.
/// Measured on tests/quality's CAD-like surfaces (crestline_crease_report):
/// their fillets turn by 10° per edge, the smallest true crease is 45°, and
/// the filtered dihedral of their flat parts under noise of 0.1 mean edges
/// stays below 30° away from the creases.
constexpr double kDefaultCreaseAngle = 35.0;

struct CreaseMeasureOptions {
  /// Steps of the bilateral face-normal filter before the dihedral angles are
  /// measured; 0 uses the raw face normals. Negative: automatic, see
  /// automatic_normal_filter_steps.
  int normal_filter_steps = -1;
  /// surface_noise_level(mesh, topology) where the caller has it (≥ 0; the
  /// Pipeline's constructor measured it): not measured again. Negative: measured
  /// here (where the filter steps are not 0).
  double noise_level = -1;
  /// CreaseAngles::median_edge_length where the caller has it (≥ 0; the
  /// Pipeline's frames measured it, ComponentFrames::median_edge_length):
  /// not measured again. Negative: measured here.
  double median_edge_length = -1;
};

/// The crease stage's rules for very noisy surfaces (creases.cpp: support
/// over 3 rings with non-maximum suppression across the edge, bridge walks
/// that widen their cone, redundant chains dropped, shortcuts dropped only
/// where both their ends keep two crease edges) run above this noise
/// level (surface_noise_level): normal noise σ = 0.1 mean edges measures
/// ~0.075 (0.088–0.101 on tests/quality's surfaces), 0.25 ~0.21 (0.198–0.224),
/// 0.5 0.31–0.37. Before these rules the smooth harness got false creases at
/// σ = 0.25 on anisotropic meshes (level 0.20) and many at σ = 0.5.
constexpr double kVeryNoisyCreaseLevel = 0.15;

/// Gaps in creases are bridged along edges of strong one-sided support
/// (creases.cpp, bridge_gaps) only on surfaces whose noise level is at most
/// this; the same limit gates the turn span of 4 mean edges and the bubbles
/// of select_creases. Normal noise of σ = 0.1 mean edges measures ~0.075,
/// 0.25 ~0.21, 0.5 0.31–0.37 (see kVeryNoisyCreaseLevel). Measured
/// (crestline_crease_report --seeds 3): with bridging every target is met
/// at σ = 0.1 (27 of 27 cases, 20 before it existed); at σ = 0.25 bridging
/// is what closes the gaps the normal filter leaves (coverage mean 0.67
/// before it existed, 0.97 now, with the rules that run above
/// kVeryNoisyCreaseLevel); with the limit raised to 0.5 the smooth harness
/// got 71 false crease lines at σ = 0.5 instead of 9.
constexpr double kBridgeNoiseLimit = 0.25;

/// Crease boundaries (CreaseOptions::boundaries) only on components whose
/// surface_noise_level is at most this: noisier, the crease stage finds false
/// creases on smooth surfaces, and cutting along them would break the smooth
/// lines. Measured on tests/quality's surfaces, seeds 1–3 (noise level
/// min–max; false crease lines of the crease stage on the 108 smooth cases;
/// the Pipeline's own selection, in the working frame, in brackets): σ = 0.2
/// 0.166–0.184, none; σ = 0.25 0.198–0.224 (the CAD-like surfaces
/// 0.211–0.222), 1 line (none); σ = 0.3 0.228–0.260, 8 lines (3, at levels
/// 0.228–0.238); σ = 0.5 0.305–0.368, 24. So the limit takes every mesh of
/// σ = 0.25 and none of 0.3. It was 0.15 (kVeryNoisyCreaseLevel), which left
/// the CAD-like surfaces at σ = 0.25 uncut (300–370 mean edges of ridge and
/// valley within 1 edge of their sharp edges, 0–41 now) and, on shared/meshes,
/// the twisted pentagonal tubes of smooth/cgal-knot2 (level 0.153; its
/// creases are the pentagon's corners, raw dihedral 53–75°), two box parts of
/// cad/cessna (0.153, 90° edges) and one of cad/occt-motor (0.188, 62–90°).
constexpr double kBoundaryNoiseLimit = 0.225;

/// Normal filter steps on a noisy surface (creases.cpp says why 12).
constexpr int kNoisyCreaseFilterSteps = 12;

/// 0 on a clean surface (surface_noise_level ≤ kNoisySurface): raw normals
/// are exact on a CAD tessellation; on a noisy one, enough steps that the
/// dihedral of flat parts no longer reaches the default angle (creases.cpp).
int automatic_normal_filter_steps(double noise_level);

struct CreaseAngles {
  /// Per edge (Topology::edges), the signed dihedral angle in radians between
  /// the (filtered) normals of its two triangles: positive where the surface
  /// is convex across the edge (a box's edges), negative where concave; 0 on
  /// boundary edges and where below 20° (never a crease, not computed).
  std::vector<double> angle;
  /// Per edge, radians ≥ 0: the angle between the mean raw normals of the
  /// faces around its ends on either side of it (creases.cpp); 0 where the
  /// angle is below 20°, and on surfaces noisier than kVeryNoisyCreaseLevel
  /// (read over three rings there) 0 where it is no local maximum across the
  /// edge. A crease must have both.
  std::vector<double> support;
  int normal_filter_steps = 0;  // used (the automatic choice resolved)
  /// The median |angle| over every interior edge, degrees: how much a
  /// smooth edge of this mesh turns (single precision, creases.cpp).
  double median = 0;
  /// The median length of the same edges (mesh units; single precision),
  /// or CreaseMeasureOptions::median_edge_length where given.
  double median_edge_length = 0;
  /// surface_noise_level of the mesh (not measured, 0, when the filter steps
  /// were given as 0): bridging (creases.cpp) only up to kBridgeNoiseLimit.
  double noise_level = 0;
  /// Whether noise_level was measured (here, or filled in by the caller).
  bool noise_measured = false;
};

/// The automatic crease angle (degrees): kDefaultCreaseAngle, raised to a
/// multiple of the median dihedral on meshes whose ordinary edges turn a lot
/// (scans), so that their fine folds do not count as creases (creases.cpp).
double automatic_crease_angle(const CreaseAngles& angles);

/// Linear in the mesh size times the filter steps. progress, if set, is
/// called on the calling thread with rising fractions below 1 (after the
/// noise level, each filter step and each block of 65,536 edges) and may
/// throw to abandon the measure.
CreaseAngles measure_crease_angles(const Mesh& mesh, const Topology& topology, const CreaseMeasureOptions& options,
                                   const std::function<void(double)>& progress = {});

struct CreaseOptions {
  /// Edges whose |dihedral angle| is at least this (degrees) are crease
  /// edges. Negative: automatic_crease_angle. Below 20° it acts as 20°
  /// (smaller angles are not measured). Angles are unitless, so the choice
  /// does not depend on the model's scale.
  double angle = -1;
  /// A chain turning by more than this (degrees) between two consecutive
  /// edges is split there, as at a corner where three or more creases meet.
  double max_turn = 60.0;
  /// Steps of the normal filter (measure_crease_angles); negative automatic.
  int normal_filter_steps = -1;
  /// The smooth lines stop at the creases (Pipeline, mesh/cut.h): the mesh is
  /// cut open along the creases of the automatic angle before pre-smoothing,
  /// so curvature, both smoothings and the tracer's boundary band treat them
  /// as boundaries. Independent of `angle`, which stays a selection; only on
  /// components no noisier than kBoundaryNoiseLimit. On by default: smooth
  /// meshes have no crease at the automatic angle, so only CAD-like parts
  /// change (README, "Smooth lines stop at creases").
  bool boundaries = true;
};

struct CreaseResult {
  /// Type LineType::Crease, points at the input mesh's vertices; `convex`
  /// tells the sign; `curvature` per point is |angle| / mean edge length (the
  /// turn across the crease, spread over one edge), so `strength` is
  /// ∑ |angle|·length / mean edge, unitless like the smooth lines'.
  std::vector<Polyline> lines;
  /// The crease edges the lines run along (after spurs were dropped).
  std::vector<uint32_t> edges;
  /// A vertex of each line (its first point's), e.g. to find its component.
  std::vector<uint32_t> line_vertex;
  double angle = 0;  // degrees, the threshold used
};

/// Selects the edges at or above the angle, chains them through vertices
/// where exactly two crease edges meet, splits chains at corners (three or
/// more), at turns sharper than max_turn and where the sign changes, and drops
/// short weak spurs (creases.cpp). Reads only `angles`: no curvature.
/// checkpoint, if set, is called on the calling thread between the
/// selection's rounds and every 256 free ends its gap bridging walks from
/// (a noisy scan's selection runs for tenths of a second), and may throw to
/// abandon it.
CreaseResult select_creases(const Mesh& mesh, const Topology& topology, const CreaseAngles& angles,
                            const CreaseOptions& options, double mean_edge_length,
                            const std::function<void()>& checkpoint = {});

}  // namespace crestline
