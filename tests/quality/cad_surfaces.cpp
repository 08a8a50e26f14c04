#include "cad_surfaces.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"
#include "point_grid.h"
#include "quality_metrics.h"

namespace crestline::quality {
namespace {

using Vec2 = Eigen::Vector2d;
using testing::kPi;

// A closed plane profile, counter-clockwise, made of lines and circular
// arcs. Each piece is sampled on its own (so that every corner is a sample);
// `samples` is the whole ring, `at(s)` the point at arc-length fraction s.
struct Profile {
  struct Piece {
    Vec2 a, b;                 // line ends; for an arc, unused
    Vec2 centre;               // arc
    double radius = 0;         // 0: a line
    double a0 = 0, a1 = 0;     // arc angles, counter-clockwise a0 < a1
    bool sharp_start = false;  // a sharp corner where this piece starts
    double length() const { return radius > 0 ? radius * (a1 - a0) : (b - a).norm(); }
    Vec2 at(double t) const {
      if (radius == 0) return a + t * (b - a);
      const double angle = a0 + t * (a1 - a0);
      return centre + radius * Vec2(std::cos(angle), std::sin(angle));
    }
  };
  std::vector<Piece> pieces;
  std::vector<Vec2> samples;
  std::vector<double> params;        // arc-length fraction of each sample
  std::vector<size_t> first_sample;  // per piece

