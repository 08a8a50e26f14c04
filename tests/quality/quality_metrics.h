#pragma once
// Scoring extracted lines against a surface's true ridges and valleys
// (issue 9). Distances are in units of the mesh's mean edge length h; a line
// point "is on" a true curve within kTolerance·h.
#include <string>
#include <vector>

#include "crestline/lines/polylines.h"
#include "crestline/pipeline.h"
#include "quality_surfaces.h"

namespace crestline::quality {

constexpr double kTolerance = 2.0;  // mean edges

/// The pipeline options with pre-smoothing forced to two implicit steps of one
/// mean edge² (Table 1, step 1), also on clean meshes: the report's comparison
/// row when it runs with --presmooth 0. The defaults decide by themselves
/// (automatic_presmooth_steps).
inline PipelineOptions with_presmoothing(PipelineOptions options = {}) {
  options.presmooth.steps = 2;
  options.presmooth.time_step = 1.0;
  return options;
}

/// One line type on one surface. Excluded regions count nowhere.
struct TypeScore {
  int true_curves = 0;  // scored pieces of true curves (split at exclusions)
  double true_length = 0;
  /// Share of the true length within tolerance of an extracted line of this type (1 if no truth).
  double coverage = 1;
  double extracted_length = 0;
  /// Share of the extracted length within tolerance of a true curve of this type (1 if none extracted).
  double precision = 1;
  /// Extracted lines running along a true curve (≥ 1 h of them within
  /// tolerance), per true curve that has any: 1 is perfect.
  double fragments = 0;
  int lines = 0;  // extracted lines with any scored length
  /// Position (issue 13): the extracted length within tolerance of a true
  /// curve of this type, and the integral over it of the distance to the
  /// nearest true curve (exact, to the truth's dense polyline), in mean edges.
  double near_length = 0;
  double offset_integral = 0;
  /// Mean distance of the extracted lines from the true ones, in mean edges (0 if none near).
  double offset() const { return near_length > 0 ? offset_integral / near_length : 0.0; }
};

struct Score {
  TypeScore ridge, valley;
  bool convex = false;
  bool control = false;  // see Surface::control
  size_t vertices = 0;
  double mean_edge = 0;
  double seconds = 0;
  /// Valleys on a convex surface are all spurious.
  int spurious_valleys() const { return convex ? valley.lines : 0; }
  /// Mean distance of ridges and valleys from their true curves, in mean
  /// edges, weighted by length; −1 when no line lies near a true one.
  double offset() const {
    const double length = ridge.near_length + valley.near_length;
    return length > 0 ? (ridge.offset_integral + valley.offset_integral) / length : -1.0;
  }
};

Score score_lines(const Surface& surface, const std::vector<Polyline>& lines, double mean_edge);

/// Repairs the surface's soup, moves every vertex along its normal by
/// N(0, (noise·h)²) with a fixed seed, runs the pipeline and scores it.
Score run_case(const Surface& surface, double noise, unsigned noise_seed, const PipelineOptions& options);

/// The surface's repaired mesh with normal noise σ = noise·h (h its clean mean edge length).
Mesh noisy_mesh(const Surface& surface, double noise, unsigned noise_seed, double& h);

/// The targets: coverage ≥ 0.95, precision ≥ 0.90, fragments ≤ 1.5,
/// no spurious valleys on convex shapes. Empty if met (or a control surface), else what failed.
std::string target_failures(const Score& score);

/// Whether case `index` of a matrix whose innermost loop has `inner` values
/// (the noise levels) runs: always, unless CRESTLINE_QUALITY_SUBSET is set
/// (tests/run-sanitize.sh sets it, as ASan makes the whole matrices most of
/// its quality run); then one inner value per row, rotating, so every
/// surface, meshing and noise level still runs once or more. The unit tests'
/// longest loops (invariance over the quality surfaces, every real mesh) take
/// every other case by it (inner = 2) under the sanitizers too.
bool quality_case_runs(std::size_t index, std::size_t inner);

}  // namespace crestline::quality
