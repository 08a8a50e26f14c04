#include "crestline/lines/clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace crestline {
namespace {

// Segments are entered into the grid by samples at most half a cell apart,
// so the nearest point of a segment is within a quarter cell of a sample. A
// point within r of the segment is then within r + cell/4 of that sample,
// so in one of the cells within ⌈(r + cell/4) / cell⌉ rings of the sample's
// cell: each sample is entered in all of those, and a point reads only its
// own cell (one lookup: most line points are far from every crease). Cells
// are 1.5 times the median r, so most segments fill 3 × 3 × 3 cells per
// sample.
constexpr double kCellPerRadius = 1.5;
// Cells of at least half a mean edge bound the samples by 4 per mean edge of
// crease (the working frame's mean edge is 1).
constexpr double kMinCell = 0.5;
// Edge lengths are capped at this multiple of their median, which bounds the
// rings of cells a segment is entered in (by 6).
constexpr double kMaxEdgeLengthPerMedian = 8.0;
// Larger distances (edge lengths) clear nothing more on any mesh and would
// overflow the cell arithmetic.
constexpr double kMaxDistance = 1e6;
// Bisection steps for the crossing: 2⁻⁶⁰ of a segment, below round-off.
constexpr int kBisectionSteps = 60;

class SegmentGrid {
 public:
  SegmentGrid(const std::vector<CreaseSegment>& segments, double distance) : segments_(segments) {
    std::vector<double> lengths;
    for (const CreaseSegment& s : segments)
      if (std::isfinite(s.edge_length) && s.edge_length > 0) lengths.push_back(s.edge_length);
    double median = 1;
    if (!lengths.empty()) {
      std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
      median = lengths[lengths.size() / 2];
    }
    cell_ = std::max(kCellPerRadius * distance * median, kMinCell);
    radius_.resize(segments.size());
    for (uint32_t s = 0; s < segments.size(); ++s) {
      const double edge = segments[s].edge_length;
      radius_[s] = distance * (std::isfinite(edge) && edge > 0 ? std::min(edge, kMaxEdgeLengthPerMedian * median) : 0);
      const Vec3 &a = segments[s].ends[0], &b = segments[s].ends[1];
      const double length = (b - a).norm();
      if (!std::isfinite(length) || radius_[s] == 0) continue;
      const auto rings = static_cast<int64_t>(std::ceil((radius_[s] + 0.25 * cell_) / cell_));
      const auto samples = static_cast<size_t>(std::ceil(length / (0.5 * cell_)));
      for (size_t k = 0; k <= samples; ++k) {
        const Vec3 p = samples ? a + (b - a) * (double(k) / double(samples)) : a;
        const int64_t cx = coord(p.x()), cy = coord(p.y()), cz = coord(p.z());
        for (int64_t dx = -rings; dx <= rings; ++dx)
          for (int64_t dy = -rings; dy <= rings; ++dy)
            for (int64_t dz = -rings; dz <= rings; ++dz) {
              auto& cell = cells_[pack(cx + dx, cy + dy, cz + dz)];
              if (cell.empty() || cell.back() != s) cell.push_back(s);
            }
      }
    }
  }

  /// The least distance from p to a segment of its component minus that
  /// segment's radius, over the segments entered in p's cell: negative
  /// exactly when p lies in some segment's band (every such segment is
  /// there); otherwise positive or infinity, which is all its callers ask.
  double clearance(const Vec3& p, uint32_t component) const {
    double least = std::numeric_limits<double>::infinity();
    const auto it = cells_.find(pack(coord(p.x()), coord(p.y()), coord(p.z())));
    if (it == cells_.end()) return least;
    for (uint32_t s : it->second)
      if (segments_[s].component == component) least = std::min(least, to_segment(p, segments_[s]) - radius_[s]);
    return least;
  }

