#pragma once
// Paper §5.1: smoothing extremalities with the sign-corrected cotan Laplacian
// Δe(p) = Σ_q w_pq (σ_pq e(q) − e(p)), σ_pq = sign⟨κ⃗(p), κ⃗(q)⟩, integrated
// implicitly: (M − t L_σ) e' = M e with the lumped mass matrix M.
#include <cstddef>
#include <functional>
#include <vector>

#include "crestline/curvature/extremality.h"

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

}  // namespace crestline
