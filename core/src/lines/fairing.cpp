#include "crestline/lines/fairing.h"

#include "crestline/numerics/parallel.h"

namespace crestline {
namespace {

// Lines a thread takes at least: a line costs about its length times the
// iterations, and most are short.
constexpr size_t kLinesPerThread = 64;

// Discrete curve Laplacian ½(x_{i−1} + x_{i+1}) − x_i; zero at fixed ends.
// The ends apart, so that the interior needs no wrap-around index (n ≥ 3).
void laplacian(const std::vector<Vec3>& x, bool closed, std::vector<Vec3>& out) {
  const size_t n = x.size();
  out.resize(n);
  for (size_t i = 1; i + 1 < n; ++i) out[i] = 0.5 * (x[i - 1] + x[i + 1]) - x[i];
  if (closed) {
    out[0] = 0.5 * (x[n - 1] + x[1]) - x[0];
    out[n - 1] = 0.5 * (x[n - 2] + x[0]) - x[n - 1];
  } else {
    out[0] = out[n - 1] = Vec3::Zero();
  }
}

}  // namespace

std::vector<Polyline> fair_polylines(const std::vector<Polyline>& lines, double mean_edge_length,
                                     const FairingOptions& options) {
  std::vector<Polyline> out = lines;
  const double bound = options.hausdorff_bound * mean_edge_length;
  if (!(bound > 0) || options.iterations <= 0) return out;
  // Lines are faired independently, each writing only itself.
  parallel_for(
      out.size(),
      [&](size_t begin, size_t end) {
        std::vector<Vec3> lap, bilap;
        for (size_t l = begin; l < end; ++l) {
          Polyline& line = out[l];
          const size_t n = line.points.size();
          if (n < (line.closed ? 4u : 3u)) continue;
          const std::vector<Vec3> original = line.points;
          for (int it = 0; it < options.iterations; ++it) {
            // Explicit bi-Laplacian flow x ← x − λ Δ²x (stable for λ < ½ with this
            // Laplacian); unlike Δ it does not shrink curves towards their chords.
            laplacian(line.points, line.closed, lap);
            laplacian(lap, line.closed, bilap);
            for (size_t i = 0; i < n; ++i) {
              if (!line.closed && (i == 0 || i + 1 == n)) continue;
              Vec3 p = line.points[i] - 0.25 * bilap[i];
              // Each vertex stays within `bound` of where it was, so every point of
              // the faired polyline is within `bound` of the matching point of the
              // original (same edge parameter) and vice versa: Hausdorff ≤ bound.
              const Vec3 moved = p - original[i];
              const double d = moved.norm();
              if (d > bound) p = original[i] + moved * (bound / d);
              line.points[i] = p;
            }
          }
          // The strength stays that of the traced line (it measures the surface,
          // not the drawing); only the length follows the faired points.
          const double strength = line.strength;
          measure_polyline(line);
          line.strength = strength;
        }
      },
      kLinesPerThread);
  return out;
}

}  // namespace crestline
