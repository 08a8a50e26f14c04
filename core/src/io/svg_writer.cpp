// Orthographic SVG drawing of feature lines with hidden parts removed.
//
// The surface is rasterized into a depth buffer at twice the drawing's
// resolution; each polyline is then sampled (at least one sample per depth
// pixel) and split into runs of visible samples. Cost: linear in the number
// of triangles plus the covered pixels plus the projected line length.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "crestline/io/write_lines.h"
#include "crestline/mesh/topology.h"

namespace crestline::io {
namespace {

/// right × up = toward (toward the viewer); depth grows toward the viewer.
struct Camera {
  Vec3 right, up, toward;
};

Camera camera_for(View view) {
  const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY(), z = Vec3::UnitZ();
  switch (view) {
    case View::Back:
      return {-x, y, -z};  // looking along +z
    case View::Left:
      return {z, y, -x};  // from -x, looking along +x
    case View::Right:
      return {-z, y, x};  // from +x, looking along -x
    case View::Top:
      return {x, -z, y};  // from +y, looking down, front at the bottom
    case View::Bottom:
      return {x, z, -y};  // from -y, looking up
    case View::Front:
    default:
      return {x, y, z};  // looking along -z, +y up
  }
}

constexpr double kSupersample = 2;   // depth pixels per drawing pixel…
constexpr double kMaxRaster = 8192;  // …up to this many on the longer side (memory)
constexpr double kMarginFraction = 0.02;

/// Maps world points to drawing coordinates (x right, y down) and a depth
/// key that is affine in the drawing (so it can be interpolated across a
/// triangle) and grows toward the viewer.
struct Projection {
  Camera camera;
  double u_min = 0, v_max = 0, scale = 1, margin = 0;
  double depth_origin = 0;       // depth is stored as float: measure it from the model
  double width = 0, height = 0;  // of the drawing, in drawing pixels
  // With an SvgCamera: the drawing is its frame; parts outside it are hidden.
  bool framed = false;
  bool perspective = false;  // key 1/w (w: distance in front of the eye); else key = depth
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  double depth_scale = 1;  // orthographic camera: model units per unit of clip z
  double lateral = 1;      // model units per unit of NDC y (× w in perspective)

  Vec3 operator()(const Vec3& p) const {
    if (!framed)
      return {(p.dot(camera.right) - u_min) * scale + margin, (v_max - p.dot(camera.up)) * scale + margin,
              p.dot(camera.toward) - depth_origin};
    const Eigen::Vector4d c = matrix * p.homogeneous();
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    // Behind the eye or outside the near/far planes: never drawn, never hides.
    if (!(c.w() > 0) || c.z() < -c.w() || c.z() > c.w()) return Vec3::Constant(nan);
    const double x = (c.x() / c.w() + 1) * 0.5 * width, y = (1 - c.y() / c.w()) * 0.5 * height;
    return {x, y, perspective ? 1.0 / c.w() : -c.z() * depth_scale - depth_origin};
  }

  /// Distance from the viewer (up to a constant) of a depth key, model units.
  double distance(double key) const { return perspective ? 1.0 / key : -key; }

