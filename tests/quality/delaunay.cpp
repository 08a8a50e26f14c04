#include "delaunay.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace crestline::quality {
namespace {

using P2 = Eigen::Vector2d;

double orient(const P2& a, const P2& b, const P2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// > 0 when d lies inside the circumcircle of the counter-clockwise a, b, c.
double incircle(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double ax = a.x() - d.x(), ay = a.y() - d.y(), bx = b.x() - d.x(), by = b.y() - d.y(), cx = c.x() - d.x(),
               cy = c.y() - d.y();
  return (ax * ax + ay * ay) * (bx * cy - cx * by) - (bx * bx + by * by) * (ax * cy - cx * ay) +
         (cx * cx + cy * cy) * (ax * by - bx * ay);
}

constexpr uint32_t kNo = 0xffffffffu;

struct Tri {
  uint32_t v[3];
  uint32_t n[3];  // neighbour across the edge opposite v[k]
  bool alive;
};

}  // namespace

std::vector<Triangle> delaunay_2d(const std::vector<P2>& input) {
  const uint32_t n = static_cast<uint32_t>(input.size());
  if (n < 3) return {};
  // A super-triangle far outside the points; its corners are n, n+1, n+2.
  P2 lo = input[0], hi = input[0];
  for (const P2& p : input) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const P2 centre = 0.5 * (lo + hi);
  const double span = std::max(hi.x() - lo.x(), hi.y() - lo.y()) + 1e-300;
  std::vector<P2> p = input;
  p.push_back(centre + 1e3 * span * P2(-1, -1));
  p.push_back(centre + 1e3 * span * P2(1, -1));
  p.push_back(centre + 1e3 * span * P2(0, 1));
  std::vector<Tri> tris = {{{n, n + 1, n + 2}, {kNo, kNo, kNo}, true}};

  // Insert in a spatially coherent order (rows of a coarse grid, serpentine)
  // so that each walk starts near its target.
  const int bins = std::max(1, static_cast<int>(std::sqrt(n / 4.0)));
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  auto bin = [&](uint32_t i, int axis) {
    const double t = (input[i][axis] - lo[axis]) / span;
    return std::min(bins - 1, static_cast<int>(t * bins));
  };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    const int ra = bin(a, 1), rb = bin(b, 1);
    if (ra != rb) return ra < rb;
    return (ra % 2 == 0) ? input[a].x() < input[b].x() : input[a].x() > input[b].x();
  });

  uint32_t last = 0;
  std::vector<uint32_t> cavity, stack;
  std::vector<uint8_t> in_cavity;
  struct Rim {
    uint32_t a, b, outside;
  };
  std::vector<Rim> rim;
  for (uint32_t i : order) {
    const P2& q = p[i];
    // Visibility walk (terminates on a Delaunay triangulation).
    uint32_t t = last;
    for (size_t guard = 0;; ++guard) {
      if (guard > 4 * tris.size() + 16) throw std::runtime_error("delaunay_2d: point location failed");
      const Tri& T = tris[t];
      int exit = -1;
      for (int k = 0; k < 3; ++k)
        if (orient(p[T.v[(k + 1) % 3]], p[T.v[(k + 2) % 3]], q) < 0) {
          exit = k;
          break;
        }
      if (exit < 0) break;
      if (T.n[exit] == kNo) throw std::runtime_error("delaunay_2d: point outside the super-triangle");
      t = T.n[exit];
    }
    // The cavity: triangles whose circumcircle holds q, grown from t.
    in_cavity.resize(tris.size(), 0);
    cavity.clear();
    stack.assign(1, t);
    in_cavity[t] = 1;
    rim.clear();
    while (!stack.empty()) {
      const uint32_t c = stack.back();
      stack.pop_back();
      cavity.push_back(c);
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = tris[c].v[(k + 1) % 3], b = tris[c].v[(k + 2) % 3], o = tris[c].n[k];
        if (o != kNo && in_cavity[o]) continue;
        if (o != kNo && incircle(p[tris[o].v[0]], p[tris[o].v[1]], p[tris[o].v[2]], q) > 0) {
          in_cavity[o] = 1;
          stack.push_back(o);
        } else {
          rim.push_back({a, b, o});
        }
      }
    }
    // Rim edges (a, b) run counter-clockwise around q: new triangles (a, b, q).
    std::unordered_map<uint32_t, uint32_t> starting;  // a → new triangle
    starting.reserve(2 * rim.size());
    std::vector<uint32_t> created;
    for (const Rim& r : rim) {
      uint32_t slot;
      if (!cavity.empty()) {
        slot = cavity.back();
        cavity.pop_back();
        in_cavity[slot] = 0;
      } else {
        slot = static_cast<uint32_t>(tris.size());
        tris.push_back({});
        in_cavity.push_back(0);
      }
      tris[slot] = {{r.a, r.b, i}, {kNo, kNo, r.outside}, true};
      if (r.outside != kNo)
        for (int k = 0; k < 3; ++k) {
          const Tri& O = tris[r.outside];
          if (O.v[(k + 1) % 3] == r.b && O.v[(k + 2) % 3] == r.a) tris[r.outside].n[k] = slot;
        }
      starting[r.a] = slot;
      created.push_back(slot);
    }
    for (uint32_t c : cavity) tris[c].alive = false, in_cavity[c] = 0;
    for (uint32_t s : created) {
      Tri& T = tris[s];
      T.n[0] = starting.at(T.v[1]);  // across (b, q): the triangle starting at b
      // across (q, a): the triangle ending at a, i.e. whose b is a
      const uint32_t other = [&] {
        for (uint32_t c : created)
          if (tris[c].v[1] == T.v[0]) return c;
        return kNo;
      }();
      T.n[1] = other;
    }
    last = created.front();
  }
  // Dead slots are reused, so `alive` marks only cavities never refilled.
  std::vector<Triangle> out;
  for (const Tri& T : tris)
    if (T.alive && T.v[0] < n && T.v[1] < n && T.v[2] < n) out.push_back({T.v[0], T.v[1], T.v[2]});
  return out;
}