  void line(const Vec2& a, const Vec2& b, bool sharp) { pieces.push_back({a, b, {}, 0, 0, 0, sharp}); }
  void arc(const Vec2& c, double r, double a0, double a1, bool sharp) {
    pieces.push_back({{}, {}, c, r, a0, a1, sharp});
  }
  double length() const {
    double l = 0;
    for (const Piece& p : pieces) l += p.length();
    return l;
  }
  void sample(double edge) {
    const double total = length();
    double done = 0;
    for (const Piece& p : pieces) {
      first_sample.push_back(samples.size());
      const int n = std::max(1, static_cast<int>(std::lround(p.length() / edge)));
      for (int k = 0; k < n; ++k) {
        samples.push_back(p.at(static_cast<double>(k) / n));
        params.push_back((done + p.length() * k / n) / total);
      }
      done += p.length();
    }
  }
  Vec2 at(double s) const {
    double target = s * length();
    for (const Piece& p : pieces) {
      if (target <= p.length()) return p.at(target / p.length());
      target -= p.length();
    }
    return pieces.back().at(1.0);
  }
};

Vec3 lift(const Vec2& p, double z) { return Vec3(p.x(), p.y(), z); }

// Appends `other` to `soup`.
void append(TriangleSoup& soup, const TriangleSoup& other) {
  const uint32_t base = static_cast<uint32_t>(soup.vertex_count());
  soup.positions.insert(soup.positions.end(), other.positions.begin(), other.positions.end());
  for (uint32_t i : other.indices) soup.indices.push_back(base + i);
}

// A flat cap inside the profile at height z, in rings around `centre` (the
// profile must be star-shaped about it): ring k of K is the profile scaled by
// k/K about the centre with about N·k/K points, stitched to the next ring by
// parameter. Normal +z, or −z when `down`.
TriangleSoup cap(const Profile& profile, const Vec2& centre, double z, double edge, bool down) {
  TriangleSoup s;
  double reach = 0;
  for (const Vec2& q : profile.samples) reach = std::max(reach, (q - centre).norm());
  const int rings = std::max(1, static_cast<int>(std::lround(0.8 * reach / edge)));
  const size_t n = profile.samples.size();
  testing::add_vertex(s, lift(centre, z));
  struct Ring {
    uint32_t first;
    std::vector<double> params;
  };
  Ring previous{0, {}};
  for (int k = 1; k <= rings; ++k) {
    Ring ring{static_cast<uint32_t>(s.vertex_count()), {}};
    if (k == rings) {
      ring.params = profile.params;
      for (const Vec2& q : profile.samples) testing::add_vertex(s, lift(q, z));
    } else {
      const size_t m = std::max<size_t>(6, static_cast<size_t>(std::lround(static_cast<double>(n) * k / rings)));
      const double shift = (k % 2) * 0.5 / m;
      for (size_t j = 0; j < m; ++j) {
        ring.params.push_back(j / static_cast<double>(m) + shift);
        testing::add_vertex(
            s, lift(centre + (static_cast<double>(k) / rings) * (profile.at(ring.params.back()) - centre), z));
      }
    }
    auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
      if (down)
        testing::add_triangle(s, a, c, b);
      else
        testing::add_triangle(s, a, b, c);
    };
    const size_t m = ring.params.size();
    if (k == 1) {
      for (size_t j = 0; j < m; ++j) tri(0, ring.first + j, ring.first + (j + 1) % m);
    } else {
      // Merge the two rings by parameter (both start near 0 and increase).
      const size_t p = previous.params.size();
      size_t i = 0, j = 0;
      while (i < p || j < m) {
        const double next_inner = i < p ? (i + 1 < p ? previous.params[i + 1] : 1 + previous.params[0]) : 2;
        const double next_outer = j < m ? (j + 1 < m ? ring.params[j + 1] : 1 + ring.params[0]) : 2;
        const uint32_t a = previous.first + i % p, b = ring.first + j % m;
        if (next_outer <= next_inner) {
          tri(a, b, ring.first + (j + 1) % m);
          ++j;
        } else {
          tri(a, b, previous.first + (i + 1) % p);
          ++i;
        }
      }
    }
    previous = ring;
  }
  return s;
}

testing::GridOptions grid_options(const CadParams& p, int nu, int nv) {
  testing::GridOptions g;
  g.nu = nu;
  g.nv = nv;
  g.periodic_u = true;
  g.seed = p.seed;
  g.diagonals = p.triangulation == Triangulation::Uniform       ? testing::Diagonals::Uniform
                : p.triangulation == Triangulation::Alternating ? testing::Diagonals::Alternating
                                                                : testing::Diagonals::Random;
  return g;
}

// A band between two rings of the same profile samples, (x,y) → lower(x,y) at
// v = 0 and upper(x,y) at v = 1; outward if the profile is counter-clockwise.
TriangleSoup band(const Profile& profile, const std::function<Vec3(const Vec2&, double)>& at, int nv,
                  const CadParams& p) {
  const int nu = static_cast<int>(profile.samples.size());
  return testing::parametric_grid(
      [&](double u, double v) {
        const int i = static_cast<int>(std::lround(u * nu)) % nu;
        return at(profile.samples[i], v);
      },
      grid_options(p, nu, nv));
}

SharpEdge sampled(const std::function<Vec3(double)>& curve, double length, bool closed, bool convex, double angle,
                  double edge) {
  SharpEdge e;
  e.closed = closed;
  e.convex = convex;
  e.angle = angle;
  const int n = std::max(2, static_cast<int>(std::ceil(20 * length / edge)));
  for (int k = 0; k <= n - (closed ? 1 : 0); ++k) e.points.push_back(curve(static_cast<double>(k) / n));
  return e;
}

// A prism: the profile extruded from z = 0 to `height`, with caps. Its sharp
// edges: the vertical edges at the profile's sharp corners, and the top and
// bottom outlines split at those corners (closed loops if there is none).
CadSurface prism(const std::string& name, Profile profile, const Vec2& centre, double height, const CadParams& p) {
  CadSurface out;
  out.name = name;
  profile.sample(p.edge);
  const int nv = std::max(2, static_cast<int>(std::lround(height / p.edge)));
  append(out.soup, band(
                       profile, [&](const Vec2& q, double v) { return lift(q, v * height); }, nv, p));
  append(out.soup, cap(profile, centre, height, p.edge, false));
  append(out.soup, cap(profile, centre, 0.0, p.edge, true));

  // Outline runs between sharp corners, as ranges of pieces.
  std::vector<size_t> corners;
  for (size_t i = 0; i < profile.pieces.size(); ++i)
    if (profile.pieces[i].sharp_start) corners.push_back(i);
  const size_t np = profile.pieces.size();
  auto outline = [&](size_t first, size_t count, double z, bool closed) {
    double len = 0;
    for (size_t k = 0; k < count; ++k) len += profile.pieces[(first + k) % np].length();
    return sampled(
        [&, first, count, len, z](double t) {
          double target = t * len;
          for (size_t k = 0; k < count; ++k) {
            const auto& piece = profile.pieces[(first + k) % np];
            if (target <= piece.length() || k + 1 == count)
              return lift(piece.at(std::min(1.0, target / piece.length())), z);
            target -= piece.length();
          }
          return Vec3(lift(profile.pieces[first].at(0), z));
        },
        len, closed, true, 90, p.edge);
  };
  for (double z : {0.0, height}) {
    if (corners.empty()) {
      out.edges.push_back(outline(0, np, z, true));
      continue;
    }
    for (size_t c = 0; c < corners.size(); ++c) {
      const size_t next = corners[(c + 1) % corners.size()];
      const size_t count = (next + np - corners[c] - 1) % np + 1;
      out.edges.push_back(outline(corners[c], count, z, false));
    }
  }
  for (size_t c : corners) {
    // The turn of the outline at the corner: its sign says convex or concave.
    const auto& before = profile.pieces[(c + np - 1) % np];
    const auto& after = profile.pieces[c];
    const Vec2 d0 = (before.at(1.0) - before.at(0.99)).normalized(), d1 = (after.at(0.01) - after.at(0.0)).normalized();
    const double turn = std::atan2(d0.x() * d1.y() - d0.y() * d1.x(), d0.dot(d1)) * 180 / kPi;
    const Vec2 q = after.at(0.0);
    out.edges.push_back(
        sampled([&, q](double t) { return lift(q, t * height); }, height, false, turn > 0, std::abs(turn), p.edge));
  }
  return out;
}

}  // namespace

