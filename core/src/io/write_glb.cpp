// glTF 2.0 binary (GLB) output: the lines as LINE_STRIP primitives, and
// optionally the surface as one TRIANGLES primitive. Written by hand (header,
// JSON chunk, BIN chunk) so the file compiles unchanged with em++.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "crestline/io/write_lines.h"

namespace crestline::io {
namespace {

constexpr uint32_t kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr uint32_t kFloat = 5126, kUnsignedInt = 5125;
constexpr int kTriangles = 4, kLineStrip = 3;
constexpr int kRidgeMaterial = 0, kValleyMaterial = 1, kSurfaceMaterial = 2, kCreaseMaterial = 3;

// "#rrggbb" as a glTF baseColorFactor "r,g,b,1" (each channel / 255, as the
// ridge and valley materials are written).
std::string color_factor(const char* hex) {
  unsigned r = 0, g = 0, b = 0;
  std::sscanf(hex, "#%02x%02x%02x", &r, &g, &b);
  char out[64];
  std::snprintf(out, sizeof out, "%.3g,%.3g,%.3g,1", r / 255.0, g / 255.0, b / 255.0);
  return out;
}

// float32 printed so that it reads back to the same float.
void append_float(std::string& out, float value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", std::isfinite(value) ? double(value) : 0.0);
  out += buffer;
}

// Collects the BIN chunk and the accessors/bufferViews describing it.
class Builder {
 public:
  std::string accessors, views;
  std::vector<uint8_t> bin;

  // Returns the accessor index of the positions.
  size_t add_positions(const std::vector<Vec3>& points) {
    float low[3], high[3];
    std::fill(low, low + 3, std::numeric_limits<float>::max());
    std::fill(high, high + 3, std::numeric_limits<float>::lowest());
    std::vector<float> values;
    values.reserve(points.size() * 3);
    for (const Vec3& p : points)
      for (int axis = 0; axis < 3; ++axis) {
        const float v = static_cast<float>(p[axis]);
        values.push_back(v);
        low[axis] = std::min(low[axis], v);
        high[axis] = std::max(high[axis], v);
      }
    const size_t view = add_view(values.data(), values.size() * sizeof(float), kArrayBuffer);
    std::string bounds;
    for (const auto& [key, values] : {std::pair{",\"min\":[", low}, std::pair{"],\"max\":[", high}}) {
      bounds += key;
      for (int axis = 0; axis < 3; ++axis) {
        if (axis) bounds += ',';
        append_float(bounds, values[axis]);
      }
    }
    bounds += ']';
    return add_accessor(view, kFloat, points.size(), "VEC3", bounds);
  }

  size_t add_indices(const std::vector<uint32_t>& indices) {
    const size_t view = add_view(indices.data(), indices.size() * sizeof(uint32_t), kElementArrayBuffer);
    return add_accessor(view, kUnsignedInt, indices.size(), "SCALAR", "");
  }

 private:
  size_t view_count = 0, accessor_count = 0;

  size_t add_view(const void* data, size_t bytes, uint32_t target) {
    const size_t offset = bin.size();  // always a multiple of 4: every element is 4 bytes
    bin.resize(offset + bytes);
    if (bytes) std::memcpy(bin.data() + offset, data, bytes);
    if (view_count) views += ',';
    views += "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(bytes) +
             ",\"target\":" + std::to_string(target) + '}';
    return view_count++;
  }

  size_t add_accessor(size_t view, uint32_t component, size_t count, const char* type, const std::string& extra) {
    if (accessor_count) accessors += ',';
    accessors += "{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" + std::to_string(component) +
                 ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + '"' + extra + '}';
    return accessor_count++;
  }
};

std::string primitive(size_t positions, size_t indices, int mode, int material, const std::string& extras = {}) {
  return "{\"attributes\":{\"POSITION\":" + std::to_string(positions) + "},\"indices\":" + std::to_string(indices) +
         ",\"mode\":" + std::to_string(mode) + ",\"material\":" + std::to_string(material) +
         (extras.empty() ? "" : ",\"extras\":" + extras) + '}';
}

void append_u32(std::vector<uint8_t>& out, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<uint8_t>(value >> shift));
}

}  // namespace