  /// Whether a triangle at `a` with this normal faces the viewer.
  bool faces(const Vec3& normal, const Vec3& a) const {
    if (!framed) return normal.dot(camera.toward) > 0;
    if (!perspective) return normal.dot(-matrix.row(2).head<3>().transpose()) > 0;
    // The eye: where clip x, y and w vanish.
    Eigen::Matrix3d rows;
    rows << matrix.row(0).head<3>(), matrix.row(1).head<3>(), matrix.row(3).head<3>();
    const Vec3 eye = rows.partialPivLu().solve(-Vec3(matrix(0, 3), matrix(1, 3), matrix(3, 3)));
    return normal.dot(eye - a) > 0;
  }
};

Projection camera_projection(const Mesh& surface, const SvgCamera& camera) {
  Projection proj;
  proj.framed = true;
  proj.matrix = camera.matrix;
  proj.width = std::max(1, camera.width);
  proj.height = std::max(1, camera.height);
  proj.perspective = camera.matrix.row(3) != Eigen::RowVector4d(0, 0, 0, 1);
  const double z_norm = camera.matrix.row(2).head<3>().norm();
  proj.depth_scale = z_norm > 0 ? 1.0 / z_norm : 1.0;
  const double y_norm = camera.matrix.row(1).head<3>().norm();
  proj.lateral = y_norm > 0 ? 1.0 / y_norm : 1.0;
  if (!proj.perspective) {
    double key_min = std::numeric_limits<double>::infinity();
    for (const Vec3& p : surface.positions) key_min = std::min(key_min, proj(p).z());
    if (std::isfinite(key_min)) proj.depth_origin = key_min;
  }
  return proj;
}

Projection make_projection(const std::vector<Polyline>& lines, const Mesh& surface, const SvgOptions& options) {
  if (options.camera) return camera_projection(surface, *options.camera);
  Projection proj;
  proj.camera = camera_for(options.view);
  constexpr double inf = std::numeric_limits<double>::infinity();
  double u_min = inf, u_max = -inf, v_min = inf, v_max = -inf, w_min = inf;
  auto extend = [&](const Vec3& p) {
    const double u = p.dot(proj.camera.right), v = p.dot(proj.camera.up), w = p.dot(proj.camera.toward);
    if (!std::isfinite(u) || !std::isfinite(v) || !std::isfinite(w)) return;
    u_min = std::min(u_min, u), u_max = std::max(u_max, u);
    v_min = std::min(v_min, v), v_max = std::max(v_max, v);
    w_min = std::min(w_min, w);
  };
  for (const Vec3& p : surface.positions) extend(p);
  for (const Polyline& line : lines)
    for (const Vec3& p : line.points) extend(p);
  if (u_min > u_max) u_min = u_max = v_min = v_max = w_min = 0;  // nothing to draw
  proj.depth_origin = w_min;

  const double longer = std::max(1, options.width);
  proj.margin = kMarginFraction * longer;
  const double extent = std::max(u_max - u_min, v_max - v_min);
  proj.scale = extent > 0 ? (longer - 2 * proj.margin) / extent : 1.0;
  proj.u_min = u_min;
  proj.v_max = v_max;
  proj.width = (u_max - u_min) * proj.scale + 2 * proj.margin;
  proj.height = (v_max - v_min) * proj.scale + 2 * proj.margin;
  return proj;
}

/// Largest depth (nearest surface) per depth pixel; -inf where empty.
class DepthBuffer {
 public:
  DepthBuffer(const Mesh& surface, const Projection& proj, double surface_tolerance)
      : framed_(proj.framed), perspective_(proj.perspective) {
    factor_ = std::min(kSupersample, kMaxRaster / std::max({proj.width, proj.height, 1.0}));
    width_ = static_cast<int>(std::ceil(proj.width * factor_));
    height_ = static_cast<int>(std::ceil(proj.height * factor_));
    depth_.assign(static_cast<size_t>(width_) * height_, -std::numeric_limits<float>::infinity());
    std::vector<Vec3> raster(surface.positions.size());
    double d_min = std::numeric_limits<double>::infinity(), d_max = -d_min;
    for (size_t v = 0; v < raster.size(); ++v) {
      raster[v] = proj(surface.positions[v]);
      raster[v].x() *= factor_;
      raster[v].y() *= factor_;
      d_min = std::min(d_min, raster[v].z());
      d_max = std::max(d_max, raster[v].z());
    }
    for (const Triangle& t : surface.triangles) fill(raster[t[0]], raster[t[1]], raster[t[2]]);
    // The lines lie ON the surface: accept samples behind it by ~2 depth
    // pixels or the lines' own distance from the surface, whichever is
    // larger, plus a small fraction of the depth range (float depth).
    const double off_surface = surface_tolerance * mean_edge_length(surface);
    if (!proj.framed) {
      const double range = d_max > d_min ? d_max - d_min : 0.0;
      tolerance_ = std::max(2.0 / (proj.scale * factor_), off_surface) + 1e-3 * range;
      return;
    }
    // A camera: the same in model units, a depth pixel measured at the far side.
    const double near = proj.distance(d_max), far = proj.distance(d_min);  // larger keys are nearer
    const double range = d_max > d_min ? far - near : 0.0;
    const double pixel = 2.0 / (proj.height * factor_) * proj.lateral * (proj.perspective ? far : 1.0);
    tolerance_ = std::max(2 * pixel, off_surface) + 1e-3 * range;
  }