CadSurface filleted_box(const CadParams& p) {
  const double r = 0.3;
  Profile profile;
  // From the sharp corner (−1, −1) counter-clockwise; the corners at x = +1 are filleted.
  profile.line({-1, -1}, {1 - r, -1}, true);
  profile.arc({1 - r, -1 + r}, r, -kPi / 2, 0, false);
  profile.line({1, -1 + r}, {1, 1 - r}, false);
  profile.arc({1 - r, 1 - r}, r, 0, kPi / 2, false);
  profile.line({1 - r, 1}, {-1, 1}, false);
  profile.line({-1, 1}, {-1, -1}, true);
  return prism("filleted-box", profile, {0, 0}, 1.0, p);
}

CadSurface notched_prism(const CadParams& p) {
  Profile profile;
  const Vec2 corners[] = {{-1, -1}, {1, -1}, {1, 1}, {0, 0.4}, {-1, 1}};
  for (int i = 0; i < 5; ++i) profile.line(corners[i], corners[(i + 1) % 5], true);
  return prism("notched-prism", profile, {0, -0.4}, 1.0, p);
}

CadSurface chamfered_cylinder(const CadParams& p) {
  const double radius = 1.0, height = 1.2, chamfer = 0.25;
  CadSurface out;
  out.name = "chamfered-cylinder";
  Profile circle;
  circle.arc({0, 0}, radius, 0, 2 * kPi, false);
  circle.sample(p.edge);
  Profile inner;  // the top cap's outline: the same angles, radius − chamfer
  inner.arc({0, 0}, radius - chamfer, 0, 2 * kPi, false);
  inner.samples = circle.samples;
  inner.params = circle.params;
  for (Vec2& q : inner.samples) q *= (radius - chamfer) / radius;
  const double wall = height - chamfer;
  const int nv_wall = static_cast<int>(std::lround(wall / p.edge));
  const int nv_chamfer = std::max(2, static_cast<int>(std::lround(chamfer * std::sqrt(2.0) / p.edge)));
  append(out.soup, band(
                       circle, [&](const Vec2& q, double v) { return lift(q, v * wall); }, nv_wall, p));
  append(out.soup,
         band(
             circle, [&](const Vec2& q, double v) { return lift(q * (1 - v * chamfer / radius), wall + v * chamfer); },
             nv_chamfer, p));
  append(out.soup, cap(inner, {0, 0}, height, p.edge, false));
  append(out.soup, cap(circle, {0, 0}, 0.0, p.edge, true));
  auto ring = [&](double r, double z, double angle) {
    return sampled([=](double t) { return Vec3(r * std::cos(2 * kPi * t), r * std::sin(2 * kPi * t), z); }, 2 * kPi * r,
                   true, true, angle, p.edge);
  };
  out.edges = {ring(radius, 0, 90), ring(radius, wall, 45), ring(radius - chamfer, height, 45)};
  return out;
}

std::vector<std::string> cad_surface_names() { return {"filleted-box", "chamfered-cylinder", "notched-prism"}; }

CadSurface make_cad_surface(const std::string& name, const CadParams& p) {
  if (name == "filleted-box") return filleted_box(p);
  if (name == "chamfered-cylinder") return chamfered_cylinder(p);
  return notched_prism(p);
}

CadCase make_cad_case(const std::string& name, Triangulation t, double noise, unsigned noise_seed, CadParams params) {
  CadCase c;
  params.triangulation = t;
  c.surface = make_cad_surface(name, params);
  c.clean = testing::repaired_in_input_order(c.surface.soup);
  c.h = mean_edge_length(c.clean);
  c.mesh = c.clean;
  if (noise > 0) testing::add_normal_noise(c.mesh, noise * c.h, noise_seed);
  return c;
}

CreaseResult find_creases(const Mesh& mesh, const Topology& topology, const CreaseOptions& options, double h,
                          CreaseAngles* angles) {
  const CreaseAngles measured = measure_crease_angles(mesh, topology, {options.normal_filter_steps});
  CreaseResult result = select_creases(mesh, topology, measured, options, h);
  if (angles) *angles = measured;
  return result;
}

