#include "quality_metrics.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"
#include "point_grid.h"

namespace crestline::quality {
namespace {

// The scored pieces of one type's true curves: maximal runs of samples
// outside the excluded regions, at least 3 h long.
struct TruthSample {
  Vec3 point;
  double length;
  int piece;  // −1: excluded
};
std::vector<TruthSample> truth_samples(const Surface& s, LineType type, double h, int& pieces) {
  std::vector<TruthSample> out;
  pieces = 0;
  for (const TrueCurve& c : s.curves) {
    if (c.type != type) continue;
    const size_t n = c.points.size();
    std::vector<uint8_t> excluded(n);
    for (size_t i = 0; i < n; ++i) excluded[i] = s.excluded(c.points[i], h);
    // A closed curve is walked from an excluded sample, if any, so that a
    // run never wraps around.
    size_t start = 0;
    if (c.closed)
      for (size_t i = 0; i < n; ++i)
        if (excluded[i]) {
          start = i;
          break;
        }
    std::vector<TruthSample> run;
    auto flush = [&] {
      double len = 0;
      for (const TruthSample& t : run) len += t.length;
      const int id = len >= 3 * h ? pieces++ : -1;
      for (TruthSample& t : run) t.piece = id, out.push_back(t);
      run.clear();
    };
    for (size_t k = 0; k < n; ++k) {
      const size_t i = (start + k) % n;
      const size_t next = (i + 1) % n;
      const double len = (c.closed || i + 1 < n) ? (c.points[next] - c.points[i]).norm() : 0.0;
      if (excluded[i]) {
        flush();
        out.push_back({c.points[i], len, -1});
      } else {
        run.push_back({c.points[i], len, 0});
      }
    }
    flush();
  }
  return out;
}

// The segments of one type's true curves, for exact distances.
class TruthSegments {
 public:
  TruthSegments(const Surface& s, LineType type, double reach) : reach_(reach), grid_(reach) {
    for (const TrueCurve& c : s.curves) {
      if (c.type != type) continue;
      const size_t n = c.points.size(), count = c.closed ? n : n - 1;
      for (size_t i = 0; i < count; ++i) {
        const Vec3 &a = c.points[i], &b = c.points[(i + 1) % n];
        grid_.add(0.5 * (a + b), static_cast<uint32_t>(segments_.size()));
        segments_.push_back({a, b});
      }
    }
  }
  /// Distance from p to the nearest segment whose midpoint lies within
  /// `reach` (far beyond the tolerance); +∞ if none.
  double distance(const Vec3& p) const {
    double best = std::numeric_limits<double>::infinity();
    grid_.near(p, reach_, [&](uint32_t i) {
      const Vec3 &a = segments_[i][0], &b = segments_[i][1], d = b - a;
      const double t = std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
      best = std::min(best, (a + t * d - p).norm());
    });
    return best;
  }

 private:
  double reach_;
  PointGrid grid_;
  std::vector<std::array<Vec3, 2>> segments_;
};

TypeScore score_type(const Surface& s, LineType type, const std::vector<Polyline>& lines, double h) {
  TypeScore score;
  const double tol = kTolerance * h;
  const std::vector<TruthSample> truth = truth_samples(s, type, h, score.true_curves);
  PointGrid truth_grid(tol);
  for (uint32_t i = 0; i < truth.size(); ++i) truth_grid.add(truth[i].point, i);
  // Truth segments are far shorter than h: a reach of tol + h finds the
  // nearest one of every point within tol.
  const TruthSegments segments(s, type, tol + h);

  PointGrid line_grid(tol);
  // (line, piece) → extracted length of the line running along the piece.
  std::map<std::pair<uint32_t, int>, double> along;
  double near_length = 0;
  for (uint32_t l = 0; l < lines.size(); ++l) {
    if (lines[l].type != type) continue;
    bool scored = false;
    for (const Sample& q : resample(lines[l], 0.25 * h)) {
      line_grid.add(q.point, l);
      if (s.excluded(q.point, h)) continue;
      scored = true;
      score.extracted_length += q.length;
      bool near = false;
      std::map<int, bool> pieces;
      truth_grid.near(q.point, tol, [&](uint32_t i) {
        near = true;
        if (truth[i].piece >= 0) pieces[truth[i].piece] = true;
      });
      if (near) {
        near_length += q.length;
        score.offset_integral += q.length * segments.distance(q.point) / h;
      }
      for (const auto& [piece, yes] : pieces) along[{l, piece}] += q.length;
    }
    score.lines += scored;
  }
  score.near_length = near_length;
  if (score.extracted_length > 0) score.precision = near_length / score.extracted_length;

  double covered = 0;
  for (const TruthSample& t : truth) {
    if (t.piece < 0) continue;
    score.true_length += t.length;
    if (line_grid.any_near(t.point, tol)) covered += t.length;
  }
  if (score.true_length > 0) score.coverage = covered / score.true_length;

  std::vector<int> per_piece(score.true_curves, 0);
  for (const auto& [key, length] : along)
    if (length >= h) ++per_piece[key.second];
  int touched = 0, total = 0;
  for (int c : per_piece)
    if (c > 0) ++touched, total += c;
  score.fragments = touched ? static_cast<double>(total) / touched : 0.0;
  return score;
}

}  // namespace

Score score_lines(const Surface& surface, const std::vector<Polyline>& lines, double mean_edge) {
  Score s;
  s.convex = surface.convex;
  s.control = surface.control;
  s.mean_edge = mean_edge;
  s.ridge = score_type(surface, LineType::Ridge, lines, mean_edge);
  s.valley = score_type(surface, LineType::Valley, lines, mean_edge);
  return s;
}

Mesh noisy_mesh(const Surface& surface, double noise, unsigned noise_seed, double& h) {
  Mesh mesh = testing::repaired_in_input_order(surface.soup);
  h = mean_edge_length(mesh);
  if (noise > 0) testing::add_normal_noise(mesh, noise * h, noise_seed);
  return mesh;
}

Score run_case(const Surface& surface, double noise, unsigned noise_seed, const PipelineOptions& options) {
  double h = 0;
  Mesh mesh = noisy_mesh(surface, noise, noise_seed, h);
  const size_t vertices = mesh.positions.size();
  const auto start = std::chrono::steady_clock::now();
  Pipeline pipeline(std::move(mesh));
  pipeline.set_options(options);
  pipeline.run();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Scored against the clean mesh's edge length: noise must not widen the tolerance.
  Score s = score_lines(surface, pipeline.lines(), h);
  s.vertices = vertices;
  s.seconds = seconds;
  return s;
}

std::string target_failures(const Score& score) {
  std::ostringstream out;
  if (score.control) return {};
  auto check = [&](const char* type, const TypeScore& t) {
    if (t.coverage < 0.95) out << type << " coverage " << t.coverage << " < 0.95; ";
    if (t.precision < 0.90) out << type << " precision " << t.precision << " < 0.90; ";
    if (t.fragments > 1.5) out << type << " fragments " << t.fragments << " > 1.5; ";
  };
  check("ridge", score.ridge);
  check("valley", score.valley);
  if (score.spurious_valleys() > 0) out << score.spurious_valleys() << " spurious valleys on a convex shape; ";
  return out.str();
}

bool quality_case_runs(std::size_t index, std::size_t inner) {
  return std::getenv("CRESTLINE_QUALITY_SUBSET") == nullptr || index % inner == index / inner % inner;
}

}  // namespace crestline::quality
