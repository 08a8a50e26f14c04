#include "quality_surfaces.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include "analytic_meshes.h"
#include "delaunay.h"

namespace crestline::quality {
namespace {

using testing::kPi;
constexpr double kSpacing = 0.004;  // truth sampling, far below every edge length used

// Scored regions stay this many mean edges away from a mesh boundary: the
// tracer leaves out two rings and the lines need room to end.
constexpr double kBoundaryBand = 4.0;

using P2 = Eigen::Vector2d;

bool delaunay_kind(Triangulation t) {
  return t == Triangulation::AnisoAlong || t == Triangulation::AnisoAcross || t == Triangulation::Graded;
}

// Tilt of the anisotropic lattices against the lines, and the jitter (in
// lattice spacings) that keeps their points off common circles.
constexpr double kLatticeTilt = 0.12;
constexpr double kLatticeJitter = 0.02;
// Jitter of the graded points, in local spacings.
constexpr double kGradedJitter = 0.25;

P2 rotated(const P2& d, double angle) {
  return {std::cos(angle) * d.x() - std::sin(angle) * d.y(), std::sin(angle) * d.x() + std::cos(angle) * d.y()};
}

// Points for the Delaunay meshings of the square [x0, x0+w]²: its boundary
// at about `spacing`, corners included, and interior points kept at least
// `margin` away from it.
struct SquarePoints {
  double x0, y0, w;
  std::vector<P2> points;
  SquarePoints(double x0_, double y0_, double w_, double spacing) : x0(x0_), y0(y0_), w(w_) {
    const int n = std::max(2, static_cast<int>(std::lround(w / spacing)));
    for (int i = 0; i < n; ++i) {
      const double t = w * i / n;
      points.emplace_back(x0 + t, y0);
      points.emplace_back(x0 + w, y0 + t);
      points.emplace_back(x0 + w - t, y0 + w);
      points.emplace_back(x0, y0 + w - t);
    }
  }
  void add_inside(const P2& q, double margin) {
    if (q.x() > x0 + margin && q.x() < x0 + w - margin && q.y() > y0 + margin && q.y() < y0 + w - margin)
      points.push_back(q);
  }
};

testing::GridOptions grid_options(const SurfaceParams& p, int nu, int nv) {
  testing::GridOptions g;
  g.nu = nu;
  g.nv = nv;
  g.seed = p.seed;
  switch (p.triangulation) {
    case Triangulation::Uniform:
      g.diagonals = testing::Diagonals::Uniform;
      break;
    case Triangulation::Alternating:
      g.diagonals = testing::Diagonals::Alternating;
      break;
    case Triangulation::Irregular:
    case Triangulation::AnisoAlong:
    case Triangulation::AnisoAcross:
    case Triangulation::Graded:
      g.diagonals = testing::Diagonals::Random;
      g.jitter = 0.3;
      break;
  }
  return g;
}

// An angle in [0.2, 0.6] rad: no grid edge or diagonal runs along the lines.
double pattern_angle(unsigned seed) {
  std::mt19937 rng(seed * 7919u + 13u);
  return std::uniform_real_distribution<double>(0.2, 0.6)(rng);
}

// A height field over [x0, x0+w] × [y0, y0+w] with its boundary band excluded.
struct HeightField {
  std::function<double(double, double)> f;
  double x0, y0, w;

