// Small in-memory files, one concern each: binary PLY of both byte orders,
// binary STL whose header starts with "solid", concave polygons, OFF
// comments, content detection, header claims refused before allocating,
// glTF companions, data URIs, strips and instancing.
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "read_test_bytes.h"
#include "test_meshes.h"

using crestline::Error;
using crestline::ErrorKind;
using crestline::TriangleSoup;
using crestline::io::MeshFormat;
using crestline::io::NamedBuffer;
using crestline::io::read_mesh_bytes;
using crestline::testing::bytes_of;
using crestline::testing::put;

namespace {

TriangleSoup read_text(const std::string& name, const std::string& text) {
  return read_mesh_bytes(name, bytes_of(text));
}

ErrorKind error_kind(const std::string& name, const std::vector<uint8_t>& bytes,
                     const crestline::io::ReadOptions& options = {}) {
  try {
    read_mesh_bytes(name, bytes, {}, options);
  } catch (const Error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).rfind(name + ": ", 0) == 0);
    return e.kind();
  }
  FAIL("no error for " << name);
  return ErrorKind::Numerical;
}

// A unit square as one quad plus a triangle, with an extra uchar property per
// vertex and ushort/int lists, in the given PLY encoding.
std::vector<uint8_t> square_ply(const std::string& format) {
  std::string header = "ply\nformat " + format +
                       " 1.0\ncomment made by a test\nelement vertex 5\nproperty float x\nproperty uchar red\n"
                       "property double y\nproperty float z\nelement face 2\n"
                       "property list ushort int vertex_indices\nend_header\n";
  const double xy[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 2}};
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {3, 2, 4}};
  if (format == "ascii") {
    for (auto& p : xy) header += std::to_string(p[0]) + " 7 " + std::to_string(p[1]) + " 0\n";
    for (auto& f : faces) {
      header += std::to_string(f.size());
      for (int i : f) header += " " + std::to_string(i);
      header += "\n";
    }
    return bytes_of(header);
  }
  const bool big = format == "binary_big_endian";
  std::vector<uint8_t> out = bytes_of(header);
  for (auto& p : xy) {
    put(out, float(p[0]), big);
    put(out, uint8_t(7), big);
    put(out, p[1], big);
    put(out, 0.0f, big);
  }
  for (auto& f : faces) {
    put(out, uint16_t(f.size()), big);
    for (int i : f) put(out, int32_t(i), big);
  }
  return out;
}

double area(const TriangleSoup& soup) {
  double total = 0;
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    const Eigen::Vector3d a(&soup.positions[3 * soup.indices[3 * t]]);
    const Eigen::Vector3d b(&soup.positions[3 * soup.indices[3 * t + 1]]);
    const Eigen::Vector3d c(&soup.positions[3 * soup.indices[3 * t + 2]]);
    total += 0.5 * (b - a).cross(c - a).norm();
  }
  return total;
}

}  // namespace

TEST_CASE("PLY: ascii, little- and big-endian binary give the same soup", "[io][ply]") {
  const TriangleSoup ascii = read_mesh_bytes("square.ply", square_ply("ascii"));
  const TriangleSoup little = read_mesh_bytes("square.ply", square_ply("binary_little_endian"));
  const TriangleSoup big = read_mesh_bytes("square.ply", square_ply("binary_big_endian"));
  CHECK(ascii.vertex_count() == 5);
  CHECK(ascii.triangle_count() == 3);
  CHECK(area(ascii) == Approx(1.5));
  CHECK(little.positions == ascii.positions);
  CHECK(big.positions == ascii.positions);
  CHECK(little.indices == ascii.indices);
  CHECK(big.indices == ascii.indices);
}

TEST_CASE("PLY: claims the file cannot hold are refused before allocating", "[io][ply]") {
  std::string huge =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  CHECK(error_kind("huge.ply", bytes_of(huge)) == ErrorKind::TooLarge);
  std::string lying =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n0000";
  CHECK(error_kind("lying.ply", bytes_of(lying)) == ErrorKind::InvalidInput);
  std::vector<uint8_t> truncated = square_ply("binary_big_endian");
  truncated.resize(truncated.size() - 3);
  CHECK(error_kind("truncated.ply", truncated) == ErrorKind::InvalidInput);
  std::string out_of_range =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_index\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n";
  CHECK(error_kind("range.ply", bytes_of(out_of_range)) == ErrorKind::InvalidInput);
}