  /// `q` in drawing coordinates with depth. Compared with the farthest of the
  /// four depth pixels around it, so a point on a steep but visible surface is
  /// not hidden by the surface's own slope between pixel centres.
  bool visible(const Vec3& q) const {
    if (!q.allFinite()) return false;  // never draw (or index with) NaN
    const double x = q.x() * factor_ - 0.5, y = q.y() * factor_ - 0.5;
    if (framed_ && (x < -0.5 || y < -0.5 || x >= width_ - 0.5 || y >= height_ - 0.5)) return false;
    const int i0 = static_cast<int>(std::floor(x)), j0 = static_cast<int>(std::floor(y));
    float farthest = std::numeric_limits<float>::infinity();
    for (int j = j0; j <= j0 + 1; ++j)
      for (int i = i0; i <= i0 + 1; ++i) {
        if (i < 0 || j < 0 || i >= width_ || j >= height_) {
          if (framed_) continue;  // the frame's edge: its inner pixels decide
          return true;
        }
        farthest = std::min(farthest, depth_[static_cast<size_t>(j) * width_ + i]);
      }
    if (!perspective_) return q.z() >= farthest - tolerance_;
    // Keys are 1/distance: compare distances; an empty pixel hides nothing.
    return farthest == -std::numeric_limits<float>::infinity() || 1.0 / q.z() <= 1.0 / farthest + tolerance_;
  }

  /// Depth pixels per drawing pixel.
  double factor() const { return factor_; }

 private:
  void fill(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (!(std::abs(area) > 0)) return;  // edge-on (or NaN): its neighbours cover it
    const int i_lo = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}) - 0.5)));
    const int i_hi = std::min(width_ - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}) - 0.5)));
    const int j_lo = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}) - 0.5)));
    const int j_hi = std::min(height_ - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}) - 0.5)));
    // Slightly inclusive edge test so shared edges leave no cracks.
    const double eps = -1e-9;
    const double inv = 1.0 / area;
    for (int j = j_lo; j <= j_hi; ++j) {
      const double py = j + 0.5;
      for (int i = i_lo; i <= i_hi; ++i) {
        const double px = i + 0.5;
        const double w0 = ((b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px)) * inv;
        const double w1 = ((c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px)) * inv;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < eps || w1 < eps || w2 < eps) continue;
        const float d = static_cast<float>(w0 * a.z() + w1 * b.z() + w2 * c.z());
        float& slot = depth_[static_cast<size_t>(j) * width_ + i];
        slot = std::max(slot, d);
      }
    }
  }

  bool framed_ = false, perspective_ = false;
  double factor_ = kSupersample;
  int width_ = 0, height_ = 0;
  std::vector<float> depth_;
  double tolerance_ = 0;
};

/// A visible piece of a line, in drawing coordinates.
struct Run {
  std::vector<Vec3> points;
  bool closed = false;
};

/// Splits a projected polyline into visible runs. Vertices are kept; inside a
/// segment only the samples where visibility changes become points.
std::vector<Run> visible_runs(const std::vector<Vec3>& projected, bool closed, const DepthBuffer& depth) {
  constexpr double kMaxSamples = 1 << 24;
  std::vector<Run> runs;
  const size_t n = projected.size();
  if (n < 2) return runs;
  const size_t segments = closed ? n : n - 1;
  Run current;
  bool open = false;     // a run is being built
  bool pending = false;  // `last` is a visible sample not yet in the run
  Vec3 last;
  bool any_hidden = false;
  auto finish = [&] {
    if (pending) current.points.push_back(last);
    if (current.points.size() >= 2) runs.push_back(std::move(current));
    current = Run{};
    open = pending = false;
  };
  for (size_t s = 0; s < segments; ++s) {
    const Vec3& a = projected[s];
    const Vec3& b = projected[(s + 1) % n];
    // One sample a pixel; a segment with a non-finite end keeps its ends only
    // (never drawn), and the count is bounded so that it stays an int.
    // sqrt of the sum of squares, which IEEE 754 rounds the same everywhere
    // (the C library's hypot differs between glibc and Emscripten in the
    // last bit, and ceil below would turn that into another sample count);
    // hypot only where the squares overflow.
    const double dx = b.x() - a.x(), dy = b.y() - a.y();
    double length = std::sqrt(dx * dx + dy * dy);
    if (std::isinf(length)) length = std::hypot(dx, dy);
    const double pixels = length * depth.factor();
    const int samples = std::isfinite(pixels) ? static_cast<int>(std::clamp(std::ceil(pixels), 1.0, kMaxSamples)) : 1;
    for (int k = s == 0 ? 0 : 1; k <= samples; ++k) {
      const double t = static_cast<double>(k) / samples;
      const Vec3 q = k == samples ? b : Vec3(a + t * (b - a));
      if (!depth.visible(q)) {
        any_hidden = true;
        if (open) finish();
        continue;
      }
      if (!open) {
        current.points.push_back(q);
        open = true;
        pending = false;
      } else if (k == samples) {
        current.points.push_back(q);  // a line vertex: always kept
        pending = false;
      } else {
        last = q;
        pending = true;
      }
    }
  }
  const bool reaches_end = open;
  finish();
  if (closed && !any_hidden && runs.size() == 1) {
    // Visible all round: the last point repeats the first.
    runs[0].points.pop_back();
    runs[0].closed = true;
  } else if (closed && reaches_end && runs.size() >= 2 && runs[0].points[0] == projected[0]) {
    // The last run continues into the first one across the start vertex.
    Run& tail = runs.back();
    tail.points.insert(tail.points.end(), runs[0].points.begin() + 1, runs[0].points.end());
    runs.erase(runs.begin());
  }
  return runs;
}