std::vector<uint8_t> write_glb(const Mesh* mesh, const std::vector<Polyline>& lines) {
  Builder builder;
  std::string meshes, nodes;
  size_t mesh_count = 0, node_count = 0;
  // One node per group; the node gets a mesh only if it has primitives
  // (glTF requires at least one per mesh).
  auto add_node = [&](const char* name, const std::string& primitives) {
    if (node_count) nodes += ',';
    nodes += std::string("{\"name\":\"") + name + '"';
    if (!primitives.empty()) {
      if (mesh_count) meshes += ',';
      meshes += std::string("{\"name\":\"") + name + "\",\"primitives\":[" + primitives + "]}";
      nodes += ",\"mesh\":" + std::to_string(mesh_count++);
    }
    nodes += '}';
    ++node_count;
  };

  if (mesh && !mesh->triangles.empty()) {
    const size_t positions = builder.add_positions(mesh->positions);
    std::vector<uint32_t> indices;
    indices.reserve(mesh->triangles.size() * 3);
    for (const Triangle& t : mesh->triangles) indices.insert(indices.end(), t.begin(), t.end());
    add_node("surface", primitive(positions, builder.add_indices(indices), kTriangles, kSurfaceMaterial));
  }
  for (LineType type : {LineType::Ridge, LineType::Valley, LineType::Crease}) {
    const int material = type == LineType::Ridge    ? kRidgeMaterial
                         : type == LineType::Valley ? kValleyMaterial
                                                    : kCreaseMaterial;
    std::string primitives;
    for (const Polyline& line : lines) {
      if (line.type != type || line.points.size() < 2) continue;
      std::vector<uint32_t> indices(line.points.size());
      for (size_t k = 0; k < indices.size(); ++k) indices[k] = static_cast<uint32_t>(k);
      if (line.closed) indices.push_back(0);  // LINE_STRIP back to the start
      const size_t positions = builder.add_positions(line.points);
      if (!primitives.empty()) primitives += ',';
      const std::string extras =
          type == LineType::Crease ? std::string("{\"convex\":") + (line.convex ? "true" : "false") + '}' : "";
      primitives += primitive(positions, builder.add_indices(indices), kLineStrip, material, extras);
    }
    // Ridges and valleys always have their node; creases only when there are any.
    if (type == LineType::Crease && primitives.empty()) continue;
    add_node(type == LineType::Ridge ? "ridges" : type == LineType::Valley ? "valleys" : "creases", primitives);
  }

  std::string scene_nodes;
  for (size_t i = 0; i < node_count; ++i) scene_nodes += (i ? "," : "") + std::to_string(i);
  auto material = [](const char* name, const char* color) {
    return std::string("{\"name\":\"") + name + "\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[" + color +
           "],\"metallicFactor\":0,\"roughnessFactor\":1}}";
  };
  std::string json =
      "{\"asset\":{\"version\":\"2.0\",\"generator\":\"crestline\"},\"scene\":0,\"scenes\":[{\"nodes\":[" +
      scene_nodes + "]}],\"nodes\":[" + nodes + "]";
  if (mesh_count) json += ",\"meshes\":[" + meshes + "]";
  json += ",\"materials\":[" + material("ridge", "0.75,0.22,0.17,1") + ',' + material("valley", "0.14,0.45,0.64,1") +
          ',' + material("surface", "0.8,0.8,0.8,1") + ',' + material("crease", color_factor(kCreaseColor).c_str()) +
          ']';
  if (!builder.bin.empty()) {
    json += ",\"buffers\":[{\"byteLength\":" + std::to_string(builder.bin.size()) + "}],\"bufferViews\":[" +
            builder.views + "],\"accessors\":[" + builder.accessors + ']';
  }
  json += '}';
  while (json.size() % 4) json += ' ';
  std::vector<uint8_t>& bin = builder.bin;
  while (bin.size() % 4) bin.push_back(0);

  std::vector<uint8_t> out;
  const size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  out.reserve(total);
  append_u32(out, 0x46546C67);  // "glTF"
  append_u32(out, 2);
  append_u32(out, static_cast<uint32_t>(total));
  append_u32(out, static_cast<uint32_t>(json.size()));
  append_u32(out, 0x4E4F534A);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  if (!bin.empty()) {
    append_u32(out, static_cast<uint32_t>(bin.size()));
    append_u32(out, 0x004E4942);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
  }
  return out;
}

}  // namespace crestline::io