TEST_CASE("STL: binary with a 'solid' header is detected by its size", "[io][stl]") {
  std::vector<uint8_t> stl = bytes_of("solid exported by a CAD tool that writes binary anyway");
  stl.resize(80, ' ');
  put(stl, uint32_t(2), false);
  const float tris[2][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (auto& t : tris) {
    for (int k = 0; k < 3; ++k) put(stl, 0.0f, false);  // normal
    for (float c : t) put(stl, c, false);
    put(stl, uint16_t(0), false);
  }
  CHECK(crestline::io::detect_format("part.dat", stl.data(), stl.size()) == MeshFormat::Stl);
  const TriangleSoup soup = read_mesh_bytes("part.stl", stl);
  CHECK(soup.vertex_count() == 6);
  CHECK(soup.triangle_count() == 2);
  CHECK(area(soup) == Approx(1.0));

  stl.resize(stl.size() - 10);  // size no longer 84 + 50 n
  CHECK(error_kind("cut.stl", stl) == ErrorKind::InvalidInput);

  const TriangleSoup ascii = read_text("a.stl",
                                       "solid a\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                                       "   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid a\n");
  CHECK(ascii.triangle_count() == 1);
  CHECK(read_text("indented.stl", "\n  solid x\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n")
            .triangle_count() == 1);
  CHECK(ascii.positions[3] == 1.0);
}

TEST_CASE("OBJ: concave polygons are ear-clipped inside their outline", "[io][obj]") {
  // A comb-shaped 12-gon in a tilted plane: a fan from vertex 1 would leave
  // the polygon.
  const std::vector<std::array<double, 2>> outline = {{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                                      {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  std::string obj = "# comb\n";
  for (auto& p : outline) {
    const Eigen::Vector3d q = tilt * Eigen::Vector3d(p[0], p[1], 0) + Eigen::Vector3d(10, -4, 2);
    obj += "v " + std::to_string(q.x()) + " " + std::to_string(q.y()) + " " + std::to_string(q.z()) + "\n";
  }
  obj += "f";
  for (size_t i = 1; i <= outline.size(); ++i) obj += " " + std::to_string(i);
  obj += "\n";
  const TriangleSoup soup = read_text("comb.obj", obj);
  REQUIRE(soup.triangle_count() == outline.size() - 2);
  CHECK(area(soup) == Approx(5 * 3 - 2 * 2).epsilon(1e-5));  // area preserved: 5x3 minus two 1x2 slots
  // No triangle outside: every centroid lies inside the outline, and every
  // triangle keeps the polygon's orientation.
  const Eigen::Vector3d normal = tilt * Eigen::Vector3d::UnitZ();
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    Eigen::Vector3d corner[3];
    for (int k = 0; k < 3; ++k) corner[k] = Eigen::Vector3d(&soup.positions[3 * soup.indices[3 * t + size_t(k)]]);
    CHECK((corner[1] - corner[0]).cross(corner[2] - corner[0]).dot(normal) > 0);
    const Eigen::Vector3d local =
        tilt.transpose() * ((corner[0] + corner[1] + corner[2]) / 3 - Eigen::Vector3d(10, -4, 2));
    bool inside = false;
    for (size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
      const auto& a = outline[i];
      const auto& b = outline[j];
      if ((a[1] > local.y()) != (b[1] > local.y()) &&
          local.x() < (b[0] - a[0]) * (local.y() - a[1]) / (b[1] - a[1]) + a[0]) {
        inside = !inside;
      }
    }
    CHECK(inside);
  }
}

TEST_CASE("OBJ: the 66-gon of polygon-concave.obj keeps its area", "[io][obj][meshes]") {
  SKIP_WITHOUT_MESHES();
  const TriangleSoup soup = crestline::io::read_mesh(crestline::testing::mesh_path("robust/obj/polygon-concave.obj"));
  // All its vertices lie in the plane x = -1.146, so each triangle has a
  // signed area in (y, z).
  const std::vector<double>& p = soup.positions;
  double signed_sum = 0;
  double total = 0;
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    const uint32_t* i = &soup.indices[3 * t];
    const double y0 = p[3 * i[0] + 1], z0 = p[3 * i[0] + 2];
    const double cross =
        (p[3 * i[1] + 1] - y0) * (p[3 * i[2] + 2] - z0) - (p[3 * i[1] + 2] - z0) * (p[3 * i[2] + 1] - y0);
    total += std::abs(cross) / 2;
    signed_sum += cross / 2;
  }
  // Consistently oriented triangles: the signed sum equals the unsigned one,
  // so no triangle folds back outside the outline.
  CHECK(std::abs(signed_sum) == Approx(total).epsilon(1e-9));
}

TEST_CASE("OFF: comments, counts on the keyword line, polygons", "[io][off]") {
  const TriangleSoup soup = read_text("p.off",
                                      "OFF 5 1 0 # a pentagon\n# comment line\n0 0 0\n1 0 0 255 0 0\n1.5 1 0\n"
                                      "0.5 1.5 0\n-0.5 1 0\n5 0 1 2 3 4 # face\n");
  CHECK(soup.vertex_count() == 5);
  CHECK(soup.triangle_count() == 3);
  const TriangleSoup cube_header = read_text("q.off", "COFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  CHECK(area(cube_header) == Approx(1.0));
  CHECK(error_kind("big.off", bytes_of("OFF\n900000000 1 0\n0 0 0\n")) == ErrorKind::TooLarge);
  CHECK(error_kind("short.off", bytes_of("OFF\n1000 1 0\n0 0 0\n")) == ErrorKind::InvalidInput);
  CHECK(error_kind("range.off", bytes_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")) == ErrorKind::InvalidInput);
}

TEST_CASE("OFF text numbers read as strtod reads them, bit for bit (PLY and STL text share the parse)",
          "[io][off][numbers]") {
  // The readers take plain decimals by fast_float and the rest by strtod:
  // every word must give strtod's double (sign of zero, subnormals, the
  // largest finite, hexadecimal, '+', long mantissas), and 3,000 random
  // decimals of 1 to 17 digits and exponents over the whole range.
  std::vector<std::string> words = {"0",
                                    "-0",
                                    "0.0",
                                    "+1.5",
                                    "1e-320",
                                    "4.9406564584124654e-324",
                                    "2.2250738585072011e-308",
                                    "1.7976931348623157e308",
                                    "0x1p3",
                                    "-0x1.8p-2",
                                    "0.1",
                                    "123456789012345678901234567890",
                                    "1e22",
                                    "1e23",
                                    "9007199254740993",
                                    "-2.5e-7",
                                    ".5",
                                    "5.",
                                    "1E5",
                                    "1e+05"};
  std::mt19937_64 random(7);
  for (int i = 0; i < 3000; ++i) {
    const int digits = 1 + int(random() % 17), exponent = int(random() % 640) - 330;
    std::string word = random() % 2 ? "-" : "";
    for (int d = 0; d < digits; ++d) word += char('0' + random() % 10);
    word += "e" + std::to_string(exponent);
    words.push_back(word);
  }
  while (words.size() % 3) words.push_back("1");
  std::string text = "OFF\n" + std::to_string(words.size() / 3) + " 1 0\n";
  for (size_t i = 0; i < words.size(); i += 3) text += words[i] + " " + words[i + 1] + " " + words[i + 2] + "\n";
  text += "3 0 1 2\n";
  const TriangleSoup soup = read_text("n.off", text);
  REQUIRE(soup.positions.size() == words.size());
  for (size_t i = 0; i < words.size(); ++i) {
    const double expected = std::strtod(words[i].c_str(), nullptr);
    INFO(words[i]);
    CHECK(std::memcmp(&soup.positions[i], &expected, sizeof expected) == 0);
  }
}

TEST_CASE("format detection reads the content before the extension", "[io][detect]") {
  using crestline::io::detect_format;
  auto detect = [](const std::string& name, const std::string& text) {
    return detect_format(name, reinterpret_cast<const uint8_t*>(text.data()), text.size());
  };
  CHECK(detect("mesh.obj", "ply\nformat ascii 1.0\n") == MeshFormat::Ply);
  CHECK(detect("mesh.bin", "glTF\x02\0\0\0") == MeshFormat::Glb);
  CHECK(detect("mesh", "  {\"asset\":{\"version\":\"2.0\"}}") == MeshFormat::Gltf);
  CHECK(detect("mesh.stl", "OFF\n3 1 0\n") == MeshFormat::Off);
  CHECK(detect("mesh.txt", "solid x\nfacet normal 0 0 1\n") == MeshFormat::Stl);
  CHECK(detect("mesh.txt", "# exported\nv 0 0 0\nf 1 2 3\n") == MeshFormat::Obj);
  CHECK(detect("mesh.OBJ", "") == MeshFormat::Obj);
  CHECK(detect("mesh.xyz", "\x01\x02\x03 random bytes") == MeshFormat::Auto);
  // A PLY stored under a wrong name still reads.
  CHECK(read_mesh_bytes("wrong.obj", square_ply("binary_big_endian")).triangle_count() == 3);
  CHECK(error_kind("mesh.xyz", bytes_of("\x01\x02\x03 random bytes")) == ErrorKind::Unsupported);
  CHECK(error_kind("empty.xyz", {}) == ErrorKind::InvalidInput);
  CHECK(error_kind("empty.stl", {}) == ErrorKind::InvalidInput);
}

TEST_CASE("options.max_triangles refuses large meshes", "[io][limits]") {
  crestline::io::ReadOptions options;
  options.max_triangles = 2;
  CHECK(error_kind("square.ply", square_ply("ascii"), options) == ErrorKind::TooLarge);
  CHECK(error_kind("fan.obj", bytes_of("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 1 0\nf 1 2 3 4 5\n"), options) ==
        ErrorKind::TooLarge);
}

namespace {

std::string base64(const std::vector<uint8_t>& data) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < data.size(); i += 3) {
    uint32_t v = uint32_t(data[i]) << 16;
    if (i + 1 < data.size()) v |= uint32_t(data[i + 1]) << 8;
    if (i + 2 < data.size()) v |= data[i + 2];
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < data.size() ? table[(v >> 6) & 63] : '=';
    out += i + 2 < data.size() ? table[v & 63] : '=';
  }
  return out;
}

// Four vertices of a unit square (float xyz) as a buffer.
std::vector<uint8_t> square_buffer() {
  std::vector<uint8_t> out;
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f}) put(out, c, false);
  return out;
}

std::string square_gltf(const std::string& uri, int mode, const std::string& nodes) {
  return R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":48,"uri":")" + uri +
         R"("}],"bufferViews":[{"buffer":0,"byteLength":48}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":)" +
         std::to_string(mode) + R"(}]}],"nodes":)" + nodes + "}";
}

}  // namespace

