#pragma once
// Larger benchmark meshes generated at run time from a real one, so nothing
// big is committed and every machine measures the same triangles.
#include "crestline/mesh/mesh.h"

namespace crestline::bench {

/// 1-to-4 subdivision: every edge gets a vertex at the midpoint of the cubic
/// Hermite curve whose end tangents are the edge projected into the tangent
/// planes of its ends (as in PN triangles). This small deterministic
/// displacement off the flat triangles keeps the curvature of the original
/// surface instead of concentrating it on the old edges. Takes a repaired
/// mesh; returns a soup with 4× the triangles, for repair_mesh like any input.
TriangleSoup subdivide(const Mesh& mesh);

/// A noisy scan's stand-in: every vertex moved along its area-weighted
/// normal by a normal deviate of `sigma` mean edge lengths (mt19937_64 with
/// `seed` and Box–Muller, so every standard library draws the same).
/// Takes a repaired mesh; returns its soup with the moved positions.
TriangleSoup add_normal_noise(const Mesh& mesh, double sigma, uint64_t seed);

}  // namespace crestline::bench
