// glTF 2.0 (.gltf and .glb) through tinygltf, which parses the JSON and
// loads buffers (external .bin, data URIs, the GLB BIN chunk) through our
// file-system callbacks. Accessors are read here with every range checked,
// because tinygltf does not check them: byte strides, normalized integers
// (KHR_mesh_quantization) and sparse accessors.
//
// Compressed data (native build only; the browser decodes it with three.js):
// - KHR_draco_mesh_compression is decoded with the draco library directly
//   rather than through TINYGLTF_ENABLE_DRACO, whose decoder in tinygltf 2.7
//   dereferences accessor and attribute ids from the file unchecked;
// - EXT_meshopt_compression bufferViews are decoded with meshoptimizer.
//
// What is read: every mesh of the default scene (else scene 0, else every
// root node) with node transforms applied, instances expanded (nodes
// sharing a mesh, and EXT_mesh_gpu_instancing).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cctype>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <type_traits>

#include "crestline/numerics/serial_blocks.h"
#include "crestline/numerics/uninitialised.h"
#include "readers.h"

#ifndef __EMSCRIPTEN__
#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#endif

namespace crestline::io::detail {
namespace {

using Json = nlohmann::json;

constexpr const char* kGlbBin = "crestline-glb-bin-chunk";
constexpr const char* kFallback = "crestline-meshopt-fallback";

struct Files {
  const Input* in = nullptr;
  const uint8_t* glb_bin = nullptr;
  size_t glb_bin_size = 0;
  /// The BIN chunk holds the buffer's declared bytes: tinygltf gets a
  /// one-byte placeholder and the accessors read the chunk where it lies
  /// (copying it cost 15.7 MB and a fifth of the dragon's read in WASM).
  bool glb_bin_in_place = false;
  std::vector<std::string> missing;
  /// Declared byteLength of each external buffer, by its URI as tinygltf
  /// passes it (URL-decoded): never more is read.
  std::map<std::string, uint64_t> byte_length;
};

bool file_exists(const std::string&, void*) { return true; }  // ReadWholeFile decides
std::string expand_path(const std::string& path, void*) { return path; }
bool write_file(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

bool read_companion(std::vector<unsigned char>* out, std::string*, const std::string& uri, void* user) {
  auto& files = *static_cast<Files*>(user);
  if (uri == kGlbBin && !files.glb_bin_in_place) {
    out->assign(files.glb_bin, files.glb_bin + files.glb_bin_size);
    return true;
  }
  if (uri == kFallback || uri == kGlbBin) {
    out->assign(1, 0);
    return true;
  }
  const auto declared = files.byte_length.find(uri);
  const uint64_t limit = declared == files.byte_length.end() ? kMaxGltfInteger : declared->second;
  if (find_companion(*files.in, uri, limit, *out)) return true;
  files.missing.push_back(uri);
  return false;
}

uint32_t read_u32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

// The JSON and BIN chunks of a .glb container, bounds-checked.
std::string split_glb(const Input& in, Files& files) {
  if (in.size < 20) fail(ErrorKind::InvalidInput, in, "the GLB file is shorter than its 20-byte header.");
  if (read_u32(in.data + 4) != 2) {
    fail(ErrorKind::Unsupported, in,
         "only GLB version 2 is supported, not " + std::to_string(read_u32(in.data + 4)) + ".");
  }
  const size_t total = std::min<size_t>(read_u32(in.data + 8), in.size);
  const size_t json_length = read_u32(in.data + 12);
  // The header's total length may be below the 20 bytes already read.
  if (read_u32(in.data + 16) != 0x4E4F534A || total < 20 || json_length > total - 20) {
    fail(ErrorKind::InvalidInput, in, "the GLB JSON chunk is missing or longer than the file.");
  }
  size_t bin = 20 + ((json_length + 3) & ~size_t(3));
  if (bin + 8 <= total && read_u32(in.data + bin + 4) == 0x004E4942) {
    const size_t bin_length = read_u32(in.data + bin);
    if (bin_length > total - bin - 8) fail(ErrorKind::InvalidInput, in, "the GLB BIN chunk is longer than the file.");
    files.glb_bin = in.data + bin + 8;
    files.glb_bin_size = bin_length;
  }
  return std::string(reinterpret_cast<const char*>(in.data + 20), json_length);
}

// Brackets nested deeper than kMaxJsonDepth are refused before any parser
// sees them: tinygltf converts the JSON recursively.
void check_depth(const Input& in, const std::string& text) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) {
        fail(ErrorKind::InvalidInput, in,
             "the glTF JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                 std::to_string(i) + ").");
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

void check_version(const Input& in, const Json& json) {
  const auto asset = json.find("asset");
  if (asset == json.end()) return;  // tinygltf refuses it
  const auto version = asset->is_object() ? asset->find("version") : asset->end();
  if (!asset->is_object() || version == asset->end() || !version->is_string()) {
    fail(ErrorKind::InvalidInput, in, "the glTF asset has no version.");
  }
  const std::string text = version->get<std::string>();
  if (text.rfind("2.", 0) != 0) {
    fail(ErrorKind::Unsupported, in, "the glTF asset version is " + quote(text) + "; Crestline reads glTF 2.0.");
  }
}

// A JSON value as a message shows it: integers exactly, other numbers as %g
// does (never 309 digits), other types by name.
std::string describe(const Json& value) {
  if (value.is_number_unsigned()) return std::to_string(value.get<uint64_t>());
  if (value.is_number_integer()) return std::to_string(value.get<int64_t>());
  if (value.is_number()) {
    const std::string text = number_text(value.get<double>());  // 3.0 as "3.0", not "3"
    return text.find_first_not_of("-0123456789") == std::string::npos ? text + ".0" : text;
  }
  if (value.is_string()) return "the string " + quote(value.get<std::string>());
  return std::string("a ") + value.type_name();
}

// Walks `pattern` ("accessors/*/sparse/count"; * is every element of an
// array or object) and checks every value found.
void check_path(const Input& in, const Json& node, const std::vector<std::string>& parts, size_t k,
                const std::string& where) {
  if (k == parts.size()) {
    const bool ok =
        (node.is_number_unsigned() && node.get<uint64_t>() <= kMaxGltfInteger) ||
        (node.is_number_integer() && node.get<int64_t>() >= 0 && uint64_t(node.get<int64_t>()) <= kMaxGltfInteger);
    if (!ok) {
      fail(ErrorKind::InvalidInput, in,
           "the glTF property " + where + " is " + describe(node) + "; it must be an integer from 0 to " +
               std::to_string(kMaxGltfInteger) + ".");
    }
    return;
  }
  if (parts[k] == "*") {
    if (node.is_array()) {
      for (size_t i = 0; i < node.size(); ++i)
        check_path(in, node[i], parts, k + 1, where + "[" + std::to_string(i) + "]");
    } else if (node.is_object()) {
      for (auto it = node.begin(); it != node.end(); ++it)
        check_path(in, it.value(), parts, k + 1, where + "." + it.key());
    }
    return;
  }
  if (!node.is_object()) return;  // tinygltf reports the wrong type
  const auto child = node.find(parts[k]);
  if (child != node.end()) check_path(in, *child, parts, k + 1, where.empty() ? parts[k] : where + "." + parts[k]);
}

// Every index, count, offset and size the reader uses is a non-negative
// integer below 2^31, checked here in 64 bits: tinygltf narrows them to int
// or size_t (32 bits in WASM), so 2^63 became 0 and -7 "no indices".
void check_integers(const Input& in, const Json& json) {
  static const char* const patterns[] = {
      "scene",
      "scenes/*/nodes/*",
      "nodes/*/mesh",
      "nodes/*/children/*",
      "nodes/*/extensions/EXT_mesh_gpu_instancing/attributes/*",
      "meshes/*/primitives/*/indices",
      "meshes/*/primitives/*/mode",
      "meshes/*/primitives/*/attributes/*",
      "meshes/*/primitives/*/extensions/KHR_draco_mesh_compression/bufferView",
      "meshes/*/primitives/*/extensions/KHR_draco_mesh_compression/attributes/*",
      "accessors/*/bufferView",
      "accessors/*/byteOffset",
      "accessors/*/componentType",
      "accessors/*/count",
      "accessors/*/sparse/count",
      "accessors/*/sparse/indices/bufferView",
      "accessors/*/sparse/indices/byteOffset",
      "accessors/*/sparse/indices/componentType",
      "accessors/*/sparse/values/bufferView",
      "accessors/*/sparse/values/byteOffset",
      "bufferViews/*/buffer",
      "bufferViews/*/byteOffset",
      "bufferViews/*/byteLength",
      "bufferViews/*/byteStride",
      "bufferViews/*/extensions/EXT_meshopt_compression/buffer",
      "bufferViews/*/extensions/EXT_meshopt_compression/byteOffset",
      "bufferViews/*/extensions/EXT_meshopt_compression/byteLength",
      "bufferViews/*/extensions/EXT_meshopt_compression/byteStride",
      "bufferViews/*/extensions/EXT_meshopt_compression/count",
      "buffers/*/byteLength",
  };
  for (const char* pattern : patterns) {
    std::vector<std::string> parts;
    for (const char* p = pattern; *p;) {
      const char* slash = std::strchr(p, '/');
      parts.emplace_back(p, slash ? size_t(slash - p) : std::strlen(p));
      p = slash ? slash + 1 : p + std::strlen(p);
    }
    check_path(in, json, parts, 0, "");
  }
}

// Rewrites what tinygltf 2.7 cannot load as is: the GLB BIN chunk becomes a
// named file we serve (cut to the buffer's byteLength: the chunk is padded),
// EXT_meshopt_compression fallback buffers (no data by design) become
// one-byte placeholders, and Draco primitives lose their "indices" accessor
// (it has no bufferView, which tinygltf rejects; the faces come from Draco).
// Everything but geometry goes too, so a broken texture or animation cannot
// stop a mesh from loading and embedded images are never decoded.
std::string prepare_json(const Input& in, const std::string& text, bool binary, Files& files) {
  check_depth(in, text);
  Json json = Json::parse(text, nullptr, false);
  if (json.is_discarded() || !json.is_object()) {
    // A ".glb" without the GLB header that is not glTF JSON either is most
    // likely no glTF at all (a renamed file, a download error page).
    const size_t dot = in.name.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : in.name.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (!binary && ext == "glb")
      fail(ErrorKind::InvalidInput, in,
           "the file is neither a GLB (which starts with the bytes 'glTF') nor glTF JSON.");
    fail(ErrorKind::InvalidInput, in, "the glTF JSON cannot be parsed.");
  }
  check_version(in, json);
  check_integers(in, json);
  for (const char* unused : {"images", "textures", "samplers", "materials", "animations", "skins", "cameras"}) {
    json.erase(unused);
  }
  auto buffers = json.find("buffers");
  if (buffers != json.end() && buffers->is_array()) {
    for (size_t i = 0; i < buffers->size(); ++i) {
      Json& buffer = (*buffers)[i];
      if (!buffer.is_object() || buffer.contains("uri")) continue;
      const Json* meshopt = nullptr;
      if (buffer.contains("extensions") && buffer["extensions"].is_object() &&
          buffer["extensions"].contains("EXT_meshopt_compression")) {
        meshopt = &buffer["extensions"]["EXT_meshopt_compression"];
      }
      if (meshopt && meshopt->is_object() && meshopt->value("fallback", false)) {
        buffer["uri"] = kFallback;
        buffer["byteLength"] = 1;
      } else if (binary && i == 0) {
        buffer["uri"] = kGlbBin;
        const Json& length = buffer.contains("byteLength") ? buffer["byteLength"] : Json();
        if (length.is_number_unsigned())
          files.glb_bin_size = std::min<size_t>(files.glb_bin_size, length.get<size_t>());
        // Else tinygltf loads a copy and reports what does not match.
        if (length.is_number_unsigned() && files.glb_bin_size > 0 && length.get<size_t>() == files.glb_bin_size) {
          files.glb_bin_in_place = true;
          buffer["byteLength"] = 1;
        }
      }
    }
    for (const Json& buffer : *buffers) {
      if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
      const Json& length = buffer.contains("byteLength") ? buffer["byteLength"] : Json();
      files.byte_length[tinygltf::dlib::urldecode(buffer["uri"].get<std::string>())] =
          length.is_number_unsigned() ? length.get<uint64_t>() : 0;
    }
  }
  auto meshes = json.find("meshes");
  if (meshes != json.end() && meshes->is_array()) {
    for (Json& mesh : *meshes) {
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      for (Json& primitive : mesh["primitives"]) {
        if (primitive.is_object() && primitive.contains("extensions") && primitive["extensions"].is_object() &&
            primitive["extensions"].contains("KHR_draco_mesh_compression")) {
          primitive.erase("indices");
        }
      }
    }
  }
  return json.dump();
}

// tinygltf's first message as a clause: one line, no full stops.
std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  // Our internal buffer names mean nothing to the user.
  for (const auto& [internal, shown] : {std::pair<std::string, std::string>{kGlbBin, "GLB BIN chunk"},
                                        std::pair<std::string, std::string>{kFallback, "meshopt fallback buffer"}}) {
    for (size_t at = line.find(internal); at != std::string::npos; at = line.find(internal, at))
      line.replace(at, internal.size(), shown);
  }

  while (!line.empty() && (line.back() == '.' || line.back() == ' ' || line.back() == '\r')) line.pop_back();
  for (size_t stop = line.find(". "); stop != std::string::npos; stop = line.find(". ", stop)) line[stop] = ';';
  return line;
}

int value_int(const tinygltf::Value& object, const char* key, int fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  return v.IsNumber() || v.IsInt() ? int(v.GetNumberAsInt()) : fallback;
}

#ifndef __EMSCRIPTEN__

std::string value_string(const tinygltf::Value& object, const char* key) {
  if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsString()) return "";
  return object.Get(key).Get<std::string>();
}
#endif

/// A range of bytes: its start and length.
using Bytes = std::pair<const uint8_t*, size_t>;

// One primitive, decoded once per mesh and reused by every instance.
struct Primitive {
  UninitialisedVector<double> positions;  // xyz
  UninitialisedVector<uint32_t> triangles;
};

/// A stored value as a double: normalized integers are divided by their
/// type's largest value (glTF 2.0, 3.11), signed ones clamped at -1.
template <typename C>
double to_double(C value, bool normalized) {
  if constexpr (std::is_same_v<C, float>) {
    return value;
  } else if constexpr (std::is_signed_v<C>) {
    return normalized ? std::max(value / double(std::numeric_limits<C>::max()), -1.0) : value;
  } else {
    return normalized ? value / double(std::numeric_limits<C>::max()) : value;
  }
}

/// The value of type C at `data` as T (uint32_t only from unsigned
/// integers: indices, which go through a double only when normalized).
template <typename C, typename T>
T value_at(const uint8_t* data, bool normalized) {
  C value;
  std::memcpy(&value, data, sizeof(C));
  if constexpr (std::is_integral_v<T>) {
    return normalized ? T(to_double(value, true)) : T(value);
  } else {
    return T(to_double(value, normalized));
  }
}

/// `count` elements of `components` values of type C, `stride` bytes
/// apart, converted to T.
/// In blocks, so that a first large file's read leaves WASM's baseline tier
/// (numerics/serial_blocks.h).
template <typename C, typename T>
void convert(const uint8_t* data, size_t count, size_t stride, size_t components, bool normalized, T* out) {
  if (stride == components * sizeof(C)) {  // packed: one loop the compiler can vectorise
    for_serial_blocks(count * components, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) out[k] = value_at<C, T>(data + k * sizeof(C), normalized);
    });
    return;
  }
  for_serial_blocks(count, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const uint8_t* element = data + i * stride;
      for (size_t c = 0; c < components; ++c)
        out[i * components + c] = value_at<C, T>(element + c * sizeof(C), normalized);
    }
  });
}