 private:
  static double to_segment(const Vec3& p, const CreaseSegment& s) {
    const Vec3 d = s.ends[1] - s.ends[0];
    const double dd = d.squaredNorm();
    const double t = dd > 0 ? std::clamp((p - s.ends[0]).dot(d) / dd, 0.0, 1.0) : 0.0;
    return (p - (s.ends[0] + t * d)).norm();
  }
  int64_t coord(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
  // 21 bits per axis: far cells may share a key, which only adds candidates.
  static int64_t pack(int64_t x, int64_t y, int64_t z) {
    return (x & 0x1fffff) | ((y & 0x1fffff) << 21) | ((z & 0x1fffff) << 42);
  }

  const std::vector<CreaseSegment>& segments_;
  std::vector<double> radius_;
  double cell_ = 1;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
};

struct Sample {
  Vec3 point;
  double curvature;
};

// Cuts one line (its points as a sequence with whether each is clear of
// the band; a closed line is passed opened at a point inside the band, that
// point repeated at the end) into the runs of clear points, each run
// extended to where its segment enters the band.
void clear_runs(const std::vector<Sample>& samples, const std::vector<uint8_t>& clear, LineType type, uint32_t source,
                const SegmentGrid& grid, uint32_t component, ClearanceResult& out) {
  // Where the segment from a clear point to one in the band reaches the band.
  auto crossing = [&](const Sample& outside, const Sample& inside) {
    double lo = 0, hi = 1;  // clear at lo, in the band at hi
    const Vec3 d = inside.point - outside.point;
    for (int k = 0; k < kBisectionSteps; ++k) {
      const double mid = 0.5 * (lo + hi);
      (grid.clearance(outside.point + mid * d, component) >= 0 ? lo : hi) = mid;
    }
    return Sample{outside.point + lo * d, outside.curvature + lo * (inside.curvature - outside.curvature)};
  };
  Polyline run;
  run.type = type;
  auto flush = [&] {
    if (run.points.size() >= 2) {
      measure_polyline(run);
      out.lines.push_back(run);
      out.source.push_back(source);
    }
    run.points.clear(), run.curvature.clear();
  };
  auto add = [&](const Sample& s) { run.points.push_back(s.point), run.curvature.push_back(s.curvature); };
  for (size_t i = 0; i < samples.size(); ++i) {
    if (clear[i]) {
      if (i > 0 && !clear[i - 1]) add(crossing(samples[i], samples[i - 1]));
      add(samples[i]);
    } else if (i > 0 && clear[i - 1]) {
      add(crossing(samples[i - 1], samples[i]));
      flush();
    }
  }
  flush();
}

}  // namespace

ClearanceResult clear_of_creases(std::vector<Polyline> lines, const std::vector<uint32_t>& line_component,
                                 const std::vector<CreaseSegment>& segments, const ClearanceOptions& options) {
  ClearanceResult out;
  if (!(options.distance > 0) || segments.empty()) {
    out.source.resize(lines.size());
    for (uint32_t i = 0; i < lines.size(); ++i) out.source[i] = i;
    out.lines = std::move(lines);
    return out;
  }
  out.lines.reserve(lines.size());
  const SegmentGrid grid(segments, std::min(options.distance, kMaxDistance));
  std::vector<uint8_t> point_clear, clear;
  std::vector<Sample> samples;
  for (uint32_t i = 0; i < lines.size(); ++i) {
    Polyline& line = lines[i];
    const uint32_t component = line_component[i];
    const size_t n = line.points.size();
    point_clear.resize(n);
    for (size_t k = 0; k < n; ++k) point_clear[k] = grid.clearance(line.points[k], component) >= 0;
    const size_t first_in_band = std::find(point_clear.begin(), point_clear.end(), 0) - point_clear.begin();
    if (first_in_band == n) {
      out.lines.push_back(std::move(line));
      out.source.push_back(i);
      continue;
    }
    samples.clear(), clear.clear();
    const size_t start = line.closed ? first_in_band : 0;
    const size_t count = line.closed ? n + 1 : n;
    for (size_t k = 0; k < count; ++k) {
      const size_t j = (start + k) % n;
      samples.push_back({line.points[j], line.curvature[j]});
      clear.push_back(point_clear[j]);
    }
    clear_runs(samples, clear, line.type, i, grid, component, out);
  }
  return out;
}

}  // namespace crestline