std::vector<Triangle> delaunay_sphere(const std::vector<Vec3>& points) {
  if (points.size() < 4 || (points[0] - Vec3::UnitZ()).norm() > 1e-12)
    throw std::invalid_argument("delaunay_sphere: points[0] must be the north pole");
  std::vector<P2> plane;
  for (size_t i = 1; i < points.size(); ++i) {
    const Vec3& q = points[i];
    plane.emplace_back(q.x() / (1 - q.z()), q.y() / (1 - q.z()));
  }
  std::vector<Triangle> out;
  std::unordered_map<uint64_t, int> edge_count;
  for (const Triangle& t : delaunay_2d(plane)) {
    const Triangle s = {t[0] + 1, t[1] + 1, t[2] + 1};
    out.push_back(s);
    for (int k = 0; k < 3; ++k) {
      const uint64_t a = s[k], b = s[(k + 1) % 3];
      ++edge_count[std::min(a, b) << 32 | std::max(a, b)];
    }
  }
  // The planar hull's edges, each closed by a triangle with the pole.
  const size_t planar = out.size();
  for (size_t i = 0; i < planar; ++i)
    for (int k = 0; k < 3; ++k) {
      const uint64_t a = out[i][k], b = out[i][(k + 1) % 3];
      if (edge_count[std::min(a, b) << 32 | std::max(a, b)] == 1)
        out.push_back({static_cast<uint32_t>(b), static_cast<uint32_t>(a), 0u});
    }
  for (Triangle& t : out) {
    const Vec3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
    if ((b - a).cross(c - a).dot(a + b + c) < 0) std::swap(t[1], t[2]);
  }
  return out;
}

}  // namespace crestline::quality