TEST_CASE("glTF: data URIs, strips, instancing with transforms, companions", "[io][gltf]") {
  const std::string uri = "data:application/octet-stream;base64," + base64(square_buffer());
  // No scene: every root node. Two instances, the second moved by 10 in x.
  const TriangleSoup strip =
      read_text("s.gltf", square_gltf(uri, 5, R"([{"mesh":0},{"mesh":0,"translation":[10,0,0]}])"));
  CHECK(strip.vertex_count() == 8);
  CHECK(strip.triangle_count() == 4);
  CHECK(area(strip) == Approx(2.0));
  CHECK(strip.positions[3 * 7] == Approx(11.0));
  // Strip winding alternates so both triangles face +z.
  for (size_t t = 0; t < 2; ++t) {
    const Eigen::Vector3d a(&strip.positions[3 * strip.indices[3 * t]]);
    const Eigen::Vector3d b(&strip.positions[3 * strip.indices[3 * t + 1]]);
    const Eigen::Vector3d c(&strip.positions[3 * strip.indices[3 * t + 2]]);
    CHECK((b - a).cross(c - a).z() > 0);
  }
  // Scaled child of a rotated parent.
  const TriangleSoup nested = read_text(
      "n.gltf",
      square_gltf(uri, 4, R"([{"children":[1],"rotation":[0,0,0.7071068,0.7071068]},{"mesh":0,"scale":[2,2,2]}])"));
  CHECK(nested.positions[3 * 1 + 1] == Approx(2.0));  // (1,0,0) scaled to (2,0,0), turned to (0,2,0)
  // An external buffer comes from the companions, by URI.
  const std::string external = square_gltf("sub/square.bin", 4, R"([{"mesh":0}])");
  const TriangleSoup companion =
      read_mesh_bytes("c.gltf", bytes_of(external), {NamedBuffer{"square.bin", square_buffer()}});
  CHECK(companion.triangle_count() == 1);
  try {
    read_mesh_bytes("c.gltf", bytes_of(external));
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Io);
    CHECK(std::string(e.what()) == "c.gltf: the buffer file 'sub/square.bin' it refers to was not found.");
  }
  // A node that is its own child.
  CHECK(error_kind("cycle.gltf", bytes_of(square_gltf(uri, 4, R"([{"mesh":0,"children":[0]}])"))) ==
        ErrorKind::InvalidInput);
  // An accessor claiming more than its bufferView holds.
  std::string overlong = square_gltf(uri, 4, R"([{"mesh":0}])");
  overlong.replace(overlong.find("\"count\":4"), 9, "\"count\":400000");
  CHECK(error_kind("long.gltf", bytes_of(overlong)) == ErrorKind::InvalidInput);
  CHECK(error_kind("broken.gltf", bytes_of("{\"asset\":")) == ErrorKind::InvalidInput);
  // JSON of the wrong type where the reader looks itself (not through tinygltf).
  CHECK(error_kind("typed.gltf", bytes_of(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":1,
      "extensions":{"EXT_meshopt_compression":{"fallback":"yes"}}}]})")) == ErrorKind::InvalidInput);
  // An accessor without a bufferView (zeros) claiming 10^8 vertices is
  // refused before allocating them.
  std::string phantom = square_gltf(uri, 4, R"([{"mesh":0}])");
  phantom.replace(phantom.find("\"bufferView\":0,\"componentType\""), 15, "");
  phantom.replace(phantom.find("\"count\":4"), 9, "\"count\":100000000");
  CHECK(error_kind("phantom.gltf", bytes_of(phantom)) == ErrorKind::InvalidInput);
  // A buffer shorter than its declared byteLength.
  std::string short_buffer = square_gltf("square.bin", 4, R"([{"mesh":0}])");
  short_buffer.replace(short_buffer.find("\"byteLength\":48"), 15, "\"byteLength\":64");
  try {
    read_mesh_bytes("short.gltf", bytes_of(short_buffer), {NamedBuffer{"square.bin", square_buffer()}});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == "short.gltf: the buffer 'square.bin' has 48 bytes but the glTF declares 64.");
  }
}

