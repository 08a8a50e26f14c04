#include "crestline/lines/fairing.h"

#include <cmath>

#include "crestline/numerics/parallel.h"

namespace crestline {
namespace {

// A squared length below which a length is surely at most `bound`: bound²
// less a relative margin of 2⁻⁵⁰, more than the roundings of bound² and of
// the product (2⁻⁵³ each), so that s < clear_below(bound) implies
// sqrt(s) ≤ bound exactly (the square root is correctly rounded and
// monotonic, `bound` representable). 0 (no shortcut) where bound² is not
// a normal number far from the range's ends.
double clear_below(double bound) {
  const double squared = bound * bound;
  return squared >= 0x1p-1000 && squared <= 0x1p1000 ? squared * (1 - 0x1p-50) : 0;
}

// Lines a thread takes at least: a line costs about its length times the
// iterations, and most are short.
constexpr size_t kLinesPerThread = 64;

// One step of the explicit bi-Laplacian flow x ← x − ¼ Δ²x (stable for
// λ < ½ with this Laplacian; unlike Δ it does not shrink curves towards their
// chords), in place, with the Hausdorff clamp. Δx = ½(x_{i−1} + x_{i+1}) − x_i
// is zero at fixed ends. It is computed one point ahead of the update, from
// points not yet moved, in a window of three: the same sums, bit for bit, as
// a pass filling an array Δx and a second one filling Δ²x, without their
// memory traffic. A closed line's Δx at its last point and at its first is
// taken before the first point moves. Needs n ≥ 3 (open) or n ≥ 4 (closed).
// `clear`: clear_below(bound).
void fair_step(std::vector<Vec3>& x, const std::vector<Vec3>& original, bool closed, double bound, double clear) {
  const size_t n = x.size();
  auto laplacian = [&x](size_t i, size_t prev, size_t next) -> Vec3 { return 0.5 * (x[prev] + x[next]) - x[i]; };
  auto move = [&](size_t i, const Vec3& bilaplacian) {
    Vec3 p = x[i] - 0.25 * bilaplacian;
    // Each vertex stays within `bound` of where it was, so every point of
    // the faired polyline is within `bound` of the matching point of the
    // original (same edge parameter) and vice versa: Hausdorff ≤ bound.
    // The distance (norm() is the square root of squaredNorm()) is taken
    // only where the squared one is not clearly below bound²: nearly every
    // point moves far less.
    const Vec3 moved = p - original[i];
    const double squared = moved.squaredNorm();
    if (!(squared < clear)) {
      const double d = std::sqrt(squared);
      if (d > bound) p = original[i] + moved * (bound / d);
    }
    x[i] = p;
  };
  if (closed) {
    const Vec3 last = laplacian(n - 1, n - 2, 0), first = laplacian(0, n - 1, 1);
    Vec3 prev = last, here = first;
    for (size_t i = 0; i < n; ++i) {
      const Vec3 next = i + 2 < n ? laplacian(i + 1, i, i + 2) : i + 2 == n ? last : first;
      move(i, 0.5 * (prev + next) - here);
      prev = here, here = next;
    }
  } else {
    Vec3 prev = Vec3::Zero(), here = laplacian(1, 0, 2);
    for (size_t i = 1; i + 1 < n; ++i) {
      const Vec3 next = i + 2 < n ? laplacian(i + 1, i, i + 2) : Vec3::Zero();
      move(i, 0.5 * (prev + next) - here);
      prev = here, here = next;
    }
  }
}

}  // namespace

std::vector<Polyline> fair_polylines(const std::vector<Polyline>& lines, double mean_edge_length,
                                     const FairingOptions& options) {
  std::vector<Polyline> out = lines;
  const double bound = options.hausdorff_bound * mean_edge_length;
  if (!(bound > 0) || options.iterations <= 0) return out;
  const double clear = clear_below(bound);
  // Lines are faired independently, each writing only itself.
  parallel_for(
      out.size(),
      [&](size_t begin, size_t end) {
        for (size_t l = begin; l < end; ++l) {
          Polyline& line = out[l];
          const size_t n = line.points.size();
          if (n < (line.closed ? 4u : 3u)) continue;
          const std::vector<Vec3> original = line.points;
          for (int it = 0; it < options.iterations; ++it) fair_step(line.points, original, line.closed, bound, clear);
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
