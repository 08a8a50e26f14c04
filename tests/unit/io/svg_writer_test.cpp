// SVG writer: hidden-line removal against the surface, views, groups.
#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "crestline/io/write_lines.h"
#include "test_polylines.h"

using crestline::LineType;
using crestline::Mesh;
using crestline::Polyline;
using crestline::Vec3;
using crestline::io::SvgOptions;
using crestline::io::View;

namespace {

const double kPi = std::acos(-1.0);

/// The rectangle [x0,x1]×[y0,y1] in the plane z = 0, facing +z, as an n×n grid.
Mesh grid(double x0, double x1, double y0, double y1, int n) {
  Mesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) mesh.positions.push_back({x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n, 0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = static_cast<uint32_t>(j * (n + 1) + i), b = a + 1, c = a + n + 2, d = a + n + 1;
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  return mesh;
}

/// The square [-1,1]² with edges of 0.1: lines 0.1 off it are well beyond
/// the default surface tolerance (half a mean edge length).
Mesh plane() { return grid(-1, 1, -1, 1, 20); }

/// Unit UV sphere; `rings` even, so the equator y = 0 is a ring of vertices.
Mesh uv_sphere(int rings, int sectors) {
  Mesh mesh;
  mesh.positions.push_back({0, 1, 0});
  for (int r = 1; r < rings; ++r) {
    const double theta = kPi * r / rings;
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2 * kPi * s / sectors;
      mesh.positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)});
    }
  }
  mesh.positions.push_back({0, -1, 0});
  const uint32_t south = static_cast<uint32_t>(mesh.positions.size() - 1);
  auto at = [&](int r, int s) { return static_cast<uint32_t>(1 + (r - 1) * sectors + (s % sectors)); };
  for (int s = 0; s < sectors; ++s) {
    mesh.triangles.push_back({0, at(1, s), at(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r) {
      mesh.triangles.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      mesh.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
    mesh.triangles.push_back({at(rings - 1, s), south, at(rings - 1, s + 1)});
  }
  return mesh;
}

using crestline::testing::test_line;

struct Path {
  std::vector<std::pair<double, double>> points;
  bool closed = false;
  double length() const {
    double sum = 0;
    for (size_t k = 1; k < points.size(); ++k)
      sum += std::hypot(points[k].first - points[k - 1].first, points[k].second - points[k - 1].second);
    if (closed && points.size() > 1)
      sum += std::hypot(points.front().first - points.back().first, points.front().second - points.back().second);
    return sum;
  }
};

/// The <path> elements inside <g id="group">, one Path per subpath.
std::vector<Path> paths_in(const std::string& svg, const std::string& group) {
  std::vector<Path> out;
  const size_t begin = svg.find("<g id=\"" + group + "\"");
  if (begin == std::string::npos) return out;
  const size_t end = svg.find("</g>", begin);
  const std::string body = svg.substr(begin, end - begin);
  static const std::regex path_re("<path d=\"([^\"]*)\"");
  static const std::regex token_re("([MLZ])|(-?[0-9.]+),(-?[0-9.]+)");
  for (std::sregex_iterator it(body.begin(), body.end(), path_re), stop; it != stop; ++it) {
    const std::string data = (*it)[1];
    for (std::sregex_iterator t(data.begin(), data.end(), token_re); t != stop; ++t) {
      if ((*t)[1] == "M")
        out.emplace_back();
      else if ((*t)[1] == "Z")
        out.back().closed = true;
      else if ((*t)[1].length() == 0)
        out.back().points.emplace_back(std::stod((*t)[2]), std::stod((*t)[3]));
    }
  }
  return out;
}

double total_length(const std::vector<Path>& paths) {
  double sum = 0;
  for (const Path& p : paths) sum += p.length();
  return sum;
}

std::string svg_of(const std::vector<Polyline>& lines, const Mesh& surface, View view = View::Front) {
  SvgOptions options;
  options.view = view;
  return crestline::io::write_lines_svg(lines, surface, options);
}

// Drawing pixels per world unit when the bounding box's longer side is `extent`.
double scale_for(double extent) { return 1000 * (1 - 2 * 0.02) / extent; }

}  // namespace

TEST_CASE("SVG: a line in front of a plane is drawn, the same line behind it is not", "[io][svg]") {
  const Mesh surface = plane();
  const auto front = test_line(LineType::Ridge, {{-0.5, 0, 0.1}, {0, 0.01, 0.1}, {0.5, 0, 0.1}});
  const auto behind = test_line(LineType::Ridge, {{-0.5, 0, -0.1}, {0, 0.01, -0.1}, {0.5, 0, -0.1}});

  const auto drawn = paths_in(svg_of({front}, surface), "ridges");
  REQUIRE(drawn.size() == 1);
  CHECK(drawn[0].points.size() == 3);  // vertices kept, no extra samples
  CHECK(drawn[0].length() == Approx(scale_for(2) * 1.0).epsilon(0.01));

  CHECK(paths_in(svg_of({behind}, surface), "ridges").empty());

  SECTION("seen from the back, it is the other way round") {
    CHECK(paths_in(svg_of({front}, surface, View::Back), "ridges").empty());
    CHECK(paths_in(svg_of({behind}, surface, View::Back), "ridges").size() == 1);
  }
}

TEST_CASE("SVG: a line lying on the surface is visible", "[io][svg]") {
  const auto on = test_line(LineType::Valley, {{-0.9, -0.3, 0}, {0.2, 0.7, 0}, {0.9, 0.1, 0}});
  const auto drawn = paths_in(svg_of({on}, plane()), "valleys");
  REQUIRE(drawn.size() == 1);
  CHECK(drawn[0].points.size() == 3);
}

TEST_CASE("SVG: lines slightly off the surface (fairing, chords) still count as on it", "[io][svg]") {
  // Mean edge length of plane() is about 0.12; 0.02 below is within half of it.
  const auto below = test_line(LineType::Ridge, {{-0.5, 0.3, -0.02}, {0.5, 0.3, -0.02}});
  CHECK(paths_in(svg_of({below}, plane()), "ridges").size() == 1);
  SvgOptions strict;
  strict.surface_tolerance = 0;
  CHECK(paths_in(crestline::io::write_lines_svg({below}, plane(), strict), "ridges").empty());
}

TEST_CASE("SVG: a line passing behind a plane is split into its visible runs", "[io][svg]") {
  const auto across = test_line(LineType::Ridge, {{-2, 0, -0.1}, {2, 0, -0.1}});
  const auto drawn = paths_in(svg_of({across}, plane()), "ridges");
  REQUIRE(drawn.size() == 2);
  const double unit = scale_for(4);  // the line widens the bounding box to 4
  for (const Path& run : drawn) CHECK(run.length() == Approx(unit).margin(2.0));
}

TEST_CASE("SVG: the equator of a sphere shows only its front half", "[io][svg]") {
  const Mesh sphere = uv_sphere(16, 48);
  std::vector<Vec3> equator;
  for (int s = 0; s < 48; ++s) equator.push_back(sphere.positions[1 + 7 * 48 + s]);
  REQUIRE(equator[0].y() == Approx(0).margin(1e-12));
  const auto ring = test_line(LineType::Ridge, equator, true);

  // Front: a horizontal stroke across the disc, drawn once (the back half is hidden).
  const auto front = paths_in(svg_of({ring}, sphere), "ridges");
  REQUIRE(front.size() == 1);
  CHECK(total_length(front) == Approx(2 * scale_for(2)).epsilon(0.02));

  // Top: the whole ring is visible and stays one closed path.
  const auto top = paths_in(svg_of({ring}, sphere, View::Top), "ridges");
  REQUIRE(top.size() == 1);
  CHECK(top[0].closed);
  CHECK(top[0].points.size() == 48);
}

TEST_CASE("SVG: a closed line hidden in the middle stays one run across its start", "[io][svg]") {
  // Square loop starting at its left edge; its right half is behind the plane
  // x ∈ [0.5, 1.5] of a narrower occluder.
  const Mesh occluder = grid(0.25, 2, -2, 2, 20);
  const auto loop =
      test_line(LineType::Ridge, {{-1, 0, -0.5}, {-1, -1, -0.5}, {1, -1, -0.5}, {1, 1, -0.5}, {-1, 1, -0.5}}, true);
  const auto drawn = paths_in(svg_of({loop}, occluder), "ridges");
  REQUIRE(drawn.size() == 1);
  CHECK_FALSE(drawn[0].closed);
  // Visible: x ∈ [-1, 0.25] on the top and bottom edges plus the left edge.
  CHECK(drawn[0].length() == Approx(scale_for(4) * (1.25 + 1.25 + 2)).margin(2.0));
}

TEST_CASE("SVG: document structure, groups and views", "[io][svg]") {
  const auto ridge = test_line(LineType::Ridge, {{-0.5, 0.5, 0.1}, {0.5, 0.5, 0.1}});
  const auto valley = test_line(LineType::Valley, {{-0.5, -0.5, 0.1}, {0.5, -0.5, 0.1}});
  SvgOptions options;
  options.silhouette = true;
  const std::string svg = crestline::io::write_lines_svg({ridge, valley}, plane(), options);
  CHECK(svg.find("viewBox=\"0 0 1000.00 1000.00\"") != std::string::npos);
  CHECK(svg.find("stroke=\"" + options.ridge_color + "\"") != std::string::npos);
  CHECK(svg.find("stroke=\"" + options.valley_color + "\"") != std::string::npos);
  CHECK(paths_in(svg, "ridges").size() == 1);
  CHECK(paths_in(svg, "valleys").size() == 1);
  // The plane's outline: its four boundary edges chained into one closed path.
  const auto outline = paths_in(svg, "silhouette");
  REQUIRE(outline.size() == 1);
  CHECK(outline[0].closed);
  CHECK(outline[0].points.size() == 80);  // 20 grid edges per side
  CHECK(outline[0].length() == Approx(4 * 960).margin(4.0));

  // The caller's adjacency gives the same drawing as the one built inside.
  CHECK(crestline::io::write_lines_svg({ridge, valley}, plane(), crestline::build_topology(plane()), options) == svg);

  // Ridge above the valley in front view (SVG y grows downwards).
  CHECK(paths_in(svg, "ridges")[0].points[0].second < paths_in(svg, "valleys")[0].points[0].second);

  SECTION("a left view of a wide box keeps the longer side at the requested width") {
    const auto wide = test_line(LineType::Ridge, {{0, 0, -3}, {0, 1, 3}});
    const std::string left = crestline::io::write_lines_svg({wide}, Mesh{}, SvgOptions{View::Left});
    CHECK(left.find("width=\"1000.00\"") != std::string::npos);
    const auto drawn = paths_in(left, "ridges");
    REQUIRE(drawn.size() == 1);
    // Seen from -x, +z points right.
    CHECK(drawn[0].points[0].first < drawn[0].points[1].first);
  }
}

TEST_CASE("SVG: the drawing does not depend on the model's scale or position", "[io][svg]") {
  const Mesh sphere = uv_sphere(12, 24);
  std::vector<Vec3> meridian;
  for (int r = 1; r < 12; ++r) meridian.push_back(sphere.positions[1 + (r - 1) * 24 + 3]);
  const auto ridge = test_line(LineType::Ridge, meridian);
  SvgOptions options;
  options.silhouette = true;
  options.view = View::Right;
  const std::string reference = crestline::io::write_lines_svg({ridge}, sphere, options);
  CHECK(paths_in(reference, "ridges").size() == 1);
  for (const double scale : {1e-6, 1e6}) {
    INFO("scale " << scale);
    // Far from the origin compared with its size: depth must not lose precision.
    const Vec3 offset(3e4 * scale, -7e4 * scale, 11e4 * scale);
    Mesh moved = sphere;
    for (Vec3& p : moved.positions) p = p * scale + offset;
    Polyline moved_ridge = ridge;
    for (Vec3& p : moved_ridge.points) p = p * scale + offset;
    CHECK(crestline::io::write_lines_svg({moved_ridge}, moved, options) == reference);
  }
}

TEST_CASE("SVG: non-finite points are skipped, not drawn", "[io][svg]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto broken = test_line(LineType::Ridge, {{-0.5, 0, 0.1}, {0, 0, 0.1}, {nan, 0, 0.1}, {0.5, 0.5, 0.1}});
  const std::string svg = svg_of({broken}, plane());
  CHECK(svg.find("nan") == std::string::npos);
  const auto drawn = paths_in(svg, "ridges");
  REQUIRE(drawn.size() == 1);
  CHECK(drawn[0].points.size() == 2);
}

TEST_CASE("SVG: the silhouette of a sphere is one closed outline, from every side", "[io][svg]") {
  const Mesh sphere = uv_sphere(16, 48);
  SvgOptions options;
  options.silhouette = true;
  for (const View view : {View::Front, View::Back, View::Left, View::Right, View::Top, View::Bottom}) {
    INFO("view " << static_cast<int>(view));
    options.view = view;
    const auto outline = paths_in(crestline::io::write_lines_svg({}, sphere, options), "silhouette");
    REQUIRE(!outline.empty());
    // The contour of a faceted sphere is a polygon close to the disc's circumference.
    CHECK(total_length(outline) == Approx(2 * kPi * scale_for(2)).epsilon(0.03));
  }
  options.view = View::Front;
  CHECK(paths_in(crestline::io::write_lines_svg({}, sphere, options), "silhouette").size() == 1);
}

TEST_CASE("SVG: a huge drawing caps its depth buffer and still hides lines", "[io][svg]") {
  SvgOptions options;
  options.width = 100000;  // 2x supersampling would need 40 G depth pixels
  const auto front = test_line(LineType::Ridge, {{-0.5, 0, 0.1}, {0.5, 0, 0.1}});
  const auto behind = test_line(LineType::Valley, {{-0.5, 0, -0.1}, {0.5, 0, -0.1}});
  const std::string svg = crestline::io::write_lines_svg({front, behind}, plane(), options);
  REQUIRE(paths_in(svg, "ridges").size() == 1);
  CHECK(paths_in(svg, "ridges")[0].length() == Approx(100000 * 0.96 / 2).epsilon(0.001));
  CHECK(paths_in(svg, "valleys").empty());
}

TEST_CASE("SVG: empty input gives a valid, empty drawing", "[io][svg]") {
  const std::string svg = crestline::io::write_lines_svg({}, Mesh{}, SvgOptions{});
  CHECK(svg.find("<svg") != std::string::npos);
  CHECK(svg.find("</svg>") != std::string::npos);
  CHECK(paths_in(svg, "ridges").empty());
}

TEST_CASE("SVG: creases in group \"creases\", each path classed convex or concave", "[io][writers][svg][creases]") {
  auto convex = test_line(LineType::Crease, {{-0.5, 0.5, 0.1}, {0.5, 0.5, 0.1}});
  convex.convex = true;
  const auto concave = test_line(LineType::Crease, {{-0.5, -0.5, 0.1}, {0.5, -0.5, 0.1}});
  const std::string svg = svg_of({convex, concave}, plane());
  const size_t group = svg.find("<g id=\"creases\"");
  REQUIRE(group != std::string::npos);
  CHECK(svg.find("<path class=\"convex\" d=\"M", group) != std::string::npos);
  CHECK(svg.find("<path class=\"concave\" d=\"M", group) != std::string::npos);
  // Without creases there is no such group.
  CHECK(svg_of({test_line(LineType::Ridge, {{-0.5, 0, 0.1}, {0.5, 0, 0.1}})}, plane()).find("creases") ==
        std::string::npos);
}

namespace {

/// A three.js-style perspective camera at (0, 0, distance) looking along -z,
/// vertical field of view `fov_y` (radians), as projection · view.
Eigen::Matrix4d perspective_camera(double distance, double fov_y, double aspect, double near, double far) {
  const double f = 1 / std::tan(fov_y / 2);
  Eigen::Matrix4d projection;
  projection << f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), 2 * far * near / (near - far), 0, 0,
      -1, 0;
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view(2, 3) = -distance;
  return projection * view;
}

std::string camera_svg(const std::vector<Polyline>& lines, const Mesh& surface, const Eigen::Matrix4d& matrix,
                       bool silhouette = false) {
  SvgOptions options;
  options.camera = crestline::io::SvgCamera{matrix, 400, 300};
  options.silhouette = silhouette;
  return crestline::io::write_lines_svg(lines, surface, options);
}

}  // namespace