TEST_CASE("glTF: interleaved positions, byte indices, unused trailing corners; -0 reads as +0", "[io][gltf]") {
  // Four float vertices 16 bytes apart (the first at x = -0), then seven
  // byte indices: two triangles and one corner no triangle uses.
  std::vector<uint8_t> buffer;
  for (float c : {-0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f}) {
    put(buffer, c, false);
    if (buffer.size() % 16 == 12) put(buffer, 0.f, false);
  }
  for (uint8_t index : {0, 1, 2, 2, 1, 3, 200}) buffer.push_back(index);
  const std::string gltf = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":71,"uri":"b.bin"}],
    "bufferViews":[{"buffer":0,"byteLength":64,"byteStride":16},{"buffer":0,"byteOffset":64,"byteLength":7}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5121,"count":7,"type":"SCALAR"}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"nodes":[{"mesh":0}]})";
  const TriangleSoup soup = read_mesh_bytes("i.gltf", bytes_of(gltf), {NamedBuffer{"b.bin", buffer}});
  CHECK(soup.indices == std::vector<uint32_t>{0, 1, 2, 2, 1, 3});
  CHECK(soup.positions == std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  CHECK(!std::signbit(soup.positions[0]));  // as the node transform's product gives it
  // A used corner out of range is named by its value.
  buffer[64 + 5] = 9;
  try {
    read_mesh_bytes("i.gltf", bytes_of(gltf), {NamedBuffer{"b.bin", buffer}});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == "i.gltf: mesh 0 primitive 0 refers to vertex 9 but has only 4 vertices.");
  }
}

