#pragma once
// Paper §5.1: smoothing extremalities with the sign-corrected cotan Laplacian
// Δe(p) = Σ_q w_pq (σ_pq e(q) − e(p)), σ_pq = sign⟨κ⃗(p), κ⃗(q)⟩, integrated
// implicitly: (M − t L_σ) e' = M e with the lumped mass matrix M.
#include <cstddef>
#include <functional>
#include <vector>

#include "crestline/curvature/extremality.h"
#include "crestline/numerics/paired_cg.h"

namespace crestline {

struct ExtremalitySmoothingOptions {
  /// Implicit steps; 0 returns the input unchanged. The paper never needs more than 5.
  int steps = 3;
  /// Time step per step in units of mean edge length squared (unitless).
  double time_step = 1.0;
  /// Optional per-vertex strength (inhomogeneous smoothing, paper §6): the
  /// time step is scaled by it, edge-wise by the mean of its two ends. Empty
  /// means 1 everywhere; 0 freezes a region.
  std::vector<double> vertex_weights;
  /// Vertices fewer than this many rings from the mesh boundary keep their
  /// extremality (weight 0): their curvature sees half a neighbourhood and
  /// must not diffuse into the interior. The Pipeline sets it to
  /// TraceOptions::boundary_rings, the band the tracer leaves out.
  int frozen_boundary_rings = 0;
};

/// The smoothed fields, and what solving for them took.
struct SmoothedExtremality : Extremality {
  /// Conjugate-gradient iterations over all steps, both fields in lockstep
  /// counting once (numerics/paired_cg.h); where the paired solve gives up,
  /// the iterations it spent (the fallback's own are not counted). The same
  /// for any thread count.
  size_t solver_iterations = 0;
};

/// Independent of the initial sign choice of the directions: flipping
/// dir(p) and e(p) at any vertices before smoothing flips exactly those
/// values after it. progress, if set, is called with the fraction done
/// (0–1) after every solver iteration; it may throw to cancel.
SmoothedExtremality smooth_extremality(const Mesh& mesh, const Topology& topology, const Curvature& curvature,
                                       const Extremality& extremality, const ExtremalitySmoothingOptions& options,
                                       const std::function<void(double fraction)>& progress = {});

/// smooth_extremality in two phases, for a caller that releases the mesh's
/// positions and edges while the solves run (the Pipeline: 24 bytes per
/// triangle less at the solves' peak). The first reads the mesh, its
/// adjacency and the curvature and builds both fields' system; the second
/// reads only that system and the values to smooth. smooth_extremality is
/// the two in turn, with smooth_extremality_unpaired where the second gives up.
struct ExtremalitySmoothingSystem {
  /// Both fields' M − t L_σ (numerics/paired_cg.h); no rows where the
  /// paired solve does not apply (more vertices than a column can index).
  SignedPairMatrix matrix;
  std::vector<double> vertex_mass;  // M
  int steps = 0;                    // 0: no smoothing (the values are returned as they are)
};
/// The first phase; progress (the stage's fractions, as smooth_extremality
/// reports them) may throw to cancel. Throws Error on invalid weights.
ExtremalitySmoothingSystem extremality_smoothing_system(const Mesh& mesh, const Topology& topology,
                                                        const Curvature& curvature,
                                                        const ExtremalitySmoothingOptions& options,
                                                        const std::function<void(double fraction)>& progress = {});

struct PairedSmoothing {
  SmoothedExtremality smoothed;
  /// False where the paired solve gave up or does not apply: smoothed then
  /// holds only the iterations spent, and smooth_extremality_unpaired, given
  /// them, finishes the smoothing.
  bool converged = false;
};
/// The second phase: the solver's set-up (which takes the system's matrix)
/// and the solves. progress continues the first phase's fractions.
PairedSmoothing solve_extremality_smoothing(ExtremalitySmoothingSystem system, const Extremality& extremality,
                                            const std::function<void(double fraction)>& progress = {});

/// Each field alone with SpdSolver (sparse_solver.h), which factorizes the
/// ill-conditioned systems the paired solve gives up on; the result counts
/// `iterations_spent` as its solver_iterations.
SmoothedExtremality smooth_extremality_unpaired(const Mesh& mesh, const Topology& topology, const Curvature& curvature,
                                                const Extremality& extremality,
                                                const ExtremalitySmoothingOptions& options, size_t iterations_spent);

}  // namespace crestline