/// convert() for a glTF componentType, chosen once per accessor rather than
/// per value. INT (5124, not a glTF accessor type) reads as FLOAT, as before.
template <typename T>
void convert(int type, const uint8_t* data, size_t count, size_t stride, size_t components, bool normalized, T* out) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return convert<int8_t>(data, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return convert<uint8_t>(data, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return convert<int16_t>(data, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return convert<uint16_t>(data, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return convert<uint32_t>(data, count, stride, components, normalized, out);
    default:
      return convert<float>(data, count, stride, components, normalized, out);
  }
}

class GltfReader {
 public:
  /// `glb_bin`: buffer 0's bytes when they stay in the GLB (Files::glb_bin_in_place), else null.
  GltfReader(const Input& in, const ReadOptions& options, const tinygltf::Model& model, Bytes glb_bin)
      : in_(in), options_(options), model_(model), glb_bin_(glb_bin) {}

  TriangleSoup read() {
    decode_meshopt_views();
    std::vector<int> roots;
    if (model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size()) {
      roots = model_.scenes[size_t(model_.defaultScene)].nodes;
    } else if (!model_.scenes.empty()) {
      roots = model_.scenes[0].nodes;
    } else {
      std::vector<char> is_child(model_.nodes.size(), 0);
      for (const auto& node : model_.nodes) {
        for (int child : node.children) {
          if (child >= 0 && size_t(child) < is_child.size()) is_child[size_t(child)] = 1;
        }
      }
      for (size_t n = 0; n < model_.nodes.size(); ++n) {
        if (!is_child[n]) roots.push_back(int(n));
      }
    }
    traverse(roots, true);  // counts what the instances expand to, refuses past the limit
    check_expansion();
    traverse(roots, false);
    if (skipped_primitives_ > 0) {
      soup_.notes.push_back(std::to_string(skipped_primitives_) + " point or line primitives were ignored.");
    }
    return std::move(soup_);
  }

 private:
  [[noreturn]] void invalid(const std::string& problem) const { fail(ErrorKind::InvalidInput, in_, problem); }

  // Walks the node tree from `roots`. Counting, it only adds up how often
  // each mesh is placed (GPU instances by their accessor's count, nothing
  // read); otherwise it places every instance in the soup.
  void traverse(const std::vector<int>& roots, bool counting) {
    struct Frame {
      int node;
      Eigen::Matrix4d parent;
      bool exit;
    };
    std::vector<char> on_path(model_.nodes.size(), 0), visited(model_.nodes.size(), 0);
    std::vector<Frame> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, Eigen::Matrix4d::Identity(), false});
    while (!stack.empty()) {
      Frame frame = stack.back();
      stack.pop_back();
      if (frame.exit) {
        on_path[size_t(frame.node)] = 0;
        continue;
      }
      if (frame.node < 0 || size_t(frame.node) >= model_.nodes.size()) {
        invalid("the scene refers to node " + std::to_string(frame.node) + " but the file has " +
                std::to_string(model_.nodes.size()) + " nodes.");
      }
      const size_t n = size_t(frame.node);
      if (on_path[n]) invalid("the node hierarchy has a cycle through node " + std::to_string(n) + ".");
      if (visited[n]) invalid("node " + std::to_string(n) + " has more than one parent.");
      on_path[n] = visited[n] = 1;
      const tinygltf::Node& node = model_.nodes[n];
      const Eigen::Matrix4d world = frame.parent * local_transform(node);
      if (node.mesh >= 0 && counting) {
        auto gpu = node.extensions.find("EXT_mesh_gpu_instancing");
        const uint64_t copies = gpu == node.extensions.end() ? 1 : gpu_instance_count(gpu->second);
        uint64_t& placed = placements_[node.mesh];
        placed = std::min<uint64_t>(placed + copies, UINT64_MAX / 2);
      } else if (node.mesh >= 0) {
        auto gpu = node.extensions.find("EXT_mesh_gpu_instancing");
        if (gpu == node.extensions.end()) {
          add_instance(node.mesh, world);
        } else {
          for (const Eigen::Matrix4d& instance : gpu_instances(gpu->second, n))
            add_instance(node.mesh, world * instance);
        }
      }
      stack.push_back({frame.node, Eigen::Matrix4d::Identity(), true});
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world, false});
    }
  }

  static Eigen::Matrix4d local_transform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return Eigen::Map<const Eigen::Matrix4d>(node.matrix.data());  // column-major
    return trs(node.translation.size() == 3 ? node.translation.data() : nullptr,
               node.rotation.size() == 4 ? node.rotation.data() : nullptr,
               node.scale.size() == 3 ? node.scale.data() : nullptr);
  }

  /// T * R * S; a null part is the identity, a quaternion is (x, y, z, w).
  static Eigen::Matrix4d trs(const double* translation, const double* rotation, const double* scale) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (scale) m = Eigen::Vector4d(scale[0], scale[1], scale[2], 1).asDiagonal();
    if (rotation) {
      Eigen::Quaterniond q(rotation[3], rotation[0], rotation[1], rotation[2]);
      if (q.norm() > 0) {
        Eigen::Matrix4d r = Eigen::Matrix4d::Identity();
        r.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix();
        m = r * m;
      }
    }
    if (translation) m.topRightCorner<3, 1>() += Eigen::Vector3d(translation[0], translation[1], translation[2]);
    return m;
  }

  /// How many instances EXT_mesh_gpu_instancing declares (the longest of
  /// its attribute accessors; gpu_instances checks they agree).
  uint64_t gpu_instance_count(const tinygltf::Value& extension) const {
    const tinygltf::Value none;
    const tinygltf::Value& attributes = extension.Has("attributes") ? extension.Get("attributes") : none;
    uint64_t count = 0;
    for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"}) {
      const int accessor = value_int(attributes, name, -1);
      if (accessor >= 0 && size_t(accessor) < model_.accessors.size())
        count = std::max<uint64_t>(count, model_.accessors[size_t(accessor)].count);
    }
    return count;
  }

  /// Refuses a scene whose instances expand past the limits, before any is
  /// expanded: each placed mesh is decoded once to count its triangles and
  /// vertices, which are then multiplied by how often it is placed (10^6
  /// GPU instances of a small mesh took 4 GB and 18 s, then gave a soup).
  /// Besides the triangle limit, the expansion is bounded relative to the
  /// triangles stored (ReadOptions::max_expansion explains the numbers).
  void check_expansion() {
    uint64_t triangles = 0, vertices = 0, placed = 0, stored = 0;
    auto add = [](uint64_t& total, uint64_t each, uint64_t copies) {
      const uint64_t cap = UINT64_MAX / 4;
      total = each > 0 && copies > (cap - total) / each ? cap : total + each * copies;
    };
    for (const auto& [mesh, copies] : placements_) {
      check_mesh_index(mesh);
      uint64_t mesh_triangles = 0, mesh_vertices = 0;
      for (const Primitive& primitive : decoded(mesh)) {
        mesh_triangles += primitive.triangles.size() / 3;
        mesh_vertices += primitive.positions.size() / 3;
      }
      if (copies > 0) stored += mesh_triangles;
      add(triangles, mesh_triangles, copies);
      add(vertices, mesh_vertices, copies);
      placed = std::min<uint64_t>(placed + copies, UINT64_MAX / 4);
    }
    if (triangles > options_.max_triangles || vertices > 3 * uint64_t(options_.max_triangles) + 3) {
      const bool by_triangles = triangles > options_.max_triangles;
      fail(ErrorKind::TooLarge, in_,
           "the scene places its meshes " + std::to_string(placed) + " times, which expands to " +
               std::to_string(by_triangles ? triangles : vertices) + (by_triangles ? " triangles" : " vertices") +
               ", more than the limit of " +
               std::to_string(by_triangles ? options_.max_triangles : 3 * options_.max_triangles + 3) + ".");
    }
    const uint64_t ratio = options_.max_expansion;
    const uint64_t limit =
        std::max<uint64_t>(options_.max_expanded_triangles,
                           stored > UINT64_MAX / 4 / std::max<uint64_t>(ratio, 1) ? UINT64_MAX / 4 : ratio * stored);
    if (triangles > limit) {
      fail(ErrorKind::TooLarge, in_,
           "the scene places its meshes " + std::to_string(placed) + " times, which expands their " +
               std::to_string(stored) + " triangles to " + std::to_string(triangles) + ", more than the limit of " +
               std::to_string(limit) + " (" + std::to_string(ratio) + " times the triangles stored, or " +
               std::to_string(options_.max_expanded_triangles) + " if that is more).");
    }
    soup_.positions.reserve(3 * vertices);
    soup_.indices.reserve(3 * triangles);
  }

  void check_mesh_index(int mesh_index) const {
    if (mesh_index < 0 || size_t(mesh_index) >= model_.meshes.size()) {
      invalid("a node refers to mesh " + std::to_string(mesh_index) + " but the file has " +
              std::to_string(model_.meshes.size()) + " meshes.");
    }
  }

  const std::vector<Primitive>& decoded(int mesh_index) {
    auto cached = decoded_.find(mesh_index);
    if (cached == decoded_.end()) cached = decoded_.emplace(mesh_index, decode_mesh(mesh_index)).first;
    return cached->second;
  }

  /// The per-instance transforms of EXT_mesh_gpu_instancing.
  std::vector<Eigen::Matrix4d> gpu_instances(const tinygltf::Value& extension, size_t node) const {
    const std::string where = "node " + std::to_string(node) + " (EXT_mesh_gpu_instancing)";
    const tinygltf::Value none;
    const tinygltf::Value& attributes = extension.Has("attributes") ? extension.Get("attributes") : none;
    std::vector<double> parts[3];
    const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    const int types[3] = {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4, TINYGLTF_TYPE_VEC3};
    size_t count = 0;
    for (int k = 0; k < 3; ++k) {
      const int accessor = value_int(attributes, names[k], -1);
      if (accessor < 0) continue;
      read_accessor(accessor, types[k], where + " " + names[k], parts[k]);
      const size_t n = parts[k].size() / size_t(k == 1 ? 4 : 3);
      if (count != 0 && n != count) invalid(where + " has attributes of different lengths.");
      count = n;
    }
    std::vector<Eigen::Matrix4d> instances;
    for (size_t i = 0; i < count; ++i) {
      instances.push_back(trs(parts[0].empty() ? nullptr : &parts[0][3 * i],
                              parts[1].empty() ? nullptr : &parts[1][4 * i],
                              parts[2].empty() ? nullptr : &parts[2][3 * i]));
    }
    return instances;
  }

  void add_instance(int mesh_index, const Eigen::Matrix4d& world) {
    check_mesh_index(mesh_index);
    for (const Primitive& primitive : decoded(mesh_index)) {
      if (soup_.triangle_count() + primitive.triangles.size() / 3 > options_.max_triangles) {
        fail(ErrorKind::TooLarge, in_,
             "the scene has more than " + std::to_string(options_.max_triangles) + " triangles.");
      }
      const uint32_t base = uint32_t(soup_.vertex_count());
      const bool identity = world == Eigen::Matrix4d::Identity();
      // Copied into the capacity check_expansion reserved (resize() would
      // zero-fill first), then transformed from the primitive's values: in
      // the WASM SIMD build an in-place p = world * (p, 1) miscomputed
      // (LLVM 14's SLP vectorizer, which the WASM build now leaves off:
      // CMakeLists.txt, tests/wasm/slp_check.cpp).
      // From pointers, so that the copies are memcpy's also in libc++ (the
      // WASM build); the loops in blocks (numerics/serial_blocks.h).
      auto& positions = soup_.positions;
      const size_t first = positions.size();
      const double* source = primitive.positions.data();
      positions.insert(positions.end(), source, source + primitive.positions.size());
      for_serial_blocks(primitive.positions.size() / 3, [&](size_t begin, size_t end) {
        for (size_t v = 3 * begin; v < 3 * end; v += 3) {
          const double* s = source + v;
          double* p = &positions[first + v];
          // The identity's product, without it: x + 0 (-0 becomes +0 as in
          // the product), unless a coordinate is not finite (0 * inf is NaN).
          if (identity && std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2])) {
            p[0] = s[0] + 0.0, p[1] = s[1] + 0.0, p[2] = s[2] + 0.0;
          } else {
            const Eigen::Vector4d q = world * Eigen::Vector4d(s[0], s[1], s[2], 1.0);
            p[0] = q[0], p[1] = q[1], p[2] = q[2];
          }
        }
      });
      auto& indices = soup_.indices;
      const size_t corner = indices.size();
      const uint32_t* triangles = primitive.triangles.data();
      indices.insert(indices.end(), triangles, triangles + primitive.triangles.size());
      if (base > 0) {
        uint32_t* added = indices.data() + corner;
        for_serial_blocks(primitive.triangles.size(), [&](size_t begin, size_t end) {
          for (size_t k = begin; k < end; ++k) added[k] += base;
        });
      }
    }
  }

  std::vector<Primitive> decode_mesh(int mesh_index) {
    std::vector<Primitive> primitives;
    const auto& mesh = model_.meshes[size_t(mesh_index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& source = mesh.primitives[p];
      const std::string where = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
      if (source.mode < TINYGLTF_MODE_TRIANGLES || source.mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        ++skipped_primitives_;
        continue;
      }
      Primitive primitive;
      UninitialisedVector<uint32_t> indices;
      bool indexed = source.indices >= 0;
      auto draco = source.extensions.find("KHR_draco_mesh_compression");
      if (draco != source.extensions.end()) {
        decode_draco(draco->second, where, primitive.positions, indices);
        indexed = true;
      } else {
        auto position = source.attributes.find("POSITION");
        if (position == source.attributes.end()) invalid(where + " has no POSITION attribute.");
        read_accessor(position->second, TINYGLTF_TYPE_VEC3, where + " POSITION", primitive.positions);
        if (indexed) {
          check_index_type(source.indices, where);
          read_accessor(source.indices, TINYGLTF_TYPE_SCALAR, where + " indices", indices);
        }
      }
      const size_t vertices = primitive.positions.size() / 3;
      if (!indexed) {
        indices.resize(vertices);
        std::iota(indices.begin(), indices.end(), 0u);
      }
      // The corners the mode uses: the whole triangles of a list, every
      // index of a strip or fan of three or more.
      const size_t count = indices.size();
      const size_t used = source.mode == TINYGLTF_MODE_TRIANGLES ? count - count % 3 : count >= 3 ? count : 0;
      uint32_t largest = 0;
      for_serial_blocks(used, [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) largest = std::max(largest, indices[k]);
      });
      // Only when one is out of range: find the first to name it.
      for (size_t k = 0; largest >= vertices && k < used; ++k) {
        if (indices[k] >= vertices) {
          invalid(where + " refers to vertex " + std::to_string(indices[k]) + " but has only " +
                  std::to_string(vertices) + " vertices.");
        }
      }
      auto& out = primitive.triangles;
      if (source.mode == TINYGLTF_MODE_TRIANGLES) {
        indices.resize(used);
        out = std::move(indices);
      } else if (source.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Every other triangle is flipped to keep one orientation.
        for (size_t k = 0; k + 2 < count; ++k) {
          if (k % 2 == 0)
            out.insert(out.end(), {indices[k], indices[k + 1], indices[k + 2]});
          else
            out.insert(out.end(), {indices[k + 1], indices[k], indices[k + 2]});
        }
      } else {
        for (size_t k = 1; k + 1 < count; ++k) out.insert(out.end(), {indices[0], indices[k], indices[k + 1]});
      }
      primitives.push_back(std::move(primitive));
    }
    return primitives;
  }

  // Indices are unsigned integers (glTF 2.0, 3.7.2.1); FLOAT ones would be
  // truncated into triangles that look merely degenerate.
  void check_index_type(int index, const std::string& where) const {
    if (index < 0 || size_t(index) >= model_.accessors.size()) return;  // read_accessor says so
    const int type = model_.accessors[size_t(index)].componentType;
    if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      invalid(where + " has indices of component type " + std::to_string(type) +
              (type == TINYGLTF_COMPONENT_TYPE_FLOAT ? " (FLOAT)" : "") +
              "; indices must be unsigned bytes, shorts or ints.");
    }
  }

  // The bytes of a buffer: tinygltf's, or the GLB BIN chunk in place.
  Bytes buffer_bytes(size_t buffer) const {
    if (buffer == 0 && glb_bin_.first) return glb_bin_;
    return {model_.buffers[buffer].data.data(), model_.buffers[buffer].data.size()};
  }

  // The bytes of a bufferView: meshopt-decoded, or a checked range of its buffer.
  Bytes view_bytes(int view_index, const std::string& what) const {
    if (view_index < 0 || size_t(view_index) >= model_.bufferViews.size()) {
      invalid(what + " refers to bufferView " + std::to_string(view_index) + ", which does not exist.");
    }
    auto decoded = meshopt_views_.find(view_index);
    if (decoded != meshopt_views_.end()) return {decoded->second.data(), decoded->second.size()};
    const tinygltf::BufferView& view = model_.bufferViews[size_t(view_index)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) {
      invalid("bufferView " + std::to_string(view_index) + " refers to a buffer that does not exist.");
    }
    const auto [data, size] = buffer_bytes(size_t(view.buffer));
    if (view.byteOffset > size || view.byteLength > size - view.byteOffset) {
      invalid("bufferView " + std::to_string(view_index) + " reaches past the end of its buffer.");
    }
    return {data + view.byteOffset, view.byteLength};
  }

  // Checks that `count` elements of `element` bytes at `stride` starting at
  // `offset` fit in `size` bytes.
  void check_range(size_t offset, size_t count, size_t stride, size_t element, size_t size,
                   const std::string& what) const {
    if (count == 0) return;
    if (stride < element || offset > size || size - offset < element ||
        (count - 1) > (size - offset - element) / stride) {
      invalid(what + " reaches past the end of its bufferView.");
    }
  }

  /// The values of accessor `index` (of glTF type `type`) into `out`:
  /// doubles, or uint32_t for indices (unsigned integer components only).
  template <typename Vector>
  void read_accessor(int index, int type, const std::string& what, Vector& out) const {
    using T = typename Vector::value_type;
    if (index < 0 || size_t(index) >= model_.accessors.size()) {
      invalid(what + " refers to accessor " + std::to_string(index) + ", which does not exist.");
    }
    const tinygltf::Accessor& accessor = model_.accessors[size_t(index)];
    const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    const int size = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    if (accessor.type != type || size <= 0 || accessor.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE) {
      invalid(what + " has an unexpected type.");
    }
    if (std::is_integral_v<T> && accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      invalid(what + " has an unexpected type.");
    }
    const size_t count = accessor.count;
    if (count > 3 * options_.max_triangles + 3) {
      fail(ErrorKind::TooLarge, in_, what + " claims " + std::to_string(count) + " elements, more than the limit.");
    }
    const size_t element = size_t(size) * size_t(components);
    if (accessor.bufferView >= 0) {
      const auto [data, length] = view_bytes(accessor.bufferView, what);
      const size_t declared = model_.bufferViews[size_t(accessor.bufferView)].byteStride;
      const size_t stride = declared ? declared : element;
      check_range(accessor.byteOffset, count, stride, element, length, what);
      out.resize(count * size_t(components));
      convert(accessor.componentType, data + accessor.byteOffset, count, stride, size_t(components),
              accessor.normalized, out.data());
    } else {
      // No bufferView: zeros, then the sparse values. Nothing in the file
      // backs the count, so allow at most one element per byte of the file.
      if (count > std::max<size_t>(in_.size, 1024)) {
        invalid(what + " claims " + std::to_string(count) + " elements that the file holds no data for.");
      }
      out.assign(count * size_t(components), T(0));
    }
    if (!accessor.sparse.isSparse) return;
    const auto& sparse = accessor.sparse;
    const size_t sparse_count = size_t(std::max(sparse.count, 0));
    const int index_size = tinygltf::GetComponentSizeInBytes(uint32_t(sparse.indices.componentType));
    if (index_size <= 0 || (index_size == 4 && sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
      invalid(what + " has sparse indices of an unexpected type.");
    }
    const auto [index_data, index_length] = view_bytes(sparse.indices.bufferView, what + " sparse indices");
    const auto [value_data, value_length] = view_bytes(sparse.values.bufferView, what + " sparse values");
    check_range(size_t(std::max(sparse.indices.byteOffset, 0)), sparse_count, size_t(index_size), size_t(index_size),
                index_length, what + " sparse indices");
    check_range(size_t(std::max(sparse.values.byteOffset, 0)), sparse_count, element, element, value_length,
                what + " sparse values");
    for (size_t k = 0; k < sparse_count; ++k) {
      double target = 0;
      convert(sparse.indices.componentType,
              index_data + std::max(sparse.indices.byteOffset, 0) + k * size_t(index_size), 1, 0, 1, false, &target);
      if (!(target >= 0 && target < double(count))) invalid(what + " has a sparse index out of range.");
      convert(accessor.componentType, value_data + std::max(sparse.values.byteOffset, 0) + k * element, 1, 0,
              size_t(components), accessor.normalized, &out[size_t(target) * size_t(components)]);
    }
  }

#ifndef __EMSCRIPTEN__
  void decode_meshopt_views() {
    for (size_t v = 0; v < model_.bufferViews.size(); ++v) {
      auto extension = model_.bufferViews[v].extensions.find("EXT_meshopt_compression");
      if (extension == model_.bufferViews[v].extensions.end()) continue;
      const tinygltf::Value& e = extension->second;
      const std::string what = "bufferView " + std::to_string(v) + " (EXT_meshopt_compression)";
      const int buffer = value_int(e, "buffer", -1);
      const int offset = value_int(e, "byteOffset", 0);
      const int length = value_int(e, "byteLength", -1);
      const int stride = value_int(e, "byteStride", -1);
      const int count = value_int(e, "count", -1);
      const std::string mode = value_string(e, "mode");
      const std::string filter = value_string(e, "filter");
      if (buffer < 0 || size_t(buffer) >= model_.buffers.size() || offset < 0 || length < 0 || stride <= 0 ||
          stride > 256 || count < 0) {
        invalid(what + " has missing or invalid properties.");
      }
      const auto [data, size] = buffer_bytes(size_t(buffer));
      if (size_t(offset) > size || size_t(length) > size - size_t(offset)) {
        invalid(what + " reaches past the end of its buffer.");
      }
      if (uint64_t(count) > 3 * uint64_t(options_.max_triangles) + 3) {
        fail(ErrorKind::TooLarge, in_, what + " claims " + std::to_string(count) + " elements, more than the limit.");
      }
      // meshopt's codecs spend at least 2 bits per 16 bytes of output (the
      // vertex codec's group headers), so more than 64:1 cannot be genuine.
      if (uint64_t(count) * uint64_t(stride) > 64 * uint64_t(length) + 4096) {
        invalid(what + " claims " + std::to_string(uint64_t(count) * uint64_t(stride)) + " bytes from " +
                std::to_string(length) + " compressed bytes.");
      }
      // meshoptimizer asserts these (the extension requires them).
      const bool valid_layout =
          mode == "ATTRIBUTES"  ? stride % 4 == 0 && (filter.empty() || filter == "NONE" ||
                                                     (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) ||
                                                     (filter == "QUATERNION" && stride == 8) || filter == "EXPONENTIAL")
          : mode == "TRIANGLES" ? (stride == 2 || stride == 4) && count % 3 == 0
          : mode == "INDICES"   ? stride == 2 || stride == 4
                                : false;
      if (!valid_layout) invalid(what + " has an invalid mode, filter or byteStride.");
      std::vector<uint8_t> out(size_t(count) * size_t(stride));
      const unsigned char* source = data + offset;
      int status = -1;
      if (mode == "ATTRIBUTES") {
        status = meshopt_decodeVertexBuffer(out.data(), size_t(count), size_t(stride), source, size_t(length));
        if (status == 0 && filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), size_t(count), size_t(stride));
        if (status == 0 && filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), size_t(count), size_t(stride));
        if (status == 0 && filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), size_t(count), size_t(stride));
      } else {
        status = mode == "TRIANGLES"
                     ? meshopt_decodeIndexBuffer(out.data(), size_t(count), size_t(stride), source, size_t(length))
                     : meshopt_decodeIndexSequence(out.data(), size_t(count), size_t(stride), source, size_t(length));
      }
      if (status != 0) invalid(what + " cannot be decoded.");
      meshopt_views_[int(v)] = std::move(out);
    }
  }

  void decode_draco(const tinygltf::Value& extension, const std::string& where, UninitialisedVector<double>& positions,
                    UninitialisedVector<uint32_t>& indices) const {
    const auto [data, length] = view_bytes(value_int(extension, "bufferView", -1), where + " (Draco)");
    const int position_id = extension.Has("attributes") ? value_int(extension.Get("attributes"), "POSITION", -1) : -1;
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), length);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
      invalid(where + " has Draco data that cannot be decoded (" + decoded.status().error_msg_string() + ").");
    const draco::Mesh& mesh = *decoded.value();
    const draco::PointAttribute* attribute =
        position_id >= 0 ? mesh.GetAttributeByUniqueId(uint32_t(position_id)) : nullptr;
    if (!attribute || attribute->num_components() < 3) invalid(where + " has no Draco POSITION attribute.");
    positions.resize(3 * size_t(mesh.num_points()));
    for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
      if (!attribute->ConvertValue<double>(attribute->mapped_index(i), 3, &positions[3 * size_t(i.value())])) {
        invalid(where + " has Draco positions that cannot be converted.");
      }
    }
    indices.resize(3 * size_t(mesh.num_faces()));
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) indices[3 * size_t(f.value()) + size_t(k)] = mesh.face(f)[k].value();
    }
  }