void append_coord(std::string& out, double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
  out += buffer;
}

void append_path_data(std::string& out, const Run& run) {
  for (size_t k = 0; k < run.points.size(); ++k) {
    out += k == 0 ? "M" : (k == 1 ? " L" : " ");
    append_coord(out, run.points[k].x());
    out += ',';
    append_coord(out, run.points[k].y());
  }
  if (run.closed) out += " Z";
}

/// An attribute value: colours may come from a page's CSS.
std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&' || c == '<' || c == '>' || c == '"')
      out += "&#" + std::to_string(static_cast<int>(c)) + ';';
    else
      out += c;
  }
  return out;
}

void open_group(std::string& out, const char* id, const std::string& color, double width) {
  out += "<g id=\"";
  out += id;
  out += "\" fill=\"none\" stroke=\"";
  out += escaped(color);
  out += "\" stroke-width=\"";
  append_coord(out, width);
  out += "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
}

/// Joins pieces that share end points (silhouette edges meet at vertices,
/// which project to bit-identical points) into longer runs, so an outline is
/// drawn with joins instead of a stack of caps, and each vertex only once.
std::vector<Run> chain_runs(std::vector<Run> pieces) {
  struct KeyHash {
    size_t operator()(const std::pair<double, double>& k) const {
      return std::hash<double>()(k.first) * 31 + std::hash<double>()(k.second);
    }
  };
  auto key = [](const Vec3& p) { return std::make_pair(p.x(), p.y()); };
  // End id 2i is the start of piece i, 2i+1 its end.
  std::unordered_map<std::pair<double, double>, std::vector<uint32_t>, KeyHash> ends;
  for (uint32_t i = 0; i < pieces.size(); ++i) {
    ends[key(pieces[i].points.front())].push_back(2 * i);
    ends[key(pieces[i].points.back())].push_back(2 * i + 1);
  }
  std::vector<uint8_t> used(pieces.size(), 0);
  // Appends an unused piece that touches the chain's last point; false if none.
  auto extend = [&](Run& chain) {
    const auto found = ends.find(key(chain.points.back()));
    if (found == ends.end()) return false;
    for (const uint32_t id : found->second) {
      if (used[id / 2]) continue;
      used[id / 2] = 1;
      const std::vector<Vec3>& p = pieces[id / 2].points;
      if (id % 2 == 0)
        chain.points.insert(chain.points.end(), p.begin() + 1, p.end());
      else
        chain.points.insert(chain.points.end(), p.rbegin() + 1, p.rend());
      return true;
    }
    return false;
  };
  std::vector<Run> chains;
  for (uint32_t i = 0; i < pieces.size(); ++i) {
    if (used[i]) continue;
    used[i] = 1;
    Run chain = std::move(pieces[i]);
    while (extend(chain)) {
    }
    std::reverse(chain.points.begin(), chain.points.end());
    while (extend(chain)) {
    }
    if (chain.points.size() > 3 && chain.points.front() == chain.points.back()) {
      chain.points.pop_back();
      chain.closed = true;
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

/// Edges where the surface turns away from the viewer, and boundary edges.
std::vector<Run> silhouette_runs(const Mesh& surface, const Topology& topology, const Projection& proj,
                                 const DepthBuffer& depth) {
  std::vector<Run> runs;
  std::vector<uint8_t> front(surface.triangles.size());
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    const Triangle& tri = surface.triangles[t];
    const Vec3& a = surface.positions[tri[0]];
    const Vec3 normal = (surface.positions[tri[1]] - a).cross(surface.positions[tri[2]] - a);
    front[t] = proj.faces(normal, a);
  }
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const auto& [t0, t1] = topology.edge_triangles[e];
    if (t0 >= front.size() || (t1 != kNone && t1 >= front.size())) continue;  // not this mesh's
    // Boundary edges outline an open surface from either side.
    const bool outline = t1 == kNone || front[t0] != front[t1];
    if (!outline) continue;
    const std::vector<Vec3> edge = {proj(surface.positions[topology.edges[e][0]]),
                                    proj(surface.positions[topology.edges[e][1]])};
    for (Run& run : visible_runs(edge, false, depth)) runs.push_back(std::move(run));
  }
  return chain_runs(std::move(runs));
}

}  // namespace

