// STL, binary and ASCII. A file is binary when its size is exactly
// 84 + 50 n for the n stored at byte 80 and it is not plain text: many binary
// exporters start the 80-byte header with "solid" too, so the word alone
// proves nothing. Every facet gets its own three vertices (a soup).
#include <cstring>

#include "readers.h"

namespace crestline::io::detail {
namespace {

TriangleSoup read_binary(const Input& in, const ReadOptions& options) {
  uint32_t count = 0;
  std::memcpy(&count, in.data + 80, 4);
  check_claim(in, options, count, 50, in.size - 84, "triangles");
  TriangleSoup soup;
  soup.positions.reserve(size_t(count) * 9);
  soup.indices.reserve(size_t(count) * 3);
  const uint8_t* facet = in.data + 84;
  for (uint32_t t = 0; t < count; ++t, facet += 50) {
    float corners[9];  // after the 12-byte normal; little-endian like every target
    std::memcpy(corners, facet + 12, sizeof corners);
    for (float c : corners) soup.positions.push_back(double(c));
    for (uint32_t k = 0; k < 3; ++k) soup.indices.push_back(3 * t + k);
  }
  return soup;
}

TriangleSoup read_ascii(const Input& in, const ReadOptions& options) {
  TriangleSoup soup;
  TextScanner text(in.data, in.size, false);
  std::vector<uint32_t> loop;
  auto close_loop = [&] {
    if (loop.size() >= 3) add_polygon(soup, loop.data(), loop.size());
    loop.clear();
    if (soup.triangle_count() > options.max_triangles) {
      fail(ErrorKind::TooLarge, in, "the file has more than " + std::to_string(options.max_triangles) + " triangles.");
    }
  };
  std::string_view word;
  while (text.next_line()) {
    if (!text.word(word)) continue;
    if (word == "vertex") {
      double xyz[3];
      for (double& c : xyz) {
        if (!text.number(c)) {
          fail(ErrorKind::InvalidInput, in,
               "line " + std::to_string(text.line_number()) + " has a vertex without three numbers.");
        }
      }
      loop.push_back(uint32_t(soup.vertex_count()));
      soup.positions.insert(soup.positions.end(), xyz, xyz + 3);
    } else if (word == "endloop" || word == "endfacet" || word == "facet") {
      close_loop();
    }
  }
  close_loop();
  return soup;
}

bool starts_with_solid(const Input& in) {
  size_t i = 0;
  while (i < in.size && (in.data[i] == ' ' || in.data[i] == '\t' || in.data[i] == '\r' || in.data[i] == '\n')) ++i;
  return in.size - i >= 5 && std::memcmp(in.data + i, "solid", 5) == 0;
}

}  // namespace

TriangleSoup read_stl(const Input& in, const ReadOptions& options) {
  TriangleSoup soup;
  if (is_binary_stl_size(in.size, in.data)) {
    soup = read_binary(in, options);
  } else if (starts_with_solid(in) && looks_like_text(in.data, in.size)) {
    soup = read_ascii(in, options);
  } else if (in.size >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, in.data + 80, 4);
    fail(ErrorKind::InvalidInput, in,
         "the binary STL header claims " + std::to_string(count) + " triangles (" +
             std::to_string(84 + 50 * uint64_t(count)) + " bytes) but the file has " + std::to_string(in.size) +
             " bytes.");
  } else {
    fail(ErrorKind::InvalidInput, in, "the file is too short to be an STL file.");
  }
  finish_soup(soup, in);
  return soup;
}

}  // namespace crestline::io::detail
