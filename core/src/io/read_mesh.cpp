// io::read_mesh: format detection, dispatch to one reader per format, and
// the helpers every reader shares (messages, header-claim checks, polygon
// triangulation, the final soup checks).
#include "crestline/io/read_mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>

#include "readers.h"

namespace crestline::io {
namespace detail {

void fail(ErrorKind kind, const Input& in, const std::string& problem) { throw Error(kind, in.name + ": " + problem); }

void check_claim(const Input& in, const ReadOptions& options, uint64_t count, uint64_t min_bytes_each,
                 size_t bytes_left, const char* what) {
  if (count > options.max_triangles) {
    fail(ErrorKind::TooLarge, in,
         "the header claims " + std::to_string(count) + " " + what + ", more than the limit of " +
             std::to_string(options.max_triangles) + ".");
  }
  if (min_bytes_each > 0 && count > bytes_left / min_bytes_each) {
    fail(ErrorKind::InvalidInput, in,
         "the header claims " + std::to_string(count) + " " + what + " but only " + std::to_string(bytes_left) +
             " bytes follow it.");
  }
}

std::string basename_of(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

static std::string directory_of(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::vector<uint8_t> read_file(const std::string& path, const std::string& display_name) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw Error(ErrorKind::Io, display_name + ": the file cannot be opened.");
  const std::streamoff size = file.tellg();
  if (size < 0) throw Error(ErrorKind::Io, display_name + ": the file cannot be read.");
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  file.seekg(0);
  if (size > 0 && !file.read(reinterpret_cast<char*>(bytes.data()), size)) {
    throw Error(ErrorKind::Io, display_name + ": the file cannot be read.");
  }
  return bytes;
}

bool find_companion(const Input& in, const std::string& uri, std::vector<uint8_t>& out) {
  if (in.companions) {
    for (const auto& pass : {uri, basename_of(uri)}) {
      for (const NamedBuffer& buffer : *in.companions) {
        if (buffer.name == pass || basename_of(buffer.name) == pass) {
          out = buffer.bytes;
          return true;
        }
      }
    }
  }
  if (in.directory.empty() || uri.empty()) return false;
  std::ifstream file(in.directory + "/" + uri, std::ios::binary);
  if (!file) return false;
  out.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  return true;
}

// --- polygon triangulation -------------------------------------------------

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
  for (size_t i = 1; i + 1 < n; ++i) {
    soup.indices.insert(soup.indices.end(), {poly[0], poly[i], poly[i + 1]});
  }
}

}  // namespace

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
  if (!(length > 0) || !std::isfinite(length)) {
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
  // Ear clipping on a circular doubly linked list. When no ear exists (a
  // self-intersecting or degenerate outline) the rest is fanned, so the
  // result always has n - 2 triangles.
  std::vector<size_t> prev(n), next(n);
  for (size_t i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto is_ear = [&](size_t i) {
    const double* a = &xy[2 * prev[i]];
    const double* b = &xy[2 * i];
    const double* c = &xy[2 * next[i]];
    if (!(cross2(a, b, c) > 0)) return false;
    for (size_t j = next[next[i]]; j != prev[i]; j = next[j]) {
      const double* p = &xy[2 * j];
      if (same_point(p, a) || same_point(p, b) || same_point(p, c)) continue;
      if (inside(p, a, b, c)) return false;
    }
    return true;
  };
  size_t remaining = n;
  size_t i = 0;
  size_t misses = 0;
  while (remaining > 3) {
    if (misses > remaining) {
      // A whole turn without an ear: the rest is self-intersecting or
      // degenerate (repeated corners). Fan it, in linear time; clipping one
      // forced corner per turn costs a whole turn of ear tests per corner
      // (a 2,000-corner face found by the fuzzer took 1.6 s, not 3 ms).
      for (size_t j = next[i]; next[j] != i; j = next[j]) {
        soup.indices.insert(soup.indices.end(), {poly[i], poly[j], poly[next[j]]});
      }
      return;
    }
    if (is_ear(i)) {
      soup.indices.insert(soup.indices.end(), {poly[prev[i]], poly[i], poly[next[i]]});
      next[prev[i]] = next[i];
      prev[next[i]] = prev[i];
      i = prev[i];
      --remaining;
      misses = 0;
    } else {
      i = next[i];
      ++misses;
    }
  }
  soup.indices.insert(soup.indices.end(), {poly[prev[i]], poly[i], poly[next[i]]});
}

void finish_soup(TriangleSoup& soup, const Input& in) {
  if (soup.indices.empty()) fail(ErrorKind::InvalidInput, in, "the file contains no triangles.");
  const size_t vertices = soup.vertex_count();
  std::vector<char> non_finite(vertices, 0);
  size_t non_finite_count = 0;
  for (size_t v = 0; v < vertices; ++v) {
    const double* p = &soup.positions[3 * v];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      non_finite[v] = 1;
      ++non_finite_count;
    }
  }
  bool any_finite_referenced = false;
  for (size_t k = 0; k < soup.indices.size(); ++k) {
    const uint32_t index = soup.indices[k];
    if (index >= vertices) {
      fail(ErrorKind::InvalidInput, in,
           "triangle " + std::to_string(k / 3) + " refers to vertex " + std::to_string(index) + " but the file has " +
               std::to_string(vertices) + " vertices.");
    }
    any_finite_referenced = any_finite_referenced || !non_finite[index];
  }
  if (!any_finite_referenced) {
    fail(ErrorKind::InvalidInput, in, "every vertex of every triangle has a NaN or infinite coordinate.");
  }
  if (non_finite_count > 0) {
    soup.notes.push_back(std::to_string(non_finite_count) +
                         " vertices have NaN or infinite coordinates; their triangles are dropped.");
  }
}

// --- format detection -------------------------------------------------------

bool looks_like_text(const uint8_t* data, size_t size) {
  const size_t n = std::min<size_t>(size, 4096);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t c = data[i];
    if (c < 9 || (c > 13 && c < 32) || c == 127) return false;
  }
  return true;
}

