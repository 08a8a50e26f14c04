// The Delaunay meshings of the quality harness (issue 13) are what they
// claim: Delaunay, manifold, 3:1 triangles along or across the lines, and
// spacing growing threefold.
#include "delaunay.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

#include "crestline/mesh/repair.h"
#include "crestline/mesh/topology.h"
#include "quality_surfaces.h"

using namespace crestline;
using namespace crestline::quality;

TEST_CASE("delaunay_2d: counter-clockwise triangles with empty circumcircles covering the hull", "[quality]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector2d> p;
  // A square's boundary with collinear runs, and random points inside.
  for (int i = 0; i < 10; ++i)
    for (const Eigen::Vector2d& q : {Eigen::Vector2d(i / 10.0, 0), Eigen::Vector2d(1, i / 10.0),
                                     Eigen::Vector2d(1 - i / 10.0, 1), Eigen::Vector2d(0, 1 - i / 10.0)})
      p.push_back(q);
  for (int i = 0; i < 300; ++i) p.emplace_back(0.01 + 0.98 * u(rng), 0.01 + 0.98 * u(rng));
  const std::vector<Triangle> t = delaunay_2d(p);
  double area = 0;
  for (const Triangle& f : t) {
    const Eigen::Vector2d &a = p[f[0]], &b = p[f[1]], &c = p[f[2]];
    const double twice = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    CHECK(twice > 0);
    area += 0.5 * twice;
    // Circumcentre and radius; no point strictly inside.
    const double d = 2 * twice;
    const double ux =
        ((a.squaredNorm()) * (b.y() - c.y()) + b.squaredNorm() * (c.y() - a.y()) + c.squaredNorm() * (a.y() - b.y())) /
        d;
    const double uy =
        ((a.squaredNorm()) * (c.x() - b.x()) + b.squaredNorm() * (a.x() - c.x()) + c.squaredNorm() * (b.x() - a.x())) /
        d;
    const Eigen::Vector2d centre(ux, uy);
    const double r = (a - centre).norm();
    for (const Eigen::Vector2d& q : p) CHECK((q - centre).norm() > r * (1 - 1e-9));
  }
  CHECK(area == Approx(1.0));
  CHECK(t.size() == 2 * p.size() - 2 - 40);  // 40 points on the hull
}

namespace {

struct Shape {
  double median_aspect = 0;  // longest edge / its altitude
  double along = 0;          // median |cos| of the triangle's long axis with `direction`
};
Shape shape(const Mesh& m, const Vec3& direction) {
  std::vector<double> aspect, cosine;
  for (const Triangle& f : m.triangles) {
    Vec3 longest = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = m.positions[f[(k + 1) % 3]] - m.positions[f[k]];
      if (e.norm() > longest.norm()) longest = e;
    }
    // The long axis: the principal axis of the corners' second moment.
    const Vec3 centre = (m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]) / 3;
    Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
    for (uint32_t v : f) moment += (m.positions[v] - centre) * (m.positions[v] - centre).transpose();
    const Vec3 axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(moment).eigenvectors().col(2);
    const double twice = (m.positions[f[1]] - m.positions[f[0]]).cross(m.positions[f[2]] - m.positions[f[0]]).norm();
    aspect.push_back(longest.squaredNorm() / twice);
    cosine.push_back(std::abs(axis.dot(direction)));
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  return {median(aspect), median(cosine)};
}

}  // namespace

TEST_CASE("the Delaunay meshings: manifold, closed where the surface is, 3:1 along or across, graded 3×", "[quality]") {
  for (const std::string& name : surface_names())
    for (Triangulation kind : {Triangulation::AnisoAlong, Triangulation::AnisoAcross, Triangulation::Graded}) {
      SurfaceParams params;
      params.triangulation = kind;
      const Surface s = make_surface(name, params);
      INFO(name << " " << triangulation_name(kind));
      const RepairResult repaired = repair_mesh(s.soup);
      const Mesh& m = repaired.mesh;
      CHECK(m.triangles.size() == s.soup.triangle_count());  // nothing degenerate dropped
      const Topology topology = build_topology(m);
      // Euler characteristic: 2 for the closed shapes, 1 for the patches, 0 for the torus.
      const long chi = static_cast<long>(m.positions.size()) - static_cast<long>(topology.edges.size()) +
                       static_cast<long>(m.triangles.size());
      CHECK(chi == (name == "superquadric" ? 2 : name == "torus" ? 0 : 1));
      if (name != "sine") continue;
      // The sine's lines are straight: their direction from a true curve.
      const Vec3 direction = (s.curves[0].points.back() - s.curves[0].points.front()).normalized();
      const Shape sh = shape(m, direction);
      INFO("median aspect " << sh.median_aspect << ", |cos| of the long axis with the lines " << sh.along);
      if (kind == Triangulation::Graded) {
        // Mean edge length near x = 0.2 and near x = 1.8 (domain [0, 2]).
        double sum[2] = {0, 0};
        int count[2] = {0, 0};
        for (const auto& e : topology.edges) {
          const Vec3 mid = 0.5 * (m.positions[e[0]] + m.positions[e[1]]);
          const int side = mid.x() > 0.1 && mid.x() < 0.3 ? 0 : mid.x() > 1.7 && mid.x() < 1.9 ? 1 : -1;
          if (side >= 0) sum[side] += (m.positions[e[0]] - m.positions[e[1]]).norm(), ++count[side];
        }
        const double ratio = (sum[1] / count[1]) / (sum[0] / count[0]);
        CHECK(ratio > 2.2);  // 3^0.8 = 2.4 between the two strips
        CHECK(ratio < 2.8);
        CHECK(sh.median_aspect < 2.0);
      } else {
        CHECK(sh.median_aspect > 2.5);
        CHECK(sh.median_aspect < 3.5);
        if (kind == Triangulation::AnisoAlong) CHECK(sh.along > 0.95);
        if (kind == Triangulation::AnisoAcross) CHECK(sh.along < 0.2);
      }
    }
}
