// OBJ and JSON line writers: the file contracts other tools rely on.
#include "crestline/io/write_lines.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "crestline/numerics/parallel.h"

using crestline::LineType;
using crestline::Polyline;
using crestline::Vec3;

namespace {

Polyline make_line(LineType type, std::vector<Vec3> points, bool closed, double strength) {
  Polyline line;
  line.type = type;
  line.points = std::move(points);
  line.curvature.assign(line.points.size(), 1.0);
  line.closed = closed;
  line.strength = strength;
  line.length = 1.0;
  return line;
}

// `count` lines of 1-12 random points in [-2, 2]³, of every type, some
// closed, some too short for OBJ, with random strengths and convexity.
std::vector<Polyline> random_lines(std::mt19937& random, int count) {
  std::uniform_real_distribution<double> coordinate(-2, 2);
  std::vector<Polyline> lines;
  for (int i = 0; i < count; ++i) {
    std::vector<Vec3> points(size_t(1 + random() % 12));
    for (Vec3& p : points) p = Vec3(coordinate(random), coordinate(random), coordinate(random));
    const auto type = static_cast<LineType>(random() % 3);
    lines.push_back(make_line(type, std::move(points), random() % 4 == 0, coordinate(random)));
    lines.back().convex = random() % 2 == 0;
  }
  return lines;
}

// `vertices` random points and a triangle at each (with its next and 7th next).
crestline::Mesh random_surface(std::mt19937& random, uint32_t vertices) {
  std::uniform_real_distribution<double> coordinate(-2, 2);
  crestline::Mesh mesh;
  for (uint32_t v = 0; v < vertices; ++v) {
    mesh.positions.emplace_back(coordinate(random), coordinate(random), coordinate(random));
    mesh.triangles.push_back({v, (v + 1) % vertices, (v + 7) % vertices});
  }
  return mesh;
}

// Ridges and valleys interleaved on purpose: writers must group them.
std::vector<Polyline> sample_lines() {
  return {
      make_line(LineType::Valley, {{0, 0, 0}, {1, 0, 0}}, false, 0.5),
      make_line(LineType::Ridge, {{0.1, 0.2, 0.3}, {1.0 / 3, 2e-300, -7.25}, {1e10, -0.0, 5}}, false, 2.0),
      make_line(LineType::Ridge, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, true, 3.0),
  };
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE("OBJ output follows the contract: v lines, o ridges, o valleys, one l per polyline", "[io][writers]") {
  const std::vector<Polyline> lines = sample_lines();
  const std::string obj = crestline::io::write_lines_obj(lines);

  std::vector<Vec3> vertices;
  std::vector<std::string> objects;
  std::vector<std::pair<std::string, std::vector<size_t>>> polylines;  // object, indices
  bool seen_object = false;
  for (const std::string& row : lines_of(obj)) {
    std::istringstream in(row);
    std::string tag;
    in >> tag;
    if (tag == "v") {
      CHECK_FALSE(seen_object);  // all vertices come first
      Vec3 p;
      in >> p.x() >> p.y() >> p.z();
      vertices.push_back(p);
    } else if (tag == "o") {
      seen_object = true;
      std::string name;
      in >> name;
      objects.push_back(name);
    } else if (tag == "l") {
      REQUIRE_FALSE(objects.empty());
      std::vector<size_t> indices;
      for (size_t i; in >> i;) indices.push_back(i);
      CHECK(indices.size() >= 2);
      polylines.emplace_back(objects.back(), indices);
    }
  }
  REQUIRE(objects == std::vector<std::string>{"ridges", "valleys"});
  REQUIRE(vertices.size() == 9);
  REQUIRE(polylines.size() == 3);

  // Ridges in input order, then the valley.
  CHECK(polylines[0].first == "ridges");
  CHECK(polylines[0].second == std::vector<size_t>{1, 2, 3});
  CHECK(polylines[1].first == "ridges");
  CHECK(polylines[1].second == std::vector<size_t>{4, 5, 6, 7, 4});  // closed: first index repeated
  CHECK(polylines[2].first == "valleys");
  CHECK(polylines[2].second == std::vector<size_t>{8, 9});

  // Coordinates round-trip exactly.
  CHECK(vertices[1] == lines[1].points[1]);
  CHECK(vertices[2] == lines[1].points[2]);
  CHECK(vertices[0] == lines[1].points[0]);
  CHECK(vertices[8] == lines[0].points[1]);
}

TEST_CASE("OBJ output without lines still names both objects", "[io][writers]") {
  const auto rows = lines_of(crestline::io::write_lines_obj({}));
  std::vector<std::string> objects;
  for (const auto& row : rows)
    if (row.rfind("o ", 0) == 0) objects.push_back(row);
  CHECK(objects == std::vector<std::string>{"o ridges", "o valleys"});
}

TEST_CASE("JSON output parses back to the same lines and stats", "[io][writers]") {
  const std::vector<Polyline> lines = sample_lines();
  crestline::PipelineStats stats;
  stats.vertices = 1234;
  stats.triangles = 2460;
  stats.singular_max = 7;
  stats.singular_min = 9;
  stats.ridges = 2;
  stats.valleys = 1;
  stats.ridge_length = 0.1 + 0.2;
  stats.valley_length = 1.0 / 7;
  stats.seconds[static_cast<int>(crestline::Stage::Curvature)] = 0.125;
  stats.read_seconds = 0.5, stats.repair_seconds = 0.25, stats.topology_seconds = 0.0625, stats.write_seconds = 2;

  const auto json = nlohmann::json::parse(crestline::io::write_lines_json(lines, stats));
  REQUIRE(json["ridges"].size() == 2);
  REQUIRE(json["valleys"].size() == 1);

  auto check_line = [](const nlohmann::json& got, const Polyline& want) {
    REQUIRE(got["points"].size() == want.points.size());
    for (size_t k = 0; k < want.points.size(); ++k) {
      INFO("point " << k);
      CHECK(got["points"][k][0].get<double>() == want.points[k].x());
      CHECK(got["points"][k][1].get<double>() == want.points[k].y());
      CHECK(got["points"][k][2].get<double>() == want.points[k].z());
    }
    CHECK(got["strength"].get<double>() == want.strength);
    CHECK(got["closed"].get<bool>() == want.closed);
  };
  check_line(json["ridges"][0], lines[1]);
  check_line(json["ridges"][1], lines[2]);
  check_line(json["valleys"][0], lines[0]);

  const auto& s = json["stats"];
  CHECK(s["vertices"] == 1234);
  CHECK(s["triangles"] == 2460);
  CHECK(s["singular_max"] == 7);
  CHECK(s["singular_min"] == 9);
  CHECK(s["ridges"] == 2);
  CHECK(s["valleys"] == 1);
  CHECK(s["ridge_length"].get<double>() == 0.1 + 0.2);
  CHECK(s["valley_length"].get<double>() == 1.0 / 7);
  REQUIRE(s["seconds"].is_object());
  // Every stage plus read, repair, topology and write.
  CHECK(s["seconds"].size() == static_cast<size_t>(crestline::Stage::Count) + 4);
  CHECK(s["seconds"][crestline::stage_name(crestline::Stage::Curvature)].get<double>() == 0.125);
  CHECK(s["seconds"]["read"].get<double>() == 0.5);
  CHECK(s["seconds"]["repair"].get<double>() == 0.25);
  CHECK(s["seconds"]["topology"].get<double>() == 0.0625);
  CHECK(s["seconds"]["write"].get<double>() == 2);
}

TEST_CASE("stats JSON is one object on one line", "[io][writers]") {
  const std::string text = crestline::io::stats_json(crestline::PipelineStats{});
  CHECK(text.find('\n') == std::string::npos);
  const auto json = nlohmann::json::parse(text);
  for (const char* key : {"vertices", "triangles", "singular_max", "singular_min", "ridges", "valleys", "ridge_length",
                          "valley_length", "smoothing_iterations", "seconds"})
    CHECK(json.contains(key));
}

TEST_CASE("JSON output without lines has empty arrays", "[io][writers]") {
  const auto json = nlohmann::json::parse(crestline::io::write_lines_json({}, {}));
  CHECK(json["ridges"].is_array());
  CHECK(json["ridges"].empty());
  CHECK(json["valleys"].empty());
  CHECK(json["stats"]["ridges"] == 0);
}

TEST_CASE("JSON output writes non-finite numbers as null, never NaN", "[io][writers]") {
  std::vector<Polyline> lines = {make_line(LineType::Ridge, {{0, 0, 0}, {1, 1, 1}}, false, 0)};
  lines[0].strength = std::numeric_limits<double>::quiet_NaN();
  const auto json = nlohmann::json::parse(crestline::io::write_lines_json(lines, {}));
  CHECK(json["ridges"][0]["strength"].is_null());
}

namespace {

// Two triangles sharing an edge: a unit square in z = 0.
crestline::Mesh square_mesh() {
  crestline::Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

}  // namespace

TEST_CASE("OBJ with the mesh: o surface with v/f first, line indices numbered after it", "[io][writers]") {
  const crestline::Mesh mesh = square_mesh();
  const std::vector<Polyline> lines = sample_lines();
  const std::string obj = crestline::io::write_mesh_and_lines_obj(mesh, lines);

  std::vector<std::string> objects;
  size_t vertices = 0;
  std::vector<std::vector<size_t>> faces;
  std::vector<std::vector<size_t>> polylines;
  for (const std::string& row : lines_of(obj)) {
    std::istringstream in(row);
    std::string tag;
    in >> tag;
    std::vector<size_t> indices;
    if (tag == "v") ++vertices;
    if (tag == "o") objects.emplace_back(), in >> objects.back();
    if (tag != "f" && tag != "l") continue;
    for (size_t i; in >> i;) indices.push_back(i);
    (tag == "f" ? faces : polylines).push_back(indices);
  }
  REQUIRE(objects == std::vector<std::string>{"surface", "ridges", "valleys"});
  REQUIRE(vertices == 4 + 9);
  REQUIRE(faces == std::vector<std::vector<size_t>>{{1, 2, 3}, {1, 3, 4}});
  // The same polylines as write_lines_obj, shifted past the 4 surface vertices.
  REQUIRE(polylines == std::vector<std::vector<size_t>>{{5, 6, 7}, {8, 9, 10, 11, 8}, {12, 13}});
  // Everything after the surface's faces is write_lines_obj's output verbatim
  // but for the numbering: the line vertices are the same text.
  const std::string plain = crestline::io::write_lines_obj(lines);
  const size_t first_line_vertex = obj.find("v 0.1 ");
  REQUIRE(first_line_vertex != std::string::npos);
  const size_t plain_first = plain.find("v 0.1 ");
  CHECK(obj.substr(first_line_vertex, obj.find("\no ridges\n") - first_line_vertex) ==
        plain.substr(plain_first, plain.find("\no ridges\n") - plain_first));
}

TEST_CASE("large files are formatted in parts on every thread: the same bytes for any thread count", "[io][writers]") {
  // 3000 lines of every type (some closed, some too short for OBJ) and a
  // 2000-vertex surface: enough items for every writer loop to run in parts.
  std::mt19937 random(5);
  const std::vector<Polyline> lines = random_lines(random, 3000);
  const crestline::Mesh mesh = random_surface(random, 2000);
  const int before = crestline::max_threads();
  std::vector<std::string> json, obj, with_mesh;
  for (int threads : {1, 2, 3}) {
    crestline::set_max_threads(threads);
    json.push_back(crestline::io::write_lines_json(lines, {}));
    obj.push_back(crestline::io::write_lines_obj(lines));
    with_mesh.push_back(crestline::io::write_mesh_and_lines_obj(mesh, lines));
  }
  crestline::set_max_threads(before);
  for (size_t i = 1; i < 3; ++i) {
    CHECK(json[i] == json[0]);
    CHECK(obj[i] == obj[0]);
    CHECK(with_mesh[i] == with_mesh[0]);
  }
  // And in order: every line's points read back in its type's array.
  const auto parsed = nlohmann::json::parse(json[1]);
  size_t seen[3] = {0, 0, 0};
  const char* names[3] = {"ridges", "valleys", "creases"};
  for (const Polyline& line : lines) {
    const int type = static_cast<int>(line.type);
    const auto& got = parsed[names[type]][seen[type]++]["points"];
    REQUIRE(got.size() == line.points.size());
    CHECK(got.back()[2].get<double>() == line.points.back().z());
  }
  CHECK(parsed["creases"].size() == seen[2]);
  // The OBJ's last `l` line is the last crease with two points or more.
  size_t last = lines.size();
  while (lines[--last].type != LineType::Crease || lines[last].points.size() < 2) {
  }
  size_t vertices = 0;
  for (const Polyline& line : lines) vertices += line.points.size() >= 2 ? line.points.size() : 0;
  const std::vector<std::string> rows = lines_of(obj[2]);
  std::string want = "l";
  for (size_t k = 0; k < lines[last].points.size(); ++k)
    want += " " + std::to_string(vertices - lines[last].points.size() + 1 + k);
  if (lines[last].closed) want += " " + std::to_string(vertices - lines[last].points.size() + 1);
  CHECK(rows.back() == want);
}

TEST_CASE("creases: OBJ object o creases after the valleys, JSON with convex per line", "[io][writers][creases]") {
  std::vector<Polyline> lines = sample_lines();
  lines.push_back(make_line(LineType::Crease, {{0, 0, 0}, {0, 0, 1}}, false, 4.0));
  lines.back().convex = true;
  lines.push_back(make_line(LineType::Crease, {{0, 1, 0}, {0, 1, 1}, {0, 2, 1}}, false, 5.0));

  std::vector<std::string> objects;
  for (const std::string& line : lines_of(crestline::io::write_lines_obj(lines)))
    if (line.rfind("o ", 0) == 0) objects.push_back(line);
  CHECK(objects == std::vector<std::string>{"o ridges", "o valleys", "o creases"});
  const std::vector<std::string> obj = lines_of(crestline::io::write_lines_obj(lines));
  CHECK(obj[obj.size() - 2] == "l 10 11");  // 9 ridge/valley vertices before
  CHECK(obj.back() == "l 12 13 14");

  crestline::PipelineStats stats;
  stats.creases = 2;
  stats.crease_length = 2.0;
  stats.crease_angle = 35;
  const auto json = nlohmann::json::parse(crestline::io::write_lines_json(lines, stats));
  REQUIRE(json["creases"].size() == 2);
  CHECK(json["creases"][0]["convex"] == true);
  CHECK(json["creases"][1]["convex"] == false);
  CHECK(json["creases"][1]["points"].size() == 3);
  CHECK(json["creases"][0]["strength"] == 4.0);
  CHECK_FALSE(json["ridges"][0].contains("convex"));
  CHECK(json["stats"]["creases"] == 2);
  CHECK(json["stats"]["crease_length"] == 2.0);
  CHECK(json["stats"]["crease_angle"] == 35);

  // Without creases: no OBJ object, but always the JSON array.
  const auto none = nlohmann::json::parse(crestline::io::write_lines_json(sample_lines(), {}));
  CHECK(none["creases"].is_array());
  CHECK(none["creases"].empty());
  CHECK(crestline::io::write_lines_obj(sample_lines()).find("\no creases") == std::string::npos);
}

TEST_CASE("OBJ numbers are the shortest of %.15g, %.16g, %.17g that reads back, as printf writes them",
          "[io][writers]") {
  // The writer lays out {fmt}'s shortest digits (Dragonbox), natively and in
  // WASM, and formats powers of two, zero and subnormals by precision
  // (std::to_chars natively, snprintf in WASM); all must give printf's
  // bytes. Random doubles over the whole exponent
  // range, short decimals (which round-trip at 15 digits), halves (exact
  // ties at some precisions), subnormals and powers of two.
  std::mt19937_64 random(11);
  std::vector<double> values;
  for (int i = 0; i < 100000; ++i) {
    uint64_t bits = random();
    double d;
    std::memcpy(&d, &bits, sizeof d);
    if (std::isfinite(d)) values.push_back(d);
  }
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int i = 0; i < 20000; ++i) values.push_back(unit(random) * std::pow(10.0, int(random() % 40) - 20));
  for (int i = 0; i < 2000; ++i) values.push_back(std::round(unit(random) * 1e6) / 1000);
  for (int i = 0; i < 200; ++i) values.push_back((int64_t(random() % 2000000) - 1000000) + 0.5);
  for (int e = -1074; e <= 1023; e += 7) values.push_back(std::ldexp(1.0, e));
  // Natively the writer lays the shortest digits out as %g would: around
  // %g's switch between fixed and exponent form (10^-5 and 10^15 to 10^17)
  // with 1 to 17 digits, and odd multiples of powers of two, among them
  // exact ties between two 16-digit decimals (8 + 1/65536 = 8.0000152587890625).
  for (int e = -7; e <= 19; ++e)
    for (int i = 0; i < 100; ++i) {
      values.push_back(unit(random) * std::pow(10.0, e));
      values.push_back(std::round(unit(random) * std::pow(10.0, int(random() % 18))) * std::pow(10.0, e - 17));
    }
  for (int i = 0; i < 2000; ++i)
    values.push_back(std::ldexp(double((random() >> (11 + random() % 48)) | 1), -int(random() % 80)));
  values.push_back(8 + 1.0 / 65536);
  values.push_back(-0.0);
  values.push_back(123456789012345678.0);
  values.push_back(1e15), values.push_back(1e16), values.push_back(1e-5), values.push_back(-1.0000000000000002e-4);
  values.push_back(std::numeric_limits<double>::denorm_min());
  values.push_back(std::numeric_limits<double>::max());
  while (values.size() % 3) values.push_back(0.0);

  std::vector<Vec3> points;
  std::string expected;
  auto printf_number = [](double value) {
    char buffer[32];
    for (int precision = 15; precision <= 17; ++precision) {
      std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
      if (precision == 17 || std::strtod(buffer, nullptr) == value) break;
    }
    return std::string(buffer);
  };
  for (size_t i = 0; i < values.size(); i += 3) {
    points.emplace_back(values[i], values[i + 1], values[i + 2]);
    expected += "v " + printf_number(values[i]) + ' ' + printf_number(values[i + 1]) + ' ' +
                printf_number(values[i + 2]) + '\n';
  }
  const std::string obj = crestline::io::write_lines_obj({make_line(LineType::Ridge, points, false, 1.0)});
  const size_t first_vertex = obj.find("\nv ") + 1;  // after the header comment
  REQUIRE(obj.size() > first_vertex + expected.size());
  const std::string written = obj.substr(first_vertex, expected.size());
  size_t differing = 0;
  std::string first_difference;
  for (size_t i = 0, start = 0; i < expected.size(); ++i)
    if (expected[i] == '\n') {
      if (written.compare(start, i + 1 - start, expected, start, i + 1 - start) != 0 && differing++ == 0)
        first_difference =
            "expected " + expected.substr(start, i - start) + ", wrote " + written.substr(start, i - start);
      start = i + 1;
    }
  INFO(first_difference);
  CHECK(differing == 0);
  CHECK(written == expected);
}

TEST_CASE("streamed text is the same bytes as the writers' strings, in pieces of about a megabyte", "[io][writers]") {
  // 40,000 lines of 1-12 points (≈ 260 k points, ≈ 15 MB of JSON) and a
  // 100,000-vertex surface: several batches and pieces in every writer.
  std::mt19937 random(7);
  const std::vector<Polyline> lines = random_lines(random, 40000);
  const crestline::Mesh mesh = random_surface(random, 100000);
  crestline::PipelineStats stats;
  stats.ridges = 3, stats.threshold = 0.25;
  const int before = crestline::max_threads();
  for (int threads : {1, 2}) {
    crestline::set_max_threads(threads);
    std::string streamed;
    size_t pieces = 0, largest = 0;
    const crestline::io::TextSink sink = [&](std::string_view piece) {
      streamed += piece, ++pieces, largest = std::max(largest, piece.size());
    };
    const auto check = [&](const std::string& whole) {
      INFO(threads << " threads, " << pieces << " pieces");
      CHECK(streamed == whole);
      CHECK(pieces >= whole.size() / (4 << 20));
      CHECK(largest < (4u << 20));
      streamed.clear(), pieces = 0, largest = 0;
    };
    crestline::io::write_lines_json(lines, stats, sink);
    check(crestline::io::write_lines_json(lines, stats));
    crestline::io::write_lines_obj(lines, sink);
    check(crestline::io::write_lines_obj(lines));
    crestline::io::write_mesh_and_lines_obj(mesh, lines, sink);
    check(crestline::io::write_mesh_and_lines_obj(mesh, lines));
    crestline::io::write_lines_json({}, stats, sink);
    check(crestline::io::write_lines_json({}, stats));
  }
  crestline::set_max_threads(before);
}
