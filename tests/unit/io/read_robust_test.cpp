// Broken files never crash, hang or throw anything but crestline::Error:
// deterministic mutations (truncation, random bytes, numbers in the text
// swapped for extreme ones, GLB JSON numbers changed in place) of one small
// file per format. Run under -DCRESTLINE_SANITIZE=ON for full effect.
#include <cctype>
#include <chrono>
#include <cstring>
#include <fstream>
#include <random>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "read_test_bytes.h"
#include "test_meshes.h"

using crestline::Error;
using crestline::io::NamedBuffer;
using crestline::io::read_mesh_bytes;

namespace {

std::vector<uint8_t> load(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// Replaces the digit run at or after `at` by `number`; with `keep_length`
// the result is cut or space-padded to the old length (GLB chunk sizes).
void replace_number(std::vector<uint8_t>& bytes, size_t at, size_t end, const std::string& number, bool keep_length) {
  while (at < end && !std::isdigit(bytes[at])) ++at;
  if (at >= end) return;
  size_t stop = at;
  while (stop < end && std::isdigit(bytes[stop])) ++stop;
  std::string text = number;
  if (keep_length) text.resize(stop - at, ' ');
  bytes.erase(bytes.begin() + long(at), bytes.begin() + long(stop));
  bytes.insert(bytes.begin() + long(at), text.begin(), text.end());
}

std::vector<uint8_t> mutate(const std::vector<uint8_t>& original, bool glb, std::mt19937& random) {
  static const char* const numbers[] = {"0",          "1",          "2",          "3",          "4",
                                        "7",          "255",        "65535",      "4294967295", "4294967296",
                                        "2147483647", "1000000000", "99999999999"};
  std::vector<uint8_t> bytes = original;
  if (bytes.size() < 24) return bytes;
  uint32_t json_length = 0;
  std::memcpy(&json_length, &bytes[12], 4);
  const size_t json_end = glb ? std::min<size_t>(20 + size_t(json_length), bytes.size()) : bytes.size();
  switch (random() % 4) {
    case 0:
      bytes.resize(random() % bytes.size());
      break;
    case 1:
      for (int k = 0; k < 1 + int(random() % 6); ++k) bytes[random() % bytes.size()] = uint8_t(random());
      break;
    default:
      for (int k = 0; k < 1 + int(random() % 3); ++k) {
        // Text files change length with each replacement; GLB JSON does not.
        const size_t start = glb ? 20 : 0;
        const size_t end = glb ? json_end : bytes.size();
        if (end <= start) break;
        replace_number(bytes, start + random() % (end - start), end,
                       glb ? std::to_string(random() % 64) : numbers[random() % 13], glb);
      }
  }
  return bytes;
}

}  // namespace

TEST_CASE("mutated files give crestline::Error or a soup, never anything else", "[io][robust][meshes]") {
  SKIP_WITHOUT_MESHES();
  const char* const files[] = {
      "robust/obj/polygon-concave-o2g.obj",
      "robust/obj/negative-indices-box.obj",
      "robust/obj/syntax-utf16be.obj",
      "glb/Box.glb",
      "glb/Box-draco.glb",
      "glb/BoxMeshopt.glb",
      "glb/Duck-quantized.glb",
      "gltf/SimpleSparseAccessor/SimpleSparseAccessor.gltf",
      "gltf/Box-draco/Box.gltf",
      "robust/gltf/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf",
  };
  for (const char* file : files) {
    const std::filesystem::path path = crestline::testing::mesh_path(file);
    const std::vector<uint8_t> original = load(path);
    std::vector<NamedBuffer> companions;
    for (const auto& entry : std::filesystem::directory_iterator(path.parent_path())) {
      if (entry.path().extension() == ".bin")
        companions.push_back({entry.path().filename().string(), load(entry.path())});
    }
    const bool glb = path.extension() == ".glb";
    std::mt19937 random(12345);
    size_t errors = 0;
    for (int round = 0; round < 300; ++round) {
      const std::vector<uint8_t> bytes = mutate(original, glb, random);
      const auto start = std::chrono::steady_clock::now();
      try {
        read_mesh_bytes(path.filename().string(), bytes, companions);
      } catch (const Error&) {
        ++errors;
      } catch (const std::exception& e) {
        FAIL(file << " round " << round << " threw a non-Crestline exception: " << e.what());
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      INFO(file << " round " << round);
      CHECK(seconds < 2.0);
    }
    INFO(file);
    CHECK(errors > 0);  // the mutations do break things
  }
}

TEST_CASE("mutated PLY, STL and OFF files give crestline::Error or a soup", "[io][robust]") {
  using crestline::testing::bytes_of;
  using crestline::testing::put;
  std::vector<uint8_t> ply = bytes_of(
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n");
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put(ply, c, true);
  put(ply, uint8_t(4), true);
  for (int i : {0, 1, 2, 3}) put(ply, int32_t(i), true);
  std::vector<uint8_t> stl = bytes_of("solid binary");
  stl.resize(80, ' ');
  put(stl, uint32_t(1));
  for (float c : {0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(stl, c);
  put(stl, uint16_t(0));
  const std::pair<const char*, std::vector<uint8_t>> files[] = {
      {"q.ply", ply},
      {"t.stl", stl},
      {"a.stl", bytes_of("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                         "endloop\nendfacet\nendsolid a\n")},
      {"p.off", bytes_of("OFF\n# square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")},
      {"a.ply", bytes_of("ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                         "property double z\nelement face 1\nproperty list uchar uint vertex_index\nend_header\n"
                         "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")},
  };
  std::mt19937 random(777);
  for (const auto& [name, original] : files) {
    for (int round = 0; round < 500; ++round) {
      const std::vector<uint8_t> bytes = mutate(original, false, random);
      try {
        read_mesh_bytes(name, bytes);
      } catch (const Error&) {
      } catch (const std::exception& e) {
        FAIL(name << " round " << round << " threw a non-Crestline exception: " << e.what());
      }
    }
  }
}