std::string write_lines_svg(const std::vector<Polyline>& lines, const Mesh& surface, const SvgOptions& options) {
  // Adjacency only matters for the silhouette.
  const Topology topology = options.silhouette && !surface.triangles.empty() ? build_topology(surface) : Topology{};
  return write_lines_svg(lines, surface, topology, options);
}

std::string write_lines_svg(const std::vector<Polyline>& lines, const Mesh& surface, const Topology& topology,
                            const SvgOptions& options) {
  const Projection proj = make_projection(lines, surface, options);
  const DepthBuffer depth(surface, proj, options.surface_tolerance);

  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"";
  std::string width, height;
  append_coord(width, proj.width);
  append_coord(height, proj.height);
  out += " width=\"" + width + "\" height=\"" + height + "\" viewBox=\"0 0 " + width + ' ' + height + "\">\n";
  if (!options.background.empty())
    out += "<rect width=\"100%\" height=\"100%\" fill=\"" + escaped(options.background) + "\"/>\n";

  if (options.silhouette) {
    // One path with a subpath per visible edge piece: thousands of tiny
    // elements would bloat the file for no visual gain.
    open_group(out, "silhouette", options.silhouette_color, 0.6 * options.stroke_width);
    std::string data;
    for (const Run& run : silhouette_runs(surface, topology, proj, depth)) {
      if (!data.empty()) data += ' ';
      append_path_data(data, run);
    }
    if (!data.empty()) out += "<path d=\"" + data + "\"/>\n";
    out += "</g>\n";
  }

  const struct {
    LineType type;
    const char* id;
    const std::string& color;
    bool shown;
  } groups[] = {{LineType::Ridge, "ridges", options.ridge_color, options.ridges},
                {LineType::Valley, "valleys", options.valley_color, options.valleys},
                {LineType::Crease, "creases", options.crease_color, options.creases}};
  const std::string concave = options.concave_color.empty() || options.concave_color == options.crease_color
                                  ? "<path class=\"concave\" d=\""
                                  : "<path class=\"concave\" stroke=\"" + escaped(options.concave_color) + "\" d=\"";
  std::vector<Vec3> projected;
  for (const auto& group : groups) {
    if (!group.shown) continue;
    // Ridges and valleys always have their group; creases only when there are any.
    const bool crease = group.type == LineType::Crease;
    if (crease &&
        std::none_of(lines.begin(), lines.end(), [](const Polyline& l) { return l.type == LineType::Crease; }))
      continue;
    open_group(out, group.id, group.color, options.stroke_width);
    for (const Polyline& line : lines) {
      if (line.type != group.type) continue;
      projected.clear();
      for (const Vec3& p : line.points) projected.push_back(proj(p));
      for (const Run& run : visible_runs(projected, line.closed, depth)) {
        out += crease ? (line.convex ? "<path class=\"convex\" d=\"" : concave) : "<path d=\"";
        append_path_data(out, run);
        out += "\"/>\n";
      }
    }
    out += "</g>\n";
  }
  out += "</svg>\n";
  return out;
}

}  // namespace crestline::io