  Vec3 lift(double x, double y) const { return Vec3(x, y, f(x, y)); }
  bool inside(double x, double y) const { return x >= x0 && x <= x0 + w && y >= y0 && y <= y0 + w; }
  bool in_band(const Vec3& q, double h) const {
    const double band = kBoundaryBand * h;
    return q.x() < x0 + band || q.x() > x0 + w - band || q.y() < y0 + band || q.y() > y0 + w - band;
  }
  int cells(const SurfaceParams& p) const { return static_cast<int>(std::lround(w * p.cells_per_unit)); }
  /// The grid meshings, or for the Delaunay ones: `along` is the direction
  /// of the true lines (straight ones), or `polar_centre` the centre of
  /// circular ones.
  TriangleSoup mesh(const SurfaceParams& p, const P2& along, const P2* polar_centre = nullptr) const {
    if (delaunay_kind(p.triangulation)) return lift(delaunay_points(p, along, polar_centre));
    TriangleSoup s = testing::height_field([this](double x, double y) { return f(x + x0, y + y0); }, w, w,
                                           grid_options(p, cells(p), cells(p)));
    for (size_t i = 0; i < s.positions.size(); i += 3) s.positions[i] += x0, s.positions[i + 1] += y0;
    return s;
  }
  TriangleSoup lift(const std::vector<P2>& points) const {
    TriangleSoup s;
    for (const P2& q : points) testing::add_vertex(s, lift(q.x(), q.y()));
    for (const Triangle& t : delaunay_2d(points)) testing::add_triangle(s, t[0], t[1], t[2]);
    return s;
  }
  // As many points as the grid's (one per cell c²).
  std::vector<P2> delaunay_points(const SurfaceParams& p, const P2& along, const P2* polar_centre) const {
    const double c = 1.0 / p.cells_per_unit;
    std::mt19937 rng(p.seed * 31337u + 5u);
    std::uniform_real_distribution<double> unit(-1, 1);
    if (p.triangulation == Triangulation::Graded) {
      // Spacing s(x) = s0 · 3^((x − x0)/w); mean of s² over the domain is
      // 3.64 s0², so s0 = 0.55 c gives about one point per c².
      const double s0 = 0.55 * c;
      auto spacing = [&](double x) { return s0 * std::pow(3.0, (x - x0) / w); };
      SquarePoints sp(x0, y0, w, s0);
      for (double x = x0 + spacing(x0); x < x0 + w; x += 0.87 * spacing(x)) {
        const double s = spacing(x);
        const double shift = unit(rng) * 0.5 * s;
        for (double y = y0 + shift; y < y0 + w; y += s)
          sp.add_inside({x + kGradedJitter * s * unit(rng), y + kGradedJitter * s * unit(rng)}, 0.4 * s);
      }
      return sp.points;
    }
    // 3:1 lattices, spacing a × 3a = c².
    const double a = c / std::sqrt(3.0);
    const bool long_along = p.triangulation == Triangulation::AnisoAlong;
    SquarePoints sp(x0, y0, w, a);
    if (polar_centre) {
      const double radial = long_along ? a : 3 * a, arc = long_along ? 3 * a : a;
      sp.add_inside(*polar_centre, 0.5 * a);
      const double reach = std::sqrt(2.0) * w + 2 * radial;
      for (double r = radial; r < reach; r += radial) {
        const int n = std::max(6, static_cast<int>(std::lround(2 * testing::kPi * r / arc)));
        const double phase = testing::kPi * unit(rng);
        for (int i = 0; i < n; ++i) {
          const double angle = phase + 2 * testing::kPi * (i + kLatticeJitter * unit(rng)) / n;
          sp.add_inside(
              *polar_centre + (r + kLatticeJitter * radial * unit(rng)) * P2(std::cos(angle), std::sin(angle)),
              0.5 * a);
        }
      }
      return sp.points;
    }
    const P2 u = rotated(long_along ? along : P2(-along.y(), along.x()), kLatticeTilt), v(-u.y(), u.x());
    const P2 centre(x0 + 0.5 * w, y0 + 0.5 * w);
    const int rows = static_cast<int>(std::ceil(w / a)), cols = static_cast<int>(std::ceil(w / (3 * a)));
    for (int j = -rows; j <= rows; ++j)
      for (int i = -cols - rows; i <= cols + rows; ++i) {
        // Sheared: each row moves by 0.05 of the long spacing, so that the
        // Delaunay triangles are the lattice's 3:1 halves of its cells (with
        // more shear the shortest lattice vectors change and so do they).
        const double along_u = 3 * a * (i + 0.05 * j + kLatticeJitter * unit(rng));
        const double along_v = a * (j + kLatticeJitter * unit(rng));
        sp.add_inside(centre + along_u * u + along_v * v, 0.5 * a);
      }
    return sp.points;
  }
  // The straight line through `origin` along `dir`, clipped to the domain.
  TrueCurve line(LineType type, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir) const {
    TrueCurve c;
    c.type = type;
    const double reach = 2 * w;
    for (double t = -reach; t <= reach; t += kSpacing) {
      const Eigen::Vector2d q = origin + t * dir;
      if (inside(q.x(), q.y())) c.points.push_back(lift(q.x(), q.y()));
    }
    return c;
  }
  // The circle of radius r about `centre`; its parts outside the domain are
  // kept (they lie in the excluded band's continuation) so it stays closed.
  TrueCurve circle(LineType type, const Eigen::Vector2d& centre, double r) const {
    TrueCurve c;
    c.type = type;
    c.closed = true;
    const int n = static_cast<int>(std::ceil(2 * kPi * r / kSpacing));
    for (int i = 0; i < n; ++i) {
      const double a = 2 * kPi * i / n;
      const Eigen::Vector2d q = centre + r * Eigen::Vector2d(std::cos(a), std::sin(a));
      c.points.push_back(lift(q.x(), q.y()));
    }
    return c;
  }
};

void add_if_nonempty(Surface& s, TrueCurve c) {
  if (c.points.size() > 1) s.curves.push_back(std::move(c));
}

// The unit sphere through points on circles of latitude, triangulated by
// delaunay_sphere, with about `vertices` vertices (as the icosphere). Along:
// spacing a between circles, 3a along them; across: the reverse; graded:
// spacing s(z) = s0 · 3^((z+1)/2) both ways, jittered.
TriangleSoup sphere_rings(Triangulation kind, int vertices, unsigned seed) {
  const double area = 4 * kPi / vertices;  // per vertex
  std::mt19937 rng(seed * 7u + 3u);
  std::uniform_real_distribution<double> unit(-1, 1);
  const double a = std::sqrt(area / 3), s0 = std::sqrt(area / 3.64);
  auto latitude_step = [&](double z) {
    return kind == Triangulation::Graded       ? s0 * std::pow(3.0, (z + 1) / 2)
           : kind == Triangulation::AnisoAlong ? a
                                               : 3 * a;
  };
  auto arc_step = [&](double z) {
    return kind == Triangulation::Graded       ? s0 * std::pow(3.0, (z + 1) / 2)
           : kind == Triangulation::AnisoAlong ? 3 * a
                                               : a;
  };
  const double jitter = kind == Triangulation::Graded ? kGradedJitter : kLatticeJitter;
  std::vector<Vec3> points = {Vec3::UnitZ()};
  for (double phi = kPi / 2 - latitude_step(1); phi > -kPi / 2 + 0.5 * latitude_step(-1);) {
    const double z = std::sin(phi), step = latitude_step(z);
    const int n = std::max(3, static_cast<int>(std::lround(2 * kPi * std::cos(phi) / arc_step(z))));
    const double phase = kPi * unit(rng);
    for (int i = 0; i < n; ++i) {
      const double lat = phi + jitter * step * unit(rng), lon = phase + 2 * kPi * (i + jitter * unit(rng)) / n;
      points.emplace_back(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
    }
    phi -= step;
  }
  points.push_back(-Vec3::UnitZ());
  TriangleSoup s;
  for (const Vec3& q : points) testing::add_vertex(s, q);
  for (const Triangle& t : delaunay_sphere(points)) testing::add_triangle(s, t[0], t[1], t[2]);
  return s;
}

Eigen::Matrix3d random_rotation(unsigned seed) {
  std::mt19937 rng(seed * 104729u + 7u);
  std::normal_distribution<double> g(0, 1);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

}  // namespace

const char* triangulation_name(Triangulation t) {
  switch (t) {
    case Triangulation::Uniform:
      return "uniform";
    case Triangulation::Alternating:
      return "checker";
    case Triangulation::Irregular:
      return "irregular";
    case Triangulation::AnisoAlong:
      return "aniso-along";
    case Triangulation::AnisoAcross:
      return "aniso-across";
    case Triangulation::Graded:
      return "graded";
  }
  return "?";
}

std::vector<Triangulation> triangulations() {
  return {Triangulation::Uniform,    Triangulation::Alternating, Triangulation::Irregular,
          Triangulation::AnisoAlong, Triangulation::AnisoAcross, Triangulation::Graded};
}

Surface sine_field(const SurfaceParams& p) {
  // Wavelength 1 on a 2×2 patch, slope amplitude 0.5. κ = −f''/(1+f'²)^{3/2}
  // has its extrema exactly where f' = 0, so the truth is exact.
  const double L = 1.0, A = 0.5 * L / (2 * kPi), theta = pattern_angle(p.seed);
  const Eigen::Vector2d centre(1, 1), d(std::cos(theta), std::sin(theta)), along(-d.y(), d.x());
  HeightField hf{
      [=](double x, double y) { return A * std::cos(2 * kPi * (Eigen::Vector2d(x, y) - centre).dot(d) / L); }, 0, 0, 2};
  Surface s;
  s.name = "sine";
  s.soup = hf.mesh(p, along);
  for (int k = -4; k <= 4; ++k) {
    add_if_nonempty(s, hf.line(LineType::Ridge, centre + k * L * d, along));
    add_if_nonempty(s, hf.line(LineType::Valley, centre + (k + 0.5) * L * d, along));
  }
  s.excluded = [hf](const Vec3& q, double h) { return hf.in_band(q, h); };
  return s;
}

Surface cosine_product(const SurfaceParams& p) {
  // In coordinates (a, b) rotated by θ: z = A cos(ka) cos(kb) = ½A (cos k√2 s + cos k√2 t)
  // with s = (a−b)/√2, t = (a+b)/√2: two crossing sine families of
  // wavelength Λ = 2π/(k√2), each line a mirror line of the surface.
  // Each family has slope amplitude 0.5, like the sine field.
  const double Lambda = 1.0, k = 2 * kPi / (Lambda * std::sqrt(2.0)), A = 2 * 0.5 * Lambda / (2 * kPi);
  const double theta = pattern_angle(p.seed) + kPi / 4;  // s, t axes at θ from the grid
  const Eigen::Vector2d centre(1, 1), ds(std::cos(theta), std::sin(theta)), dt(-ds.y(), ds.x());
  HeightField hf{[=](double x, double y) {
                   const Eigen::Vector2d q(x - centre.x(), y - centre.y());
                   const double s = q.dot(ds), t = q.dot(dt);
                   return 0.5 * A * (std::cos(k * std::sqrt(2.0) * s) + std::cos(k * std::sqrt(2.0) * t));
                 },
                 0, 0, 2};
  Surface s;
  s.name = "cos-product";
  s.soup = hf.mesh(p, dt);
  for (int i = -6; i <= 6; ++i) {
    const LineType type = i % 2 == 0 ? LineType::Ridge : LineType::Valley;
    add_if_nonempty(s, hf.line(type, centre + 0.5 * i * Lambda * ds, dt));
    add_if_nonempty(s, hf.line(type, centre + 0.5 * i * Lambda * dt, ds));
  }
  // Where two lines cross (peaks, pits: umbilics; saddles: |κ₁| = |κ₂|).
  const double radius = 0.15 * Lambda;
  s.excluded = [=](const Vec3& q, double h) {
    if (hf.in_band(q, h)) return true;
    const Eigen::Vector2d r(q.x() - centre.x(), q.y() - centre.y());
    const double a = r.dot(ds) / (0.5 * Lambda), b = r.dot(dt) / (0.5 * Lambda);
    return std::hypot(a - std::round(a), b - std::round(b)) * 0.5 * Lambda < radius;
  };
  return s;
}

Surface ripple(const SurfaceParams& p) {
  const double L = 1.0, A = 0.5 * L / (2 * kPi);
  const Eigen::Vector2d centre(1.6, 1.6);
  HeightField hf{
      [=](double x, double y) { return A * std::cos(2 * kPi * std::hypot(x - centre.x(), y - centre.y()) / L); }, 0, 0,
      3.2};
  Surface s;
  s.name = "ripple";
  s.soup = hf.mesh(p, P2::UnitX(), &centre);
  add_if_nonempty(s, hf.circle(LineType::Valley, centre, 0.5 * L));
  add_if_nonempty(s, hf.circle(LineType::Ridge, centre, L));
  add_if_nonempty(s, hf.circle(LineType::Valley, centre, 1.5 * L));
  s.excluded = [=](const Vec3& q, double h) {
    return hf.in_band(q, h) || std::hypot(q.x() - centre.x(), q.y() - centre.y()) < 0.25 * L;
  };
  return s;
}

Surface paraboloid_ridge(const SurfaceParams& p) {
  // κ across the long axis is 2a at the crest, along it 2b: no umbilic.
  const double a = 1.0, b = 0.1, theta = pattern_angle(p.seed) + kPi / 2;
  const Eigen::Vector2d across(std::cos(theta), std::sin(theta)), along(-across.y(), across.x());
  HeightField hf{[=](double x, double y) {
                   const Eigen::Vector2d q(x, y);
                   const double u = q.dot(across), v = q.dot(along);
                   return -(a * u * u + b * v * v);
                 },
                 -0.75, -0.75, 1.5};
  Surface s;
  s.name = "paraboloid";
  s.convex = true;
  s.soup = hf.mesh(p, along);
  add_if_nonempty(s, hf.line(LineType::Ridge, Eigen::Vector2d::Zero(), along));
  s.excluded = [hf](const Vec3& q, double h) { return hf.in_band(q, h); };
  return s;
}

Surface superquadric(const SurfaceParams& p) {
  constexpr double n = 4;
  auto project = [](const Vec3& d) {
    const double r =
        std::pow(std::pow(std::abs(d.x()), n) + std::pow(std::abs(d.y()), n) + std::pow(std::abs(d.z()), n), 1 / n);
    return Vec3(d / r);
  };
  const int level = p.cells_per_unit <= 20 ? 4 : 5;
  Surface s;
  s.name = "superquadric";
  s.convex = true;
  const bool delaunay = delaunay_kind(p.triangulation);
  s.soup = delaunay ? sphere_rings(p.triangulation, 10 * (1 << (2 * level)) + 2, p.seed) : testing::icosphere(level);
  const Eigen::Matrix3d rotation =
      p.triangulation == Triangulation::Uniform || delaunay ? Eigen::Matrix3d::Identity() : random_rotation(p.seed);
  std::mt19937 rng(p.seed);
  const double jitter = p.triangulation == Triangulation::Irregular ? 0.3 * 1.1 / (1 << level) : 0.0;
  std::uniform_real_distribution<double> jit(-jitter, jitter);
  for (size_t i = 0; i < s.soup.positions.size(); i += 3) {
    Vec3 d(s.soup.positions[i], s.soup.positions[i + 1], s.soup.positions[i + 2]);
    if (jitter > 0) d += Vec3(jit(rng), jit(rng), jit(rng));
    const Vec3 q = project(rotation * d.normalized());
    for (int c = 0; c < 3; ++c) s.soup.positions[i + c] = q[c];
  }
  // Each rounded edge lies in a mirror plane x_i = ±x_j, where the curvature
  // across the edge peaks: x_i = ±σ, x_j = ±σ, x_k = z, 2σ⁴ + z⁴ = 1, up to the corners |z| = 3^{−1/4}.
  const double corner = std::pow(3.0, -1 / n);
  for (int k = 0; k < 3; ++k)
    for (int si = -1; si <= 1; si += 2)
      for (int sj = -1; sj <= 1; sj += 2) {
        TrueCurve c;
        for (double z = -corner; z <= corner; z += kSpacing) {
          const double sigma = std::pow((1 - std::pow(std::abs(z), n)) / 2, 1 / n);
          Vec3 q;
          q[(k + 1) % 3] = si * sigma;
          q[(k + 2) % 3] = sj * sigma;
          q[k] = z;
          c.points.push_back(q);
        }
        s.curves.push_back(std::move(c));
      }
  s.excluded = [corner](const Vec3& q, double) {
    const Vec3 nearest(std::copysign(corner, q.x()), std::copysign(corner, q.y()), std::copysign(corner, q.z()));
    return (q - nearest).norm() < 0.3;
  };
  return s;
}

Surface torus(const SurfaceParams& p) {
  Surface s;
  s.name = "torus";
  s.control = true;
  // The Delaunay kinds get grids of 3:1 cells (long around the big circle,
  // or around the tube) or, graded, the irregular grid.
  const double stretch = p.triangulation == Triangulation::AnisoAlong    ? std::sqrt(3.0)
                         : p.triangulation == Triangulation::AnisoAcross ? 1 / std::sqrt(3.0)
                                                                         : 1.0;
  s.soup = testing::torus(1.0, 0.4,
                          grid_options(p, static_cast<int>(std::lround(2 * kPi * p.cells_per_unit / stretch)),
                                       static_cast<int>(std::lround(2 * kPi * 0.4 * p.cells_per_unit * stretch))));
  s.excluded = [](const Vec3&, double) { return false; };
  return s;
}

std::vector<std::string> surface_names() {
  return {"sine", "cos-product", "ripple", "paraboloid", "superquadric", "torus"};
}

Surface make_surface(const std::string& name, const SurfaceParams& p) {
  if (name == "sine") return sine_field(p);
  if (name == "cos-product") return cosine_product(p);
  if (name == "ripple") return ripple(p);
  if (name == "paraboloid") return paraboloid_ridge(p);
  if (name == "superquadric") return superquadric(p);
  if (name == "torus") return torus(p);
  throw std::invalid_argument("unknown quality surface " + name);
}

}  // namespace crestline::quality