TEST_CASE("SVG with a camera: perspective projection, hidden parts and the frame", "[io][svg][camera]") {
  const double fov = kPi / 4, f = 1 / std::tan(fov / 2), aspect = 400.0 / 300.0;
  const Eigen::Matrix4d camera = perspective_camera(5, fov, aspect, 0.1, 100);
  const auto front = test_line(LineType::Ridge, {{-0.5, 0.2, 0.1}, {0.5, 0.2, 0.1}});
  const auto behind = test_line(LineType::Valley, {{-0.5, -0.2, -0.1}, {0.5, -0.2, -0.1}});
  const std::string svg = camera_svg({front, behind}, plane(), camera);
  CHECK(svg.find("viewBox=\"0 0 400.00 300.00\"") != std::string::npos);
  const auto drawn = paths_in(svg, "ridges");
  REQUIRE(drawn.size() == 1);
  REQUIRE(drawn[0].points.size() == 2);
  // Pinhole projection at distance 4.9: x = (f/aspect · X/4.9 + 1)/2 · 400, y = (1 - f · Y/4.9)/2 · 300.
  CHECK(drawn[0].points[0].first == Approx((f / aspect * -0.5 / 4.9 + 1) / 2 * 400).margin(0.01));
  CHECK(drawn[0].points[0].second == Approx((1 - f * 0.2 / 4.9) / 2 * 300).margin(0.01));
  CHECK(drawn[0].points[1].first == Approx((f / aspect * 0.5 / 4.9 + 1) / 2 * 400).margin(0.01));
  CHECK(paths_in(svg, "valleys").empty());

  SECTION("from behind the plane the other line shows") {
    Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();  // half a turn about y
    turn(0, 0) = turn(2, 2) = -1;
    const std::string back = camera_svg({front, behind}, plane(), camera * turn);
    CHECK(paths_in(back, "ridges").empty());
    CHECK(paths_in(back, "valleys").size() == 1);
  }
  SECTION("a line leaving the frame is cut at its edge") {
    const auto wide = test_line(LineType::Ridge, {{-50, 0, 0.1}, {0.3, 0, 0.1}});
    const auto cut = paths_in(camera_svg({wide}, plane(), camera), "ridges");
    REQUIRE(cut.size() == 1);
    CHECK(cut[0].points.front().first >= 0);
    CHECK(cut[0].points.front().first <= 1.0);
  }
  SECTION("a line behind the eye is not drawn") {
    const auto past = test_line(LineType::Ridge, {{-0.5, 0, 6}, {0.5, 0, 6}});
    CHECK(paths_in(camera_svg({past}, plane(), camera), "ridges").empty());
  }
}

