// Ear clipping with a spatial index over the corners (see
// triangulate_polygon.h): each ear test looks only at the corners in the
// ear's bounding box.
#include "triangulate_polygon.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace crestline::io::detail {

PolygonWork& polygon_work() {
  thread_local PolygonWork work;
  return work;
}

namespace {

double cross2(const double* o, const double* a, const double* b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Inclusive point-in-triangle test for a counter-clockwise triangle.
bool inside(const double* p, const double* a, const double* b, const double* c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

bool same_point(const double* p, const double* q) { return p[0] == q[0] && p[1] == q[1]; }

void add_fan(TriangleSoup& soup, const uint32_t* poly, size_t n) {
  for (size_t i = 1; i + 1 < n; ++i) soup.indices.insert(soup.indices.end(), {poly[0], poly[i], poly[i + 1]});
}

// The points of the corners not clipped yet, in a k-d tree over their plane
// coordinates (leaves of up to 8, split at the median of the longer side),
// with a count of live points per node so that removed ones cost nothing.
// An ear test asks for the points in the ear's bounding box: O(log n + k) for the
// thin ears of a star-shaped outline too, where a z-order range (earcut's
// hash) spans most of the polygon and made a 4·10^5-corner star quadratic.
class CornerTree {
 public:
  explicit CornerTree(const std::vector<double>& xy) : xy_(xy), n_(uint32_t(xy.size() / 2)) {
    order_.resize(n_);
    std::iota(order_.begin(), order_.end(), 0u);
    nodes_.resize(size_t{4} * (n_ / kLeaf + 1));
    build(0, 0, n_);
    where_.resize(n_);
    for (uint32_t k = 0; k < n_; ++k) where_[order_[k]] = k;
    alive_.assign(n_, 1);
  }

  void remove(uint32_t corner) {
    alive_[corner] = 0;
    const uint32_t position = where_[corner];
    for (uint32_t node = 0, lo = 0, hi = n_;;) {
      --nodes_[node].alive;
      if (hi - lo <= kLeaf) break;
      const uint32_t mid = lo + (hi - lo) / 2;
      if (position < mid)
        node = 2 * node + 1, hi = mid;
      else
        node = 2 * node + 2, lo = mid;
    }
  }

  /// True when `stop` returns true for a live point in the box.
  template <typename Stop>
  bool any_in_box(double x0, double y0, double x1, double y1, const Stop& stop) const {
    struct Range {
      uint32_t node, lo, hi;
    };
    Range stack[64];
    int top = 0;
    stack[top++] = {0, 0, n_};
    PolygonWork& work = polygon_work();
    while (top > 0) {
      const Range r = stack[--top];
      const Node& node = nodes_[r.node];
      ++work.nodes;
      if (node.alive == 0 || node.x0 > x1 || node.x1 < x0 || node.y0 > y1 || node.y1 < y0) continue;
      if (r.hi - r.lo <= kLeaf) {
        for (uint32_t k = r.lo; k < r.hi; ++k) {
          const uint32_t corner = order_[k];
          const double* p = &xy_[size_t{2} * corner];
          ++work.points;
          if (alive_[corner] && p[0] >= x0 && p[0] <= x1 && p[1] >= y0 && p[1] <= y1 && stop(corner)) return true;
        }
        continue;
      }
      const uint32_t mid = r.lo + (r.hi - r.lo) / 2;
      stack[top++] = {2 * r.node + 1, r.lo, mid};
      stack[top++] = {2 * r.node + 2, mid, r.hi};
    }
    return false;
  }

 private:
  static constexpr uint32_t kLeaf = 8;
  struct Node {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    uint32_t alive = 0;
  };

  void build(uint32_t index, uint32_t lo, uint32_t hi) {
    Node& node = nodes_[index];
    node.alive = hi - lo;
    for (uint32_t k = lo; k < hi; ++k) {
      const double* p = &xy_[size_t{2} * order_[k]];
      node.x0 = std::min(node.x0, p[0]), node.x1 = std::max(node.x1, p[0]);
      node.y0 = std::min(node.y0, p[1]), node.y1 = std::max(node.y1, p[1]);
    }
    if (hi - lo <= kLeaf) return;
    const int axis = node.x1 - node.x0 >= node.y1 - node.y0 ? 0 : 1;
    const uint32_t mid = lo + (hi - lo) / 2;
    std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                     [&](uint32_t a, uint32_t b) { return xy_[2 * a + axis] < xy_[2 * b + axis]; });
    build(2 * index + 1, lo, mid);
    build(2 * index + 2, mid, hi);
  }

  const std::vector<double>& xy_;
  const uint32_t n_;
  std::vector<uint32_t> order_, where_;
  std::vector<char> alive_;
  std::vector<Node> nodes_;
};

// The distinct positions of the corners (a degenerate outline may visit a
// few points thousands of times; the tree holds each point once).
std::vector<double> distinct_points(const std::vector<double>& xy, std::vector<uint32_t>& point_of) {
  const uint32_t n = uint32_t(xy.size() / 2);
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](uint32_t i) { return std::make_pair(xy[size_t{2} * i], xy[size_t{2} * i + 1]); };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
  std::vector<double> points;
  point_of.resize(n);
  for (uint32_t k = 0; k < n; ++k) {
    if (k == 0 || key(order[k]) != key(order[k - 1]))
      points.insert(points.end(), {xy[size_t{2} * order[k]], xy[size_t{2} * order[k] + 1]});
    point_of[order[k]] = uint32_t(points.size() / 2 - 1);
  }
  return points;
}

// The outline as a circular list of the corners not clipped yet, and the
// points they stand on in a CornerTree (a point leaves it with its last
// corner).
class EarClipper {
 public:
  explicit EarClipper(const std::vector<double>& xy)
      : xy_(xy), points_(distinct_points(xy, point_of_)), tree_(points_), corners_on_(points_.size() / 2, 0) {
    const uint32_t n = uint32_t(xy.size() / 2);
    for (uint32_t i = 0; i < n; ++i) ++corners_on_[point_of_[i]];
    prev_.resize(n), next_.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      prev_[i] = i == 0 ? n - 1 : i - 1;
      next_[i] = i + 1 == n ? 0 : i + 1;
    }
  }