#else
  void decode_meshopt_views() {
    for (const auto& view : model_.bufferViews) {
      if (view.extensions.count("EXT_meshopt_compression")) unsupported_compression("EXT_meshopt_compression");
    }
  }
  void decode_draco(const tinygltf::Value&, const std::string&, UninitialisedVector<double>&,
                    UninitialisedVector<uint32_t>&) const {
    unsupported_compression("KHR_draco_mesh_compression");
  }
  [[noreturn]] void unsupported_compression(const char* extension) const {
    fail(ErrorKind::Unsupported, in_,
         std::string("the mesh is compressed with ") + extension +
             "; decode it in the browser before passing it to the WASM core.");
  }
#endif

  const Input& in_;
  const ReadOptions& options_;
  const tinygltf::Model& model_;
  const Bytes glb_bin_;
  TriangleSoup soup_;
  std::map<int, std::vector<uint8_t>> meshopt_views_;
  std::map<int, std::vector<Primitive>> decoded_;
  std::map<int, uint64_t> placements_;  // how often each mesh is placed
  size_t skipped_primitives_ = 0;
};

}  // namespace

TriangleSoup read_gltf(const Input& in, const ReadOptions& options) {
  Files files;
  files.in = &in;
  const bool binary = in.size >= 4 && std::memcmp(in.data, "glTF", 4) == 0;
  const std::string json = prepare_json(
      in, binary ? split_glb(in, files) : std::string(reinterpret_cast<const char*>(in.data), in.size), binary, files);

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({file_exists, expand_path, read_companion, write_file, &files});
  tinygltf::Model model;
  std::string error, warning;
  if (!loader.LoadASCIIFromString(&model, &error, &warning, json.data(), unsigned(json.size()), "")) {
    if (!files.missing.empty()) {
      fail(ErrorKind::Io, in, "the buffer file " + quote(files.missing.front()) + " it refers to was not found.");
    }
    // "File size mismatch : <uri>, requestedBytes <n>, but got <m>"
    const size_t mismatch = error.find("File size mismatch : ");
    if (mismatch != std::string::npos) {
      std::string detail = first_line(error.substr(mismatch + 21));
      const size_t comma = detail.find(", requestedBytes ");
      const size_t got = detail.find(", but got ");
      if (comma != std::string::npos && got != std::string::npos) {
        const std::string uri = detail.substr(0, comma);
        fail(ErrorKind::InvalidInput, in,
             "the " + (uri == "GLB BIN chunk" ? uri : "buffer " + quote(uri)) + " has " + detail.substr(got + 10) +
                 " bytes but the glTF declares " + detail.substr(comma + 17, got - comma - 17) + ".");
      }
    }
    // tinygltf echoes a broken data URI whole (kilobytes): keep its start.
    std::string clause = first_line(error);
    if (clause.size() > 2 * kMaxQuoted) clause = clause.substr(0, 2 * kMaxQuoted - 3) + "...";
    fail(ErrorKind::InvalidInput, in, "the glTF data is invalid (" + clause + ").");
  }
  const Bytes glb_bin{files.glb_bin_in_place ? files.glb_bin : nullptr, files.glb_bin_size};
  TriangleSoup soup = GltfReader(in, options, model, glb_bin).read();
  finish_soup(soup, in);
  return soup;
}

}  // namespace crestline::io::detail