TEST_CASE("glTF: EXT_mesh_gpu_instancing is expanded", "[io][gltf]") {
  std::vector<uint8_t> buffer = square_buffer();
  for (float c : {0.f, 0.f, 0.f, 10.f, 0.f, 0.f, 0.f, 10.f, 0.f}) put(buffer, c);  // 3 translations
  const std::string json = R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_mesh_gpu_instancing"],
  "buffers":[{"byteLength":84,"uri":"data:application/octet-stream;base64,)" +
                           base64(buffer) + R"("}],
  "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":36}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
               {"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":5}]}],
  "nodes":[{"mesh":0,"scale":[2,2,2],"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1}}}}]})";
  const TriangleSoup soup = read_text("instances.gltf", json);
  CHECK(soup.vertex_count() == 12);
  CHECK(soup.triangle_count() == 6);
  CHECK(area(soup) == Approx(3 * 4.0));          // node scale 2 applies after the instance offsets
  CHECK(soup.positions[3 * 4] == Approx(20.0));  // instance 1, vertex 0: (10,0,0) scaled by 2
}

TEST_CASE("glTF read from memory with its .bin companion", "[io][gltf][meshes]") {
  SKIP_WITHOUT_MESHES();
  auto load = [](const std::string& relative) {
    std::ifstream file(crestline::testing::mesh_path(relative), std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  };
  const TriangleSoup duck = read_mesh_bytes("Duck.gltf", load("gltf/Duck/Duck.gltf"),
                                            {NamedBuffer{"Duck0.bin", load("gltf/Duck/Duck0.bin")}});
  CHECK(duck.vertex_count() == 2399);
  CHECK(duck.triangle_count() == 4212);
  const TriangleSoup glb = read_mesh_bytes("whatever.bin", load("glb/Box-draco.glb"));
  CHECK(glb.triangle_count() == 12);
  // A meshopt byteStride the codec would assert on (6 is not a multiple of 4)
  // is refused first; same length, so the GLB container stays valid.
  std::vector<uint8_t> meshopt = load("glb/BoxMeshopt.glb");
  const std::string needle = R"("byteLength":71,"byteStride":4)";
  auto at = std::search(meshopt.begin(), meshopt.end(), needle.begin(), needle.end());
  REQUIRE(at != meshopt.end());
  *(at + long(needle.size()) - 1) = '6';
  CHECK(error_kind("BoxMeshopt.glb", meshopt) == ErrorKind::InvalidInput);
}

TEST_CASE("OBJ: nan and inf stay non-finite in any case and place; other words with a or i change nothing",
          "[io][obj]") {
  // nan and inf (any case) stay non-finite so that repair drops their
  // triangles (tinyobjloader read them as 0); other words are no number.
  const std::string faces = "f 1 2 3\n";
  struct Case {
    const char* vertices;
    std::array<bool, 9> finite;  // x y z of the three vertices
  };
  const Case cases[] = {
      {"v 1 2 3\nv 4 5 6\nv 7 8 INF", {true, true, true, true, true, true, true, true, false}},
      {"v NaN 2 3\nv 4 5 6\nv 7 8 9\n", {false, true, true, true, true, true, true, true, true}},
      {"v 1 2 3\nv 4 -iNf 6\nv 7 8 9\n", {true, true, true, true, false, true, true, true, true}},
      {"# main info, a Nan-free file: a i A I\nv 1 2 3\nv 4 5 6\nv 7 8 9\n",
       {true, true, true, true, true, true, true, true, true}},
  };
  // Texts too short to hold a triangle (the fuzzer's sanitizers once found
  // memchr called on an empty view, which may hold no pointer).
  for (const std::string text : {"", "v", "f 1"}) CHECK_THROWS_AS(read_text("t.obj", text), Error);
  for (const Case& c : cases) {
    INFO(c.vertices);
    // The vertex lines last, so that "INF" can end the text.
    const std::string text = faces + c.vertices;
    const TriangleSoup soup = read_text("t.obj", text);
    REQUIRE(soup.positions.size() == 9);
    for (size_t i = 0; i < 9; ++i) CHECK(std::isfinite(soup.positions[i]) == c.finite[i]);
  }
}