TEST_CASE("SVG with a camera: a sphere's equator and silhouette in perspective", "[io][svg][camera]") {
  const Mesh sphere = uv_sphere(16, 48);
  std::vector<Vec3> equator;
  for (int s = 0; s < 48; ++s) equator.push_back(sphere.positions[1 + 7 * 48 + s]);
  const auto ring = test_line(LineType::Ridge, equator, true);
  const double fov = kPi / 4, f = 1 / std::tan(fov / 2);
  const std::string svg = camera_svg({ring}, sphere, perspective_camera(4, fov, 400.0 / 300.0, 0.1, 100), true);
  // Only the near half of the ring: one open run, roughly from limb to limb.
  const auto drawn = paths_in(svg, "ridges");
  REQUIRE(drawn.size() == 1);
  CHECK_FALSE(drawn[0].closed);
  // The limb seen from distance 4 lies at angle asin(1/4) off the axis.
  const double limb = std::tan(std::asin(0.25)) * f * 150;  // drawing pixels from the centre (150 = half the height)
  double x_min = 1e9, x_max = -1e9;
  for (const auto& p : drawn[0].points) x_min = std::min(x_min, p.first), x_max = std::max(x_max, p.first);
  CHECK(x_max - x_min == Approx(2 * limb).epsilon(0.05));
  // The outline: a closed curve of about that radius around the centre.
  const auto outline = paths_in(svg, "silhouette");
  REQUIRE(!outline.empty());
  CHECK(total_length(outline) == Approx(2 * kPi * limb).epsilon(0.05));
}