namespace {

bool starts_with(const uint8_t* data, size_t size, const char* prefix) {
  const size_t n = std::strlen(prefix);
  return size >= n && std::memcmp(data, prefix, n) == 0;
}

std::string lower_extension(const std::string& name) {
  const std::string base = basename_of(name);
  const size_t dot = base.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = base.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The first whitespace-delimited word, after an optional UTF-8 byte-order mark.
std::string first_word(const uint8_t* data, size_t size) {
  size_t i = starts_with(data, size, "\xEF\xBB\xBF") ? 3 : 0;
  while (i < size && std::isspace(data[i])) ++i;
  std::string word;
  while (i < size && word.size() < 16 && !std::isspace(data[i])) word += char(data[i++]);
  return word;
}

bool looks_like_obj(const uint8_t* data, size_t size) {
  if (!looks_like_text(data, size)) return false;
  const std::string word = first_word(data, size);
  static const char* const keywords[] = {"#", "v", "vn", "vt", "f", "o", "g", "mtllib", "usemtl", "s"};
  return std::any_of(std::begin(keywords), std::end(keywords),
                     [&](const char* k) { return word == k || (word[0] == '#' && k[0] == '#'); });
}

}  // namespace

bool is_binary_stl_size(size_t size, const uint8_t* data) {
  if (size < 84) return false;
  uint32_t count = 0;
  std::memcpy(&count, data + 80, 4);  // little-endian on every target we build for
  return uint64_t(size) == 84 + 50 * uint64_t(count) && !looks_like_text(data, size);
}

}  // namespace detail

MeshFormat detect_format(const std::string& name, const uint8_t* bytes, size_t size) {
  using namespace detail;
  if (starts_with(bytes, size, "glTF")) return MeshFormat::Glb;
  const std::string word = first_word(bytes, size);
  if (word == "ply") return MeshFormat::Ply;
  if (word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0 &&
      std::all_of(word.begin(), word.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)); })) {
    return MeshFormat::Off;
  }
  if (is_binary_stl_size(size, bytes)) return MeshFormat::Stl;
  if (word == "solid" && looks_like_text(bytes, size)) return MeshFormat::Stl;
  if (!word.empty() && word[0] == '{') return MeshFormat::Gltf;
  const std::string ext = lower_extension(name);
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "gltf") return MeshFormat::Gltf;
  if (ext == "glb") return MeshFormat::Glb;
  if (ext == "ply") return MeshFormat::Ply;
  if (ext == "stl") return MeshFormat::Stl;
  if (ext == "off") return MeshFormat::Off;
  if (looks_like_obj(bytes, size)) return MeshFormat::Obj;
  return MeshFormat::Auto;  // not recognised
}

namespace {

TriangleSoup dispatch_format(const detail::Input& in, const ReadOptions& options) {
  using namespace detail;
  const MeshFormat format =
      options.format == MeshFormat::Auto ? detect_format(in.name, in.data, in.size) : options.format;
  switch (format) {
    case MeshFormat::Obj:
      return read_obj(in, options);
    case MeshFormat::Gltf:
    case MeshFormat::Glb:
      return read_gltf(in, options);
    case MeshFormat::Ply:
      return read_ply(in, options);
    case MeshFormat::Stl:
      return read_stl(in, options);
    case MeshFormat::Off:
      return read_off(in, options);
    case MeshFormat::Auto:
      break;
  }
  if (in.size == 0) fail(ErrorKind::InvalidInput, in, "the file is empty.");
  fail(ErrorKind::Unsupported, in, "the format is not recognised (Crestline reads OBJ, glTF/GLB, PLY, STL and OFF).");
}

// Whatever a library throws becomes one sentence about the file too.
TriangleSoup dispatch(const detail::Input& in, const ReadOptions& options) {
  try {
    return dispatch_format(in, options);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    detail::fail(ErrorKind::TooLarge, in, "there is not enough memory to read the file.");
  } catch (const std::exception& e) {
    detail::fail(ErrorKind::InvalidInput, in, std::string("the file cannot be read (") + e.what() + ").");
  }
}

}  // namespace

TriangleSoup read_mesh(const std::string& path, const ReadOptions& options) {
  detail::Input in;
  in.name = detail::basename_of(path);
  const std::vector<uint8_t> bytes = detail::read_file(path, in.name);
  in.data = bytes.data();
  in.size = bytes.size();
  in.directory = detail::directory_of(path);
  return dispatch(in, options);
}

TriangleSoup read_mesh_bytes(const std::string& name, const std::vector<uint8_t>& bytes,
                             const std::vector<NamedBuffer>& companions, const ReadOptions& options) {
  detail::Input in;
  in.name = detail::basename_of(name);
  in.data = bytes.data();
  in.size = bytes.size();
  in.companions = &companions;
  return dispatch(in, options);
}

}  // namespace crestline::io