  uint32_t prev(uint32_t i) const { return prev_[i]; }
  uint32_t next(uint32_t i) const { return next_[i]; }

  // Strictly convex, and no other corner inside or on the triangle (corners
  // coincident with one of its three are skipped: repeated corners).
  bool is_ear(uint32_t i) const {
    ++polygon_work().ear_tests;
    const double* a = &xy_[size_t{2} * prev_[i]];
    const double* b = &xy_[size_t{2} * i];
    const double* c = &xy_[size_t{2} * next_[i]];
    if (!(cross2(a, b, c) > 0)) return false;
    const double x0 = std::min({a[0], b[0], c[0]}), x1 = std::max({a[0], b[0], c[0]});
    const double y0 = std::min({a[1], b[1], c[1]}), y1 = std::max({a[1], b[1], c[1]});
    return !tree_.any_in_box(x0, y0, x1, y1, [&](uint32_t point) {
      const double* p = &points_[size_t{2} * point];
      if (same_point(p, a) || same_point(p, b) || same_point(p, c)) return false;
      return inside(p, a, b, c);
    });
  }

  void remove(uint32_t i) {
    next_[prev_[i]] = next_[i], prev_[next_[i]] = prev_[i];
    if (--corners_on_[point_of_[i]] == 0) tree_.remove(point_of_[i]);
  }

 private:
  const std::vector<double>& xy_;
  std::vector<uint32_t> point_of_;  // the point each corner stands on
  const std::vector<double> points_;
  CornerTree tree_;
  std::vector<uint32_t> corners_on_;  // live corners per point
  std::vector<uint32_t> prev_, next_;
};

}  // namespace

// Polygons up to this size keep the clipping order of Crestline's first
// clipper (step back after an ear), so their triangles are unchanged; larger
// ones take earcut's (two corners on), which keeps ears small: stepping back
// grows a fan whose ears span the polygon, and each then meets every corner.
constexpr size_t kSmallPolygon = 80;

// Ear tests a large polygon may spend, per corner, before the rest is
// fanned. Simple outlines need about one a corner (the O(n log n) test:
// ≤ 2); one that winds round the same few points many times (a fuzzed face
// of 5,003 corners on a square's 4) finds an ear only every half turn, and
// the turns made it quadratic: 4·10^4 corners took 8 s.
constexpr size_t kEarTestsPerCorner = 16;

void add_polygon(TriangleSoup& soup, const uint32_t* poly, size_t n) {
  if (n < 3) return;
  if (n == 3) {
    soup.indices.insert(soup.indices.end(), {poly[0], poly[1], poly[2]});
    return;
  }
  auto point = [&](size_t i) { return Vec3(soup.positions.data() + 3 * size_t(poly[i])); };
  Vec3 centroid = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) centroid += point(i);
  centroid /= double(n);
  // Newell's normal: the polygon is counter-clockwise around it.
  Vec3 normal = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) normal += (point(i) - centroid).cross(point((i + 1) % n) - centroid);
  const double length = normal.norm();
  if (!(length > 0) || !std::isfinite(length) || n >= UINT32_MAX) {
    add_fan(soup, poly, n);
    return;
  }
  normal /= length;
  const Vec3 u = normal.unitOrthogonal();
  const Vec3 v = normal.cross(u);
  std::vector<double> xy(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 d = point(i) - centroid;
    xy[2 * i] = d.dot(u);
    xy[2 * i + 1] = d.dot(v);
  }
  EarClipper ring(xy);
  size_t remaining = n;
  uint32_t i = 0;
  size_t misses = 0;
  // Small polygons keep the first clipper's results: at most n² tests.
  size_t tests_left = n > kSmallPolygon ? kEarTestsPerCorner * n : n * n;
  while (remaining > 3) {
    if (misses > remaining || tests_left-- == 0) {
      // A whole turn without an ear, or the budget spent: the rest is
      // self-intersecting or degenerate (repeated corners). Fan it, in
      // linear time; clipping one forced corner per turn costs a whole turn
      // of ear tests per corner (a 2,000-corner face found by the fuzzer
      // took 1.6 s, not 3 ms).
      for (uint32_t j = ring.next(i); ring.next(j) != i; j = ring.next(j)) {
        soup.indices.insert(soup.indices.end(), {poly[i], poly[j], poly[ring.next(j)]});
      }
      return;
    }
    if (ring.is_ear(i)) {
      const uint32_t before = ring.prev(i), after = ring.next(i);
      soup.indices.insert(soup.indices.end(), {poly[before], poly[i], poly[after]});
      ring.remove(i);
      i = n > kSmallPolygon ? ring.next(after) : before;
      --remaining;
      misses = 0;
    } else {
      i = ring.next(i);
      ++misses;
    }
  }
  soup.indices.insert(soup.indices.end(), {poly[ring.prev(i)], poly[i], poly[ring.next(i)]});
}

}  // namespace crestline::io::detail