TEST_CASE("SVG: which groups are drawn, their colours, a background", "[io][svg]") {
  auto convex = test_line(LineType::Crease, {{-0.5, 0.5, 0.1}, {0.5, 0.5, 0.1}});
  convex.convex = true;
  const auto concave = test_line(LineType::Crease, {{-0.5, -0.5, 0.1}, {0.5, -0.5, 0.1}});
  const auto ridge = test_line(LineType::Ridge, {{-0.5, 0, 0.1}, {0.5, 0, 0.1}});
  SvgOptions options;
  options.ridges = false;
  options.concave_color = "#111111";
  options.background = "#f0f0f0\"<";
  const std::string svg = crestline::io::write_lines_svg({convex, concave, ridge}, plane(), options);
  CHECK(svg.find("id=\"ridges\"") == std::string::npos);
  CHECK(svg.find("id=\"valleys\"") != std::string::npos);
  CHECK(svg.find("<path class=\"concave\" stroke=\"#111111\" d=\"M") != std::string::npos);
  CHECK(svg.find("<rect width=\"100%\" height=\"100%\" fill=\"#f0f0f0&#34;&#60;\"/>") != std::string::npos);
  options.creases = false;
  CHECK(crestline::io::write_lines_svg({convex, concave}, plane(), options).find("creases") == std::string::npos);
}
