// The fuzzers' structure-aware text mutator (fuzz/text_mutator.h) reaches
// the inputs of issue 18 that byte mutations missed: from the repository's
// own OBJ and glTF seeds, a few hundred mutations give a JSON nested past
// the depth limit (a stack overflow before), an OBJ polygon of thousands of
// corners (quadratic before) and OBJ indices beyond 32 bits (wrapped
// before). The readers now refuse each, or read it with the ear clipper's
// work counted to be O(n log n).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "text_mutator.h"
#include "triangulate_polygon.h"

using namespace crestline;

namespace {

std::string seed(const char* relative) {
  std::ifstream file(std::filesystem::path(CRESTLINE_FUZZ_SEEDS) / relative, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// The mutation of `text` with `seed`, with room for up to 1 MB.
std::string mutated(const std::string& text, uint32_t seed) {
  std::vector<uint8_t> buffer(size_t(1) << 20);
  std::copy(text.begin(), text.end(), buffer.begin());
  buffer.resize(fuzz::mutate_text(buffer.data(), text.size(), buffer.size(), seed));
  return {buffer.begin(), buffer.end()};
}

// The message reading `text` as `name` gives ("" when read), and the ear
// clipper's work for it.
std::string outcome(const std::string& name, const std::string& text, io::detail::PolygonWork& work) {
  io::detail::polygon_work() = {};
  std::string message;
  try {
    io::read_mesh_bytes(name, std::vector<uint8_t>(text.begin(), text.end()));
  } catch (const Error& e) {
    message = e.what();
  }
  work = io::detail::polygon_work();
  return message;
}

// The corners of the longest face of `obj`, and of all faces in `total`.
size_t longest_face(const std::string& obj, size_t& total) {
  size_t longest = 0;
  total = 0;
  for (size_t at = obj.find("f "); at != std::string::npos; at = obj.find("\nf ", at + 1)) {
    const size_t end = std::min(obj.find('\n', at + 1), obj.size());
    size_t corners = 0;
    for (size_t i = at + 1; i < end; ++i) corners += obj[i] != ' ' && obj[i - 1] == ' ';
    longest = std::max(longest, corners);
    total += corners;
  }
  return longest;
}

}  // namespace

TEST_CASE("the text mutator reaches deep JSON, huge polygons and wide integers", "[hardening][fuzz]") {
  const std::string gltf = seed("gltf/strip-fan-sparse.gltf"), obj = seed("obj/quad-and-negative.obj");
  REQUIRE(!gltf.empty());
  REQUIRE(!obj.empty());
  bool deep = false, polygon = false, wide = false;
  for (uint32_t s = 0; s < 300 && !(deep && polygon && wide); ++s) {
    io::detail::PolygonWork work;
    const std::string json = mutated(gltf, s);
    const std::string json_message = outcome("m.gltf", json, work);
    deep = deep || json_message.find("nests deeper than 64 levels") != std::string::npos;
    const std::string text = mutated(obj, s);
    const std::string obj_message = outcome("m.obj", text, work);
    size_t corners = 0;
    if (longest_face(text, corners) >= 2000 && obj_message.empty()) {
      // Read, and clipped in O(n log n): the quadratic clipper made n ear
      // tests per corner.
      polygon = true;
      INFO(corners << " corners: " << work.ear_tests << " ear tests, " << work.nodes << " nodes");
      CHECK(work.ear_tests <= 4 * corners);
      CHECK(double(work.nodes) <= 4 * double(corners) * std::log2(double(corners)));
    }
    wide = wide || obj_message.find("which is out of range") != std::string::npos;
  }
  CHECK(deep);
  CHECK(polygon);
  CHECK(wide);
}