CreaseResult smooth_surface_creases(const std::string& name, Triangulation t, double noise,
                                    const CreaseOptions& options, CreaseAngles* angles) {
  SurfaceParams p;
  p.triangulation = t;
  double h = 0;
  const Mesh mesh = noisy_mesh(make_surface(name, p), noise, 101, h);
  return find_creases(mesh, build_topology(mesh), options, h, angles);
}

std::vector<Polyline> sharp_edges_as_lines(const CadSurface& surface) {
  std::vector<Polyline> out;
  for (const SharpEdge& e : surface.edges) {
    Polyline l;
    l.type = LineType::Crease;
    l.points = e.points;
    l.closed = e.closed;
    l.convex = e.convex;
    out.push_back(std::move(l));
  }
  return out;
}

SmoothNearCreases smooth_lines_near(const std::vector<Polyline>& sharp, const std::vector<Polyline>& lines, double h,
                                    double radius, const std::vector<Polyline>& away, double away_radius) {
  SmoothNearCreases out;
  const double tol = radius * h;
  PointGrid truth(tol), found(away_radius * h);
  for (size_t e = 0; e < sharp.size(); ++e)
    for (const Sample& s : resample(sharp[e], 0.1 * h)) truth.add(s.point, static_cast<uint32_t>(e));
  for (const Polyline& l : away)
    for (const Sample& s : resample(l, 0.1 * h)) found.add(s.point, 0);
  for (const Polyline& line : lines) {
    if (line.type == LineType::Crease) continue;
    ++out.lines;
    for (const Sample& s : resample(line, 0.25 * h)) {
      out.length += s.length / h;
      if (truth.any_near(s.point, tol) && !found.any_near(s.point, away_radius * h)) out.near_length += s.length / h;
    }
  }
  return out;
}

Pipeline run_cad_pipeline(const CadCase& c, const PipelineOptions& options) {
  Pipeline p(c.mesh);
  p.set_options(options);
  p.run();
  return p;
}

CreaseScore score_creases(const CadSurface& surface, const std::vector<Polyline>& creases, double h) {
  CreaseScore score;
  const double tol = 1.0 * h;
  // True edges as samples tagged by edge index.
  PointGrid truth(tol);
  std::vector<std::vector<Sample>> truth_samples;
  const std::vector<Polyline> sharp = sharp_edges_as_lines(surface);
  for (size_t e = 0; e < sharp.size(); ++e) {
    truth_samples.push_back(resample(sharp[e], 0.1 * h));
    for (const Sample& s : truth_samples.back())
      truth.add(s.point, static_cast<uint32_t>(e)), score.true_length += s.length;
  }
  score.true_edges = static_cast<int>(surface.edges.size());
  PointGrid lines(tol);
  std::vector<int> along(surface.edges.size(), 0);
  double precise = 0;
  for (size_t l = 0; l < creases.size(); ++l) {
    if (creases[l].type != LineType::Crease) continue;
    ++score.lines;
    std::vector<double> near_length(surface.edges.size(), 0);
    for (const Sample& s : resample(creases[l], 0.25 * h)) {
      lines.add(s.point, static_cast<uint32_t>(l));
      score.extracted_length += s.length;
      std::set<uint32_t> near;
      truth.near(s.point, tol, [&](uint32_t e) { near.insert(e); });
      if (!near.empty()) precise += s.length;
      for (uint32_t e : near) near_length[e] += s.length;
    }
    for (size_t e = 0; e < surface.edges.size(); ++e)
      if (near_length[e] >= 3 * h) {
        ++along[e];
        if (creases[l].convex != surface.edges[e].convex) ++score.wrong_sign;
      }
  }
  score.precision = score.extracted_length > 0 ? precise / score.extracted_length : 1;
  double covered = 0;
  for (const auto& samples : truth_samples)
    for (const Sample& s : samples)
      if (lines.any_near(s.point, tol)) covered += s.length;
  score.coverage = score.true_length > 0 ? covered / score.true_length : 1;
  int with_lines = 0, total = 0;
  for (int n : along)
    if (n > 0) ++with_lines, total += n;
  score.fragments = with_lines ? static_cast<double>(total) / with_lines : 0;
  return score;
}

std::string crease_target_failures(const CreaseScore& s) {
  std::ostringstream out;
  if (s.coverage < 0.98) out << "coverage " << s.coverage << " < 0.98; ";
  if (s.precision < 0.95) out << "precision " << s.precision << " < 0.95; ";
  if (s.fragments > 1.2) out << "fragments " << s.fragments << " > 1.2; ";
  if (s.wrong_sign > 0) out << s.wrong_sign << " lines with the wrong sign; ";
  return out.str();
}

}  // namespace crestline::quality
